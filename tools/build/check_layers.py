#!/usr/bin/env python3
"""tools/build/check_layers.py - the source-structure rules of `make check`
(called by tools/build/check_firmware.sh; rules 6-10 there):

  6. include layering: every direct #include of a fieldloc header from a
     header in include/fieldloc/ or a file in src/<folder>/ goes from a layer
     to a layer the LAYERS table below allows (or is a listed EXCEPTION);
     a header or src/ folder that the table does not know is an error;
  7. private headers: src/<folder>/<stage>_int.h is included only by files of
     the same folder whose name starts with <stage>; never from another stage,
     include/, tools/ or host_tests/ (by any path);
  8. no include circles among src/ and include/ files, among tools/ files,
     nor among tools/ folders (tools/X/* including "Y/..." is an edge X -> Y);
  9. no function in src/ longer than MAX_FUNCTION_LINES lines (signature to
     closing brace), except those in tools/build/long_functions.txt; a listed
     function that is no longer long fails too, so the list only shrinks;
 10. tools/ reach a localizer only through localizer.h: no tools file
     includes a localizer's own header (fuzzy.h) or calls its fl_<name>_*
     functions, except the files in LOC_OWN_TOOLS (with the reason).

Paths come from the environment (overridable so host_tests/test_rules.c can
feed planted trees): SRC_DIR, INC_DIR, TOOLS_DIR, TESTS_DIR, LONG_FUNCTIONS.
Output lines start with "check: " and failures with "check: FAIL: ".
"""
import os
import re
import sys

SCRIPT = "tools/build/check_layers.py"

# ---- the layer table: the one place to classify a new header or src/ folder --
# Public headers (include/fieldloc/*.h) by layer.
HEADER_LAYER = {
    "common.h": "base", "config.h": "base", "fixed.h": "base", "image.h": "base",
    "text.h": "base",            # the text formats' words, numbers, writer
    "camera.h": "model", "calib.h": "model", "field.h": "model",
    "homography.h": "model",     # image <-> field plane geometry, like camera.h
    "coach.h": "vision",         # the coach's image path: pixels to reports
    "obs.h": "obs",              # the seam between vision and localization
    "color.h": "vision", "scan.h": "vision", "lines.h": "vision",
    "crossings.h": "vision", "circle.h": "vision", "goal.h": "vision",
    "beacon.h": "vision", "vision.h": "vision", "color_auto.h": "vision",
    "skeleton.h": "vision",      # thinning and crossings of a binary mask
    "hlvision.h": "vision",      # seed 002's path: boxes, poles, mask, skeleton
    "corners.h": "vision",       # seed 004's corners: C, T-field, T-net, nets
    "fuzzy.h": "loc", "localizer.h": "loc", "mcl.h": "loc",
    "ukf.h": "loc", "upf.h": "loc", "relmap.h": "loc",
    "report.h": "loc",           # observer reports: assignment, re-seed policy
                                 # over localizer.h, the message
    "odocal.h": "loc",           # odometry scale from an observer's track
    # future localizers: "grid.h": "loc",
    "fieldloc.h": "umbrella",    # users only: never included from src/, include/
}
# src/<folder>/ by layer (the folder's .c and _int.h files take its layer).
FOLDER_LAYER = {"base": "base", "model": "model", "vision": "vision", "loc": "loc"}
# Which headers a file of a layer may include directly.  A layer name allows
# every header of that layer; "-x.h" then forbids one header of it, "+x.h"
# allows one header of another layer.  Order: layers first, then -/+ entries.
ALLOW = {
    "base":   ["base"],
    "model":  ["base", "model"],
    "obs":    ["base", "obs", "+field.h"],                    # not camera.h
    "vision": ["base", "model", "obs", "vision"],
    "loc":    ["base", "-image.h", "obs", "loc", "+field.h"],  # no pixels, no
                                                            # camera, no vision
    "umbrella": ["base", "model", "obs", "vision", "loc"],
}
# Exceptions: (including file's basename, included header) -> why.  Each one
# is a known debt; remove it when the include goes.
EXCEPTIONS = {
    # e.g. ("x.h", "camera.h"): "why",
}
MAX_FUNCTION_LINES = 150
# Rule 10: the tools reach a localizer only through localizer.h.  A loc-layer
# header other than these is one localizer's own API (fuzzy.h: fl_fuzzy_*);
# the tools may neither include it nor call its fl_<name>_ functions, except
# the files listed here, which measure that localizer's internals.
LOC_INTERFACE = {"localizer.h", "obs.h",
                 "report.h",   # no localizer's own API: a policy over localizer.h
                 "odocal.h"}   # no localizer's API: corrects the odometry fed to any
LOC_OWN_TOOLS = {"bench/bench_fuzzy.c": "the fuzzy grid's benchmark section "
                                        "(worst-case cells, sizeof)",
                 "eval/eval_relmap.c": "seed 002's evaluation: the relative map's "
                                       "eq. 4 pose and tie set per frame",
                 "cli/cmd_ukf_check.c": "the UKF step's numerics against the double "
                                        "reference (ukf.h building blocks)",
                 "eval/walk004.c": "seed 004's walk-through: the fuzzy grid fed one "
                                   "observation at a time (fl_fuzzy_update_one), its "
                                   "cells drawn and measured, the true pose's possibility"}
# ---------------------------------------------------------------------------

fails = []


def bad(msg):
    fails.append(msg)
    print("check: FAIL: " + msg)


def say(msg):
    print("check: " + msg)


INC_RE = re.compile(r'^\s*#\s*include\s*["<]([^">]+)[">]', re.M)


def includes(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return INC_RE.findall(f.read())
    except OSError:
        return []


def files_under(root, exts):
    out = []
    if not root or not os.path.isdir(root):
        return out
    for d, subs, names in os.walk(root):
        subs.sort()
        for n in sorted(names):
            if n.endswith(exts):
                out.append(os.path.join(d, n))
    return out


def allowed(layer, header):
    ok = False
    for e in ALLOW[layer]:
        if e.startswith("-"):
            if header == e[1:]:
                ok = False
        elif e.startswith("+"):
            if header == e[1:]:
                ok = True
        elif HEADER_LAYER.get(header) == e:
            ok = True
    return ok


def describe(layer):
    """ALLOW[layer] in words: 'base (not image.h), obs, loc, field.h'."""
    out = []
    for e in ALLOW[layer]:
        if e.startswith("-"):
            if out:
                out[-1] += " (not %s)" % e[1:]
        else:
            out.append(e.lstrip("+"))
    return ", ".join(out)


def find_cycle(graph):
    """Return one cycle as a list of nodes (first == last), or None."""
    color = {}
    stack = []

    def dfs(u):
        color[u] = 1
        stack.append(u)
        for v in sorted(graph.get(u, ())):
            if color.get(v) == 1:
                return stack[stack.index(v):] + [v]
            if color.get(v) is None:
                c = dfs(v)
                if c:
                    return c
        stack.pop()
        color[u] = 2
        return None

    sys.setrecursionlimit(10000)
    for u in sorted(graph):
        if color.get(u) is None:
            c = dfs(u)
            if c:
                return c
    return None


def function_lengths(path):
    """Crude: a function body opens with a line starting '{' and closes at the
    next line starting '}'; its signature is the non-blank, non-comment lines
    just above.  Yields (name, lines from signature to closing brace, line)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("{"):
            j = i - 1
            sig = ""
            while (j >= 0 and lines[j].strip() and not lines[j].startswith("}")
                   and not lines[j].lstrip().startswith(("*", "/*", "//", "#"))
                   and not lines[j].rstrip().endswith(";")):
                sig = lines[j] + " " + sig
                j -= 1
            names = re.findall(r"(\w+)\s*\(", sig)
            k = i + 1
            while k < len(lines) and not lines[k].startswith("}"):
                k += 1
            if names:
                yield names[0], k - j, j + 2
            i = k
        i += 1


def main():
    src = os.environ.get("SRC_DIR") or "src"
    inc = os.environ.get("INC_DIR") or "include"
    tools = os.environ.get("TOOLS_DIR") or "tools"
    tests = os.environ.get("TESTS_DIR") or "host_tests"
    longlist = os.environ.get("LONG_FUNCTIONS") or "tools/build/long_functions.txt"
    incdir = os.path.join(inc, "fieldloc")

    headers = files_under(incdir, (".h",))
    srcfiles = files_under(src, (".c", ".h"))
    toolfiles = files_under(tools, (".c", ".h", ".cpp"))
    testfiles = files_under(tests, (".c", ".h", ".cpp"))

    # ---- 6. layering (direct includes) ----
    n6 = 0
    for h in headers:
        if os.path.basename(h) not in HEADER_LAYER:
            bad("assign a layer to %s in %s" % (os.path.basename(h), SCRIPT))
    file_layer = {}
    for h in headers:
        lay = HEADER_LAYER.get(os.path.basename(h))
        if lay:
            file_layer[h] = lay
    unknown = set()
    for f in srcfiles:
        rel = os.path.relpath(f, src)
        folder = rel.split(os.sep)[0] if os.sep in rel else "."
        if folder not in FOLDER_LAYER:
            if folder not in unknown:
                unknown.add(folder)
                bad("assign a layer to src folder %s/ in %s"
                    % (os.path.join(src, folder) if folder != "." else src, SCRIPT))
            continue
        file_layer[f] = FOLDER_LAYER[folder]
    used_exc = set()
    for f, lay in sorted(file_layer.items()):
        me = os.path.basename(f)
        for i in includes(f):
            if not i.startswith("fieldloc/"):
                continue
            h = i[len("fieldloc/"):]
            if h not in HEADER_LAYER:
                continue    # a missing/unknown header is reported above or by cc
            n6 += 1
            if h == "fieldloc.h":
                bad("%s includes the umbrella header fieldloc/fieldloc.h "
                    "(users only)" % f)
                continue
            if allowed(lay, h):
                continue
            if (me, h) in EXCEPTIONS:
                used_exc.add((me, h))
                continue
            bad("layering: %s (%s) includes %s (%s); %s may include %s"
                % (f, lay, i, HEADER_LAYER[h], lay, describe(lay)))
    for k in sorted(set(EXCEPTIONS) - used_exc):
        say("note: exception %s -> %s is no longer needed: remove it from %s"
            % (k[0], k[1], SCRIPT))
    say("%d includes follow the layers (%d listed exceptions: %s)"
        % (n6, len(EXCEPTIONS),
           ", ".join("%s -> %s" % k for k in sorted(EXCEPTIONS)) or "none"))

    # ---- 7. private headers ----
    private = {}    # basename -> (folder path, stage)
    for f in srcfiles:
        b = os.path.basename(f)
        if b.endswith("_int.h"):
            private[b] = (os.path.dirname(f), b[:-len("_int.h")])
    n7 = 0
    for f in srcfiles + headers + toolfiles + testfiles:
        for i in includes(f):
            b = os.path.basename(i)
            if b not in private:
                continue
            n7 += 1
            folder, stage = private[b]
            ok = (f in srcfiles
                  and os.path.normpath(os.path.dirname(f)) == os.path.normpath(folder)
                  and os.path.basename(f).startswith(stage))
            if not ok:
                bad("private header %s included by %s (only %s/%s*.c may)"
                    % (b, f, folder, stage))
    say("%d private-header includes (%s) stay within their stage"
        % (n7, " ".join(sorted(private)) or "none"))

    # ---- 8. include circles ----
    def resolve(f, i, roots):
        cand = [os.path.join(os.path.dirname(f), i)] + [os.path.join(r, i) for r in roots]
        for c in cand:
            if os.path.isfile(c):
                return os.path.normpath(c)
        return None

    fw = set(os.path.normpath(f) for f in srcfiles + headers)
    g = {}
    for f in srcfiles + headers:
        u = os.path.normpath(f)
        g[u] = set()
        for i in includes(f):
            v = resolve(f, i, [inc])
            if v in fw and v != u:
                g[u].add(v)
            elif v == u:
                g[u].add(v)
    c = find_cycle(g)
    if c:
        bad("include circle in src/include: " + " -> ".join(c))
    tf = set(os.path.normpath(f) for f in toolfiles)
    g = {}
    folders = {}
    for f in toolfiles:
        u = os.path.normpath(f)
        g[u] = set()
        rel = os.path.relpath(f, tools)
        x = rel.split(os.sep)[0] if os.sep in rel else "."
        folders.setdefault(x, set())
        for i in includes(f):
            v = resolve(f, i, [tools])
            if v in tf:
                g[u].add(v)
            y = i.split("/")[0] if "/" in i else None
            if y and y != x and os.path.isdir(os.path.join(tools, y)):
                folders[x].add(y)
    c = find_cycle(g)
    if c:
        bad("include circle in tools: " + " -> ".join(c))
    c = find_cycle(folders)
    if c:
        bad("include circle among tools folders: " + " -> ".join(c))
    say("no include circles (src+include files, tools files, tools folders: %s)"
        % "; ".join("%s -> %s" % (x, ",".join(sorted(folders[x])) or "-")
                    for x in sorted(folders)))

    # ---- 10. tools use localizers through the interface ----
    own = sorted(h for h, lay in HEADER_LAYER.items()
                 if lay == "loc" and h not in LOC_INTERFACE)
    n10 = 0
    for f in toolfiles:
        rel = os.path.relpath(f, tools).replace(os.sep, "/")
        if rel in LOC_OWN_TOOLS:
            continue
        with open(f, encoding="utf-8", errors="replace") as fh:
            text = fh.read()
        code = re.sub(r"/\*.*?\*/|//[^\n]*", " ", text, flags=re.S)
        code = re.sub(r'"(?:\\.|[^"\\\n])*"', '""', code)
        for h in own:
            stem = h[:-2]
            if re.search(r'#\s*include\s*[<"]fieldloc/%s[>"]' % re.escape(h), text):
                bad("%s includes fieldloc/%s: tools use a localizer through "
                    "localizer.h only" % (f, h))
            m = re.search(r"\bfl_%s_\w+" % re.escape(stem), code)
            if m:
                bad("%s calls %s: tools use a localizer through localizer.h only "
                    "(or list the file in LOC_OWN_TOOLS in %s, with why)"
                    % (f, m.group(0), SCRIPT))
        n10 += 1
    say("%d tools files reach localizers (%s) through localizer.h only (%d own: %s)"
        % (n10, " ".join(own) or "-", len(LOC_OWN_TOOLS),
           ", ".join(sorted(LOC_OWN_TOOLS)) or "-"))

    # ---- 9. function length ----
    allow = {}
    try:
        with open(longlist, encoding="utf-8") as f:
            for ln, line in enumerate(f, 1):
                line = line.split("#", 1)[0].strip()
                if line:
                    allow[line] = ln
    except OSError:
        if "LONG_FUNCTIONS" in os.environ and os.environ["LONG_FUNCTIONS"]:
            bad("cannot read %s" % longlist)
    seen = set()
    nf = 0
    for f in srcfiles:
        if not f.endswith(".c"):
            continue
        rel = os.path.relpath(f, src).replace(os.sep, "/")
        for name, n, line in function_lengths(f):
            nf += 1
            key = "%s:%s" % (rel, name)
            if n > MAX_FUNCTION_LINES:
                if key in allow:
                    seen.add(key)
                else:
                    bad("function too long: %s:%d %s is %d lines (max %d; split it)"
                        % (f, line, name, n, MAX_FUNCTION_LINES))
    for key in sorted(allow):
        if key not in seen:
            bad("%s is no longer longer than %d lines (or gone): remove it from %s"
                % (key, MAX_FUNCTION_LINES, longlist))
    say("%d functions at most %d lines, %d allowed longer (%s)"
        % (nf, MAX_FUNCTION_LINES, len(seen), longlist))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())

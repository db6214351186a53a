#!/usr/bin/env python3
"""tools/build/stack_report.py - worst-case stack depth of every public entry point.

Reads the .ci files that gcc writes with -fcallgraph-info=su (one per
firmware source: each function's own frame size and its direct calls),
merges them, and for every exported fl_* function prints the deepest path:
its own frame plus the deepest callee, recursively.  Fails (exit 1) on
recursion, on a dynamic (VLA/alloca) frame, on an indirect call that no
--indirect rule covers, on a call to an unknown non-library function, or
when an entry point needs more than --limit bytes (default 4096).

--indirect CALLER_PREFIX=TARGET_PREFIX (repeatable): an indirect call in a
function whose name starts with CALLER_PREFIX may reach any function whose
node title starts with TARGET_PREFIX; it counts as the deepest of them (an
upper bound).  The localizer interface calls its adapters' functions
through the fl_localizer_t table: --indirect fl_loc_=src/loc/loc_.

Usage: stack_report.py [--limit N] [--indirect C=T]... FILE.ci...
"""
import re
import sys

def main(argv):
    limit = 4096
    files = []
    indirect = []
    i = 0
    while i < len(argv):
        if argv[i] == "--limit":
            limit = int(argv[i + 1]); i += 2
        elif argv[i] == "--indirect":
            caller, target = argv[i + 1].split("=", 1)
            indirect.append((caller, target)); i += 2
        else:
            files.append(argv[i]); i += 1
    frame, kind, edges, local = {}, {}, {}, set()
    node_re = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"(.*)\}')
    edge_re = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
    for f in files:
        for line in open(f):
            m = node_re.search(line)
            if m:
                name, label, rest = m.groups()
                s = re.search(r'\\n(\d+) bytes \((\w+)', label)
                if s:
                    frame[name] = int(s.group(1)); kind[name] = s.group(2)
                    if 'shape : ellipse' not in rest:
                        local.add(name)
                continue
            m = edge_re.search(line)
            if m:
                edges.setdefault(m.group(1), []).append(m.group(2))
    libc = {"memcpy", "memset", "memmove", "memcmp"}
    problems = []
    memo = {}

    def depth(fn, stack):
        if fn in memo:
            return memo[fn]
        if fn in stack:
            problems.append("recursion: " + " -> ".join(stack + [fn]))
            return 0, [fn]
        if fn not in frame:
            if fn in libc or fn.startswith("__builtin"):
                return 0, [fn]
            if fn == "__indirect_call":
                caller = stack[-1]
                targets = [n for c, t in indirect if caller.startswith(c)
                           for n in frame if n.startswith(t)]
                if not targets:
                    problems.append("indirect call in " + caller)
                    return 0, [fn]
                best, path = 0, ["(indirect)"]
                for t in sorted(targets):
                    d, p = depth(t, stack)
                    if d > best:
                        best, path = d, ["(indirect)"] + p
                return best, path
            problems.append("unknown callee %s (from %s)" % (fn, stack[-1] if stack else "?"))
            return 0, [fn]
        if kind.get(fn) != "static":
            problems.append("non-static frame in %s (%s)" % (fn, kind.get(fn)))
        best, path = 0, []
        for c in edges.get(fn, []):
            d, p = depth(c, stack + [fn])
            if d > best:
                best, path = d, p
        memo[fn] = (frame[fn] + best, [fn] + path)
        return memo[fn]

    entries = sorted(n for n in frame if n.startswith("fl_"))
    worst = 0
    print("%-34s %6s  deepest path" % ("entry point", "bytes"))
    for e in entries:
        d, p = depth(e, [])
        worst = max(worst, d)
        flag = "  OVER LIMIT" if d > limit else ""
        print("%-34s %6d  %s%s" % (e, d, " > ".join(p), flag))
        if d > limit:
            problems.append("%s needs %d bytes > %d" % (e, d, limit))
    print("worst entry point: %d bytes (limit %d)" % (worst, limit))
    for p in sorted(set(problems)):
        print("stack: FAIL: " + p)
    return 1 if problems else 0

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/env python3
"""Every localizer of the catalogue side by side, for docs/RESULTS.md
(tools/build/results.sh runs it; results are not part of the tests).

    loc_table.py catalogue --cli build/fieldloc
        one line per localizer: NAME stochastic=0|1 particles=0|1
        (stochastic: `simulate --param seed=1` is accepted, i.e. the
        localizer has the parameter "seed" of localizer.h; particles: it
        has "n_particles")

    loc_table.py run --cli build/fieldloc --work DIR [--cli-big CLI]
                     [--jobs N] [--dry-run] [options below]
        runs the simulated walks (fieldloc simulate --quiet) into DIR/runs/
        and the UvA standing spots (fieldloc localize --uva-spots) into
        DIR/uva/, then prints the markdown of the comparison on stdout.
        Frames mode reads the observation caches DIR/FIELD.SEED.obs, which
        must exist (results.sh makes them with the fuzzy walks), so every
        localizer and every random-generator seed sees the same vision
        observations.  A run whose output already exists with its summary
        lines is not repeated (results.sh's fuzzy walks are reused).
        Any failing command: its output tail on stderr, exit status 1.

    loc_table.py walks --cli build/fieldloc --work DIR [--jobs N] [--dry-run]
                       [--localizers ...] [--fields ...] [--feature-seeds ...]
                       [--frame-seeds ...] [--rng-seeds ...]
        the walks of `run` only (no particle sweep, no UvA spots) and the
        markdown of their table (median / worst per localizer, field and
        mode; the targets only on the fields that have them): a field of
        its own, e.g. seed 002's hl3x2, beside the others.  Frames mode
        reads DIR/FIELD.SEED.obs as `run` does.

Options (comma-separated lists):
    --localizers fuzzy,mcl   default: the catalogue
    --fields spl2013,uva2013,aibo2004,spl2020
    --feature-seeds 1,...,6 / --frame-seeds 1,...,6   walk seeds
    --rng-seeds 1,...,5      random-generator seeds of a stochastic localizer
    --counts 32,64,128,256,512   particle counts (frames mode), run with
                             --cli-big when --cli does not accept the count
    --count-rng-seeds 1      random-generator seeds of the particle sweep

Statistics (per localizer, field and mode, over walk seeds x generator
seeds): the median and the worst (largest) of each metric; "inf" never
(converged / recovered), a run's "nan" RMSE (no record qualifies) counts as
inf.  Kidnap recovery: every kidnap of every run (the "# kidnap K ..."
lines of simulate when it prints them, else its kidnap_recover_s).
"""
import argparse
import concurrent.futures
import math
import os
import re
import statistics
import subprocess
import sys

INF = float('inf')

# The targets of the localization issue: vision in the loop (frames mode).
# (field -> pos mm, heading deg) at 256 particles, and pos mm at 64.
TARGET_256 = {'spl2013': (45, 1.5), 'uva2013': (35, 1.2), 'aibo2004': (65, 3.6)}
TARGET_64_POS = {'spl2013': 60, 'uva2013': 50, 'aibo2004': 100}
KIDNAP_256 = (3.0, 10.0)    # median, worst (s)
KIDNAP_64 = 5.0             # median (s)
CONVERGE_MEDIAN = 1.0       # s, from the own-half prior
SUMMARY = ('pos_rmse_mm', 'heading_rmse_deg', 'converge_s', 'kidnap_recover_s', 'flips')
KIDNAP_RE = re.compile(r'^# kidnap (\d+) at ([0-9.]+)\s*s?\b.*?'
                       r'(?:recovered after ([0-9.]+|inf)|(never))')


def ints(s):
    return [int(x) for x in s.split(',') if x.strip() != ''] if s else []


def names(s):
    return [x for x in s.split(',') if x.strip() != ''] if s else []


def call(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    return p.returncode, p.stdout


def catalogue(cli):
    """[(name, stochastic, particles)] from the CLI: the known names are in
    simulate's message for an unknown localizer, the parameters are probed
    with a walk of 0 steps."""
    rc, out = call([cli, 'simulate', '--field', 'spl2013', '--seed', '1', '--steps', '0',
                    '--localizer', '-no-such-localizer-'])
    m = re.search(r'\(known:([^)]*)\)', out)
    if rc == 0 or not m:
        sys.exit('loc_table: cannot read the catalogue from `%s simulate` (%s)' % (cli, out.strip()))
    res = []
    for name in m.group(1).split():
        probe = [cli, 'simulate', '--field', 'spl2013', '--seed', '1', '--steps', '0',
                 '--quiet', '--localizer', name]
        stochastic = call(probe + ['--param', 'seed=1'])[0] == 0
        particles = call(probe + ['--param', 'n_particles=1'])[0] == 0
        res.append((name, stochastic, particles))
    return res


def accepts(cli, loc, count):
    return call([cli, 'simulate', '--field', 'spl2013', '--seed', '1', '--steps', '0', '--quiet',
                 '--localizer', loc, '--param', 'n_particles=%d' % count])[0] == 0


def run_name(loc, field, mode, seed, rseed=None, count=None):
    n = '%s.%s.%s.s%d' % (loc, field, mode, seed)
    if rseed is not None:
        n += '.r%d' % rseed
    if count is not None:
        n += '.n%d' % count
    return n + '.out'


def walk_cmd(cli, work, loc, field, mode, seed, rseed=None, count=None):
    cmd = [cli, 'simulate', '--field', field, '--localizer', loc, '--seed', str(seed),
           '--' + mode, '--quiet']
    if mode == 'frames':
        cmd += ['--obs-cache', os.path.join(work, '%s.%d.obs' % (field, seed))]
    if rseed is not None:
        cmd += ['--param', 'seed=%d' % rseed]
    if count is not None:
        cmd += ['--param', 'n_particles=%d' % count]
    return cmd


def done(path):
    try:
        with open(path) as f:
            return any(line.startswith('flips ') for line in f)
    except OSError:
        return False


def parse(path):
    """The summary lines of one simulate output, and the kidnap recoveries."""
    d, kid = {}, []
    with open(path) as f:
        for line in f:
            w = line.split()
            if len(w) == 2 and w[0] in SUMMARY:
                d[w[0]] = float(w[1])
            m = KIDNAP_RE.match(line)
            if m:
                kid.append(INF if m.group(4) else float(m.group(3)))
    missing = [k for k in SUMMARY if k not in d]
    if missing:
        sys.exit('loc_table: %s: no %s line' % (path, ', '.join(missing)))
    if not kid and not math.isnan(d['kidnap_recover_s']):
        kid = [d['kidnap_recover_s']]
    d['kidnaps'] = kid
    return d


def execute(jobs, n_jobs, dry):
    """jobs: [(cmd, out_path)]; runs those not done yet, n_jobs at a time."""
    todo = [(c, o) for c, o in jobs if not done(o)]
    if dry:
        for c, o in todo:
            print('%s > %s' % (' '.join(c), o), file=sys.stderr)
        return
    failed = []

    def one(job):
        cmd, out = job
        rc, text = call(cmd)
        with open(out, 'w') as f:
            f.write(text)
        return job, rc, text

    with concurrent.futures.ThreadPoolExecutor(max_workers=n_jobs) as ex:
        for (cmd, out), rc, text in ex.map(one, todo):
            if rc != 0 or (out.endswith('.out') and '/runs/' in out and not done(out)):
                failed.append((cmd, out, rc, text))
    for cmd, out, rc, text in failed:
        print('loc_table: `%s` exited with status %d (output in %s):' % (' '.join(cmd), rc, out),
              file=sys.stderr)
        print('\n'.join(text.splitlines()[-15:]), file=sys.stderr)
    if failed:
        sys.exit('loc_table: %d of %d runs failed' % (len(failed), len(todo)))


def num(v, fmt='%.1f'):
    if v is None:
        return '-'
    if math.isinf(v):
        return 'inf'
    return fmt % v


def med(vals):
    return statistics.median(vals) if vals else None


def worst(vals):
    return max(vals) if vals else None


def verdict(ok):
    return 'met' if ok else '**MISSED**'


def nan_inf(v):
    return INF if math.isnan(v) else v


def stats(outs):
    """Median and worst of every metric over the parsed outputs."""
    pos = [nan_inf(o['pos_rmse_mm']) for o in outs]
    head = [nan_inf(o['heading_rmse_deg']) for o in outs]
    conv = [o['converge_s'] for o in outs]
    kid = [k for o in outs for k in o['kidnaps']]
    flips = [int(o['flips']) for o in outs]
    return {'runs': len(outs), 'pos': (med(pos), worst(pos)), 'head': (med(head), worst(head)),
            'conv': (med(conv), worst(conv)), 'kid': (med(kid), worst(kid)),
            'kidnaps': len(kid), 'flips': sum(flips), 'flip_runs': sum(1 for f in flips if f)}


def cell(pair, fmt, target=None, check_worst=None):
    """'median / worst' and, with a target, '(<= T: met)' on the median
    (and the worst against check_worst when given)."""
    s = '%s / %s' % (num(pair[0], fmt), num(pair[1], fmt))
    if target is None:
        return s
    ok = pair[0] is not None and pair[0] <= target
    if check_worst is None:
        return '%s (<= %g: %s)' % (s, target, verdict(ok))
    okw = pair[1] is not None and pair[1] <= check_worst
    return '%s (<= %g / %g: %s)' % (s, target, check_worst, verdict(ok and okw))


def main_table(a, cat, work, rseeds):
    """Table 1: every localizer, field and mode."""
    print('| localizer | field | mode | runs | pos RMSE mm | heading RMSE deg | converge s '
          '| kidnap recover s (kidnaps) | flips (runs with flips) |')
    print('|---|---|---|---|---|---|---|---|---|')
    missed = []
    for loc, stochastic, _ in cat:
        for mode in ('features', 'frames'):
            seeds = a.feature_seeds if mode == 'features' else a.frame_seeds
            for field in a.fields:
                outs = [parse(os.path.join(work, 'runs', run_name(loc, field, mode, s, r)))
                        for s in seeds for r in (rseeds if stochastic else [None])]
                st = stats(outs)
                # a field without the targets (spl2020) is measured only
                t = mode == 'frames' and field in TARGET_256
                tp, th = TARGET_256.get(field, (None, None))
                row = [loc, field, mode, str(st['runs']),
                       cell(st['pos'], '%.1f', tp if t else None),
                       cell(st['head'], '%.2f', th if t else None),
                       cell(st['conv'], '%.2f', CONVERGE_MEDIAN if t else None),
                       cell(st['kid'], '%.2f', KIDNAP_256[0] if t else None,
                            KIDNAP_256[1] if t else None) + ' (%d)' % st['kidnaps'],
                       '%d (%d)' % (st['flips'], st['flip_runs'])]
                if t:
                    row[-1] += ' (0: %s)' % verdict(st['flips'] == 0)
                    for what, ok in (('pos', st['pos'][0] is not None and st['pos'][0] <= tp),
                                     ('heading', st['head'][0] is not None and st['head'][0] <= th),
                                     ('converge', st['conv'][0] is not None
                                      and st['conv'][0] <= CONVERGE_MEDIAN),
                                     ('kidnap', st['kid'][0] is not None
                                      and st['kid'][0] <= KIDNAP_256[0]
                                      and st['kid'][1] <= KIDNAP_256[1]),
                                     ('flips', st['flips'] == 0)):
                        if not ok:
                            missed.append('%s %s %s' % (loc, field, what))
                print('| ' + ' | '.join(row) + ' |')
    return missed


def count_table(a, loc, work, cli_of):
    """Table 2: one particle localizer against its particle count."""
    print('| particles | field | runs | pos RMSE mm median | heading RMSE deg median | converge s median '
          '| kidnap recover s median / worst | flips (runs with flips) | targets |')
    print('|---|---|---|---|---|---|---|---|---|')
    missed = []
    for n in a.counts:
        if (loc, n) not in cli_of:
            continue
        for field in a.fields:
            outs = [parse(os.path.join(work, 'runs', run_name(loc, field, 'frames', s, r, n)))
                    for s in a.frame_seeds for r in a.count_rng_seeds]
            st = stats(outs)
            tp, th = TARGET_256.get(field, (None, None))
            checks = []
            if field not in TARGET_256:
                pass   # measured only
            elif n == 256:
                checks = [('pos <= %g' % tp, st['pos'][0] <= tp),
                          ('heading <= %g' % th, st['head'][0] <= th),
                          ('converge <= %g' % CONVERGE_MEDIAN, st['conv'][0] <= CONVERGE_MEDIAN),
                          ('kidnap <= %g / %g' % KIDNAP_256,
                           st['kid'][0] is not None and st['kid'][0] <= KIDNAP_256[0]
                           and st['kid'][1] <= KIDNAP_256[1]),
                          ('flips 0', st['flips'] == 0)]
            elif n == 64:
                checks = [('pos <= %g' % TARGET_64_POS[field], st['pos'][0] <= TARGET_64_POS[field]),
                          ('kidnap <= %g' % KIDNAP_64,
                           st['kid'][0] is not None and st['kid'][0] <= KIDNAP_64),
                          ('flips 0', st['flips'] == 0)]
            for what, ok in checks:
                if not ok:
                    missed.append('%s n_particles=%d %s %s' % (loc, n, field, what))
            tgt = '; '.join('%s: %s' % (w, verdict(ok)) for w, ok in checks) or '-'
            print('| %d%s | %s | %d | %s | %s | %s | %s | %d (%d) | %s |'
                  % (n, '' if cli_of[(loc, n)] == a.cli else ' (*)', field, st['runs'],
                     num(st['pos'][0]), num(st['head'][0], '%.2f'), num(st['conv'][0], '%.2f'),
                     cell(st['kid'], '%.2f'), st['flips'], st['flip_runs'], tgt))
    return missed


UVA_SPOT = re.compile(r'^spot_result (-?\d+) (-?\d+) frames (\d+) pos_err_mm (\S+) '
                      r'heading_err_deg (\S+)')
UVA_ALL = re.compile(r'^uva_spots (\d+) pos_rmse_mm (\S+) heading_rmse_deg (\S+)')


def uva_table(runs):
    """Table 3: runs = [(label, path)] of localize --uva-spots outputs."""
    parsed = []
    for label, path in runs:
        spots, total = [], None
        with open(path) as f:
            for line in f:
                m = UVA_SPOT.match(line)
                if m:
                    spots.append(('%s,%s' % (m.group(1), m.group(2)), m.group(4), m.group(5)))
                m = UVA_ALL.match(line)
                if m:
                    total = (m.group(2), m.group(3))
        parsed.append((label, spots, total))
    if not parsed or parsed[0][2] is None:
        with open(runs[0][1]) as f:
            print('```\n' + f.read().strip() + '\n```')
        return
    cols = [s[0] for s in parsed[0][1]]
    print('| localizer | pos RMSE mm | heading RMSE deg | '
          + ' | '.join('spot %s cm' % c for c in cols) + ' |')
    print('|---|---|---|' + '---|' * len(cols))
    groups = {}
    for label, spots, total in parsed:
        by = {s[0]: '%s / %s' % (s[1], s[2]) for s in spots}
        print('| %s | %s | %s | %s |' % (label, total[0] if total else '-', total[1] if total else '-',
                                         ' | '.join(by.get(c, '-') for c in cols)))
        if ' seed=' in label and total:
            groups.setdefault(label.split()[0], []).append((total, {s[0]: s for s in spots}))
    for loc, runs in groups.items():
        for what, f in (('median', med), ('worst', worst)):
            def v(vals, fmt):
                return num(f([float(x) for x in vals]), fmt)
            print('| %s %s of %d seeds | %s | %s | %s |'
                  % (loc, what, len(runs), v([t[0] for t, _ in runs], '%.0f'),
                     v([t[1] for t, _ in runs], '%.1f'),
                     ' | '.join('%s / %s' % (v([sp[c][1] for _, sp in runs if c in sp], '%.0f'),
                                             v([sp[c][2] for _, sp in runs if c in sp], '%.1f'))
                                for c in cols)))


def prepare(a):
    """The catalogue (or --localizers, in that order) after checking that
    the frames walks' observation caches exist; the work folders made."""
    work = a.work
    os.makedirs(os.path.join(work, 'runs'), exist_ok=True)
    os.makedirs(os.path.join(work, 'uva'), exist_ok=True)
    cat = catalogue(a.cli)
    if a.localizers:
        known = {c[0]: c for c in cat}
        for name in a.localizers:
            if name not in known:
                sys.exit('loc_table: unknown localizer %s (known: %s)' % (name, ' '.join(known)))
        cat = [known[name] for name in a.localizers]
    for field in a.fields:
        for s in a.frame_seeds:
            p = os.path.join(work, '%s.%d.obs' % (field, s))
            if not os.path.isfile(p) and not a.dry_run:
                sys.exit('loc_table: %s missing (results.sh renders it with the fuzzy walks)' % p)
    return cat


def walk_jobs(a, cat):
    """Every localizer, mode, field and walk seed (a stochastic localizer
    once per random-generator seed, a deterministic one once)."""
    jobs = []
    for loc, stochastic, _ in cat:
        for mode in ('features', 'frames'):
            for field in a.fields:
                for s in (a.feature_seeds if mode == 'features' else a.frame_seeds):
                    for r in (a.rng_seeds if stochastic else [None]):
                        jobs.append((walk_cmd(a.cli, a.work, loc, field, mode, s, r),
                                     os.path.join(a.work, 'runs', run_name(loc, field, mode, s, r))))
    return jobs


def cmd_walks(a):
    cat = prepare(a)
    jobs = walk_jobs(a, cat)
    print('loc_table: %d walks, %d at a time' % (len(jobs), a.jobs), file=sys.stderr)
    execute(jobs, a.jobs, a.dry_run)
    if a.dry_run:
        return
    missed = main_table(a, cat, a.work, a.rng_seeds)
    if missed:
        print()
        print('Targets missed: %s.' % '; '.join(missed))


def cmd_run(a):
    work = a.work
    cat = prepare(a)
    jobs = walk_jobs(a, cat)
    swept = [c for c in cat if c[2]] if a.counts else []
    cli_of = {}
    for loc, _, _ in swept:
        for n in a.counts:
            if accepts(a.cli, loc, n):
                cli_of[(loc, n)] = a.cli
            elif a.cli_big and ((a.dry_run and not os.path.exists(a.cli_big)) or
                                accepts(a.cli_big, loc, n)):
                # a dry run builds nothing: the second CLI is taken as built
                cli_of[(loc, n)] = a.cli_big
            elif loc == 'mcl':
                sys.exit('loc_table: no CLI accepts --param n_particles=%d for %s (--cli-big %s)'
                         % (n, loc, a.cli_big))
            else:
                continue   # beyond this localizer's largest capacity (upf: 64): not swept
            for field in a.fields:
                for s in a.frame_seeds:
                    for r in a.count_rng_seeds:
                        jobs.append((walk_cmd(cli_of[(loc, n)], work, loc, field, 'frames', s, r, n),
                                     os.path.join(work, 'runs',
                                                  run_name(loc, field, 'frames', s, r, n))))
    uva = []
    for loc, stochastic, _ in cat:
        for r in (a.rng_seeds if stochastic else [None]):
            label = loc if r is None else '%s seed=%d' % (loc, r)
            cmd = [a.cli, 'localize', '--uva-spots', '--localizer', loc]
            if r is not None:
                cmd += ['--param', 'seed=%d' % r]
            out = os.path.join(work, 'uva', '%s%s.out' % (loc, '' if r is None else '.r%d' % r))
            uva.append((label, out, cmd))
    print('loc_table: %d walks, %d uva-spots runs, %d at a time' % (len(jobs), len(uva), a.jobs),
          file=sys.stderr)
    execute(jobs, a.jobs, a.dry_run)
    for label, out, cmd in uva:
        if os.path.exists(out):
            os.remove(out)
    execute([(cmd, out) for label, out, cmd in uva], a.jobs, a.dry_run)
    if a.dry_run:
        return

    rs = ','.join(map(str, a.rng_seeds))
    print('### Every localizer on the same observations')
    print()
    print('Per localizer, field and mode: **median / worst** over the walk seeds (features %s, frames %s)'
          % (','.join(map(str, a.feature_seeds)), ','.join(map(str, a.frame_seeds))))
    print('and, for a stochastic localizer (one with the parameter "seed": %s), over random-generator'
          % (', '.join(c[0] for c in cat if c[1]) or 'none in the catalogue'))
    print('seeds %s each (`--param seed=R`); a deterministic one (%s) runs once per walk seed. Command'
          ' per run:' % (rs, ', '.join(c[0] for c in cat if not c[1]) or 'none in the catalogue'))
    print('`fieldloc simulate --field FIELD --localizer L --seed SEED --MODE --quiet [--obs-cache'
          ' FIELD.SEED.obs] [--param seed=R]`;')
    print('frames mode renders each walk once and every localizer and generator seed reads the same')
    print('vision observations from its cache. Default parameters of each localizer (its frames preset'
          ' in frames mode).')
    print('Kidnap recovery: every kidnap of every run (count in brackets); flips: the total over the runs')
    print('(runs with a flip in brackets). "inf": never (converged / recovered; an RMSE of nan, no record')
    print('after convergence, counts as inf).')
    print()
    print('Targets (the issue\'s, vision in the loop with 256 particles; frames rows, every localizer'
          ' against the same')
    print('numbers): position RMSE <= 45 / 35 / 65 mm and heading <= 1.5 / 1.2 / 3.6 deg (spl2013 /'
          ' uva2013 /')
    print('aibo2004) on the median, convergence from the own-half prior median <= 1 s, kidnap recovery'
          ' median <= 3 s')
    print('and worst <= 10 s, 0 flips. Anchor: a double-precision AMCL (nav2, 500-2000 particles) on'
          ' the same streams:')
    print('43 / 30 / 60 mm, 1.1 / 1.0 / 3.6 deg, 17-35 s to recover from a kidnap. spl2020 (today\'s field,'
          ' the spl2013')
    print('lap with other robots in view) has no targets: its rows are measured only.')
    print()
    missed = main_table(a, cat, work, a.rng_seeds)
    print()
    print('Targets missed: %s.' % ('; '.join(missed) if missed else 'none'))
    print()
    for loc, _, _ in swept:
        print('### %s against the particle count' % loc)
        print()
        print('Frames mode, walk seeds %s, random-generator seeds %s (`--param n_particles=N --param'
              ' seed=R`);' % (','.join(map(str, a.frame_seeds)), ','.join(map(str, a.count_rng_seeds))))
        big = sorted(n for n in a.counts if (loc, n) in cli_of and cli_of[(loc, n)] != a.cli)
        beyond = [n for n in a.counts if (loc, n) not in cli_of]
        if beyond:
            print('Counts %s: beyond %s\'s largest capacity, not run.'
                  % (', '.join(map(str, beyond)), loc))
        if big:
            print('(*): the count exceeds the default capacity; run with `%s`, built with a larger'
                  ' capacity.' % a.cli_big)
        print('Medians over the runs (kidnap: median / worst over every kidnap). Targets: 256 particles as'
              ' above; 64 particles:')
        print('position RMSE <= 60 / 50 / 100 mm, kidnap recovery median <= 5 s, 0 flips.')
        print()
        missed = count_table(a, loc, work, cli_of)
        print()
        print('Targets missed: %s.' % ('; '.join(missed) if missed else 'none'))
        print()
    print('### The UvA 2013 standing spots')
    print()
    print('Command: `fieldloc localize --uva-spots --localizer L [--param seed=R]` (real qvga frames,'
          ' each spot')
    print('from total ignorance, errors modulo the symmetry; see the top of tools/cli/cmd_localize.c).'
          ' Per spot:')
    print('the final position error mm / heading error deg; RMSE over the spots\' final estimates.')
    print()
    uva_table([(label, out) for label, out, cmd in uva])
    print()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('what', choices=('catalogue', 'run', 'walks'))
    ap.add_argument('--cli', required=True)
    ap.add_argument('--cli-big', default='')
    ap.add_argument('--work', default='')
    ap.add_argument('--jobs', type=int, default=os.cpu_count() or 1)
    ap.add_argument('--dry-run', action='store_true')
    ap.add_argument('--localizers', type=names, default=[])
    ap.add_argument('--fields', type=names, default=['spl2013', 'uva2013', 'aibo2004', 'spl2020'])
    ap.add_argument('--feature-seeds', type=ints, default=[1, 2, 3, 4, 5, 6])
    ap.add_argument('--frame-seeds', type=ints, default=[1, 2, 3, 4, 5, 6])
    ap.add_argument('--rng-seeds', type=ints, default=[1, 2, 3, 4, 5])
    ap.add_argument('--counts', type=ints, default=[32, 64, 128, 256, 512])
    ap.add_argument('--count-rng-seeds', type=ints, default=[1])
    a = ap.parse_args()
    if a.what == 'catalogue':
        for name, stochastic, particles in catalogue(a.cli):
            print('%s stochastic=%d particles=%d' % (name, stochastic, particles))
        return
    if not a.work:
        sys.exit('loc_table %s: --work DIR needed' % a.what)
    if a.what == 'walks':
        cmd_walks(a)
    else:
        cmd_run(a)


if __name__ == '__main__':
    main()

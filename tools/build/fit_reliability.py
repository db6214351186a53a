#!/usr/bin/env python3
"""Fit the fuzzy grid's reliability calibration (src/loc/fuzzy_estimate.c,
fz_calibrate) from `fieldloc reliability --dump` files of TRAINING walks.

    build/fieldloc reliability --seeds 11,...,40 --frame-seeds 11,...,16 \
        --obs-cache-dir DIR --dump train.tsv
    python3 tools/build/fit_reliability.py train.tsv

The raw score is computed exactly as fz_calibrate does (integers): the grid's
own reliability (score) x 16 / (16 + predict calls since an observation was
applied).  The map raw -> reliability is fitted on the records whose half is
decided (state TRACKING): raw is cut at QUANTILES (fine where the bad records are),
the share of good records of each interval is made monotone (pool adjacent
violators, weighted by count) and lowered by two binomial standard errors;
feature mode and frames mode are fitted apart and the smaller value of the
two is kept at each knot (the localizer does not know its mode); each knot
is the interval's upper end, so that linear interpolation between knots
never exceeds the interval's share.  The other states are scaled in
fz_calibrate (AMBIGUOUS: 1 / (1 + mirror); LOST: LOST_NUM / 256, printed
here from the LOST records).  Prints the C table.
"""
import csv
import math
import sys

QUANTILES = (0.003, 0.006, 0.01, 0.015, 0.02, 0.03, 0.04, 0.06, 0.08, 0.1, 0.15,
             0.2, 0.3, 1.0)
CAP = 0.97


def raw_of(r):
    return int(r['score']) * 16 // (16 + min(int(r['since']), 65535))


def load(paths):
    rows = []
    for p in paths:
        with open(p) as f:
            for r in csv.DictReader(f, delimiter='\t'):
                rows.append(r)
    return rows


def pav(vals):
    """vals: list of [share, weight]; returns the monotone non-decreasing fit."""
    blocks = []
    for v, w in vals:
        blocks.append([v, w, 1])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            v2, w2, n2 = blocks.pop()
            v1, w1, n1 = blocks.pop()
            blocks.append([(v1 * w1 + v2 * w2) / (w1 + w2), w1 + w2, n1 + n2])
    out = []
    for v, w, n in blocks:
        out += [(v, w)] * n
    return out


def fit(rows, cuts):
    """share of good per interval (lo, hi] of raw, monotone, lowered."""
    n = [0] * len(cuts)
    g = [0] * len(cuts)
    for r in rows:
        x = raw_of(r)
        i = 0
        while cuts[i] < x:
            i += 1
        n[i] += 1
        g[i] += int(r['good'])
    fitted = pav([(g[i] / n[i] if n[i] else 0.0, n[i]) for i in range(len(cuts))])
    out = []
    for (p, w), cnt in zip(fitted, n):
        se = math.sqrt(max(p * (1 - p), 0.01) / max(w, 1))
        out.append(max(0.0, min(CAP, p - 2 * se)))
    return out, n


def main():
    rows = load(sys.argv[1:])
    trk = [r for r in rows if r['state'] == '2']
    xs = sorted(raw_of(r) for r in trk)
    cuts = sorted(set(xs[min(len(xs) - 1, int(len(xs) * q))] for q in QUANTILES))
    cuts[-1] = 65535
    fits = []
    for mode in ('0', '1'):
        sub = [r for r in trk if r['mode'] == mode]
        if sub:
            f, n = fit(sub, cuts)
            fits.append(f)
            print('# mode %s: %d tracking records, per interval %s' % (mode, len(sub), n))
    val = [min(f[i] for f in fits) for i in range(len(cuts))]
    for i in range(1, len(val)):           # min of monotone maps is monotone
        val[i] = max(val[i], val[i - 1])
    lost = [r for r in rows if r['state'] == '0']
    lost_share = sum(int(r['good']) for r in lost) / max(len(lost), 1)
    print('# LOST records %d, good share %.3f' % (len(lost), lost_share))
    for st, name in (('1', 'AMBIGUOUS'), ('0', 'LOST')):
        sub = [r for r in rows if r['state'] == st]
        if sub:
            print('# %s records %d, good share %.3f' % (name, len(sub),
                  sum(int(r['good']) for r in sub) / len(sub)))
    print('static const uint16_t fz_cal_raw[FZ_CAL_KNOTS] = {%s};' %
          ', '.join(str(c) for c in [0] + cuts))
    print('static const uint16_t fz_cal_rel[FZ_CAL_KNOTS] = {%s};' %
          ', '.join(str(int(v * 65535)) for v in [0.0] + val))
    print('#define FZ_CAL_KNOTS %d' % (len(cuts) + 1))


if __name__ == '__main__':
    main()

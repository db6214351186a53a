/*
 * src/loc/fuzzy_trap.c - the heading trapezoids of the fuzzy position grid
 * (seed 004, Fig. 3): evaluation, product intersection and union, each
 * replaced by its OUTER trapezoidal envelope, and the 8-byte cell coding.
 *
 * Algorithm (intersection).  For a = (ha, ba, ta) and b = (hb, bb, tb), with
 * mu = bias + (height - bias) * t, write aa = ha - ba, ab = hb - bb:
 *     P = mu_a mu_b = ba bb + (aa bb) ta + (ba ab) tb + aa ab ta tb,
 * a floor, a's plateau (a's shape), b's plateau (b's shape) and a bump on
 * the intersection.  Two outer envelopes are computed and the one of the
 * smaller area (integral over the circle) is kept:
 *   E1 (narrow): P <= e + (ha hb - e) min(ta, tb), e = max(ba hb, ha bb)
 *      (expand with ta <= tb or the reverse; the slack is (e - ba hb)(1 - m)).
 *      min(ta, tb) is not a trapezoid; its envelope: when the supports meet
 *      in one arc [A, B], the peak of the min is v = min(1, (La + Lb - |d|)
 *      / (Sa + Sb)) (the crossing of a's falling and b's rising side, 1 when
 *      the cores overlap; L = core + slope, S = slope, d = centre
 *      difference); near A the min is below the ramp of the trapezoid whose
 *      support starts at A, (theta - A) / S_A, near B likewise, so
 *          v * trap(core [A + v S_A, B - v S_B], support [A, B]) >= min,
 *      symmetrized about the core's centre (the wider slope on both sides).
 *      Height e + (ha hb - e) v, bias e.
 *   E2 (low floor): the weaker plateau folded into the bias, the dominant
 *      one and the bump under the hull of the dominant's shape and E1's:
 *      bias ba bb + weak, height ba bb + weak + dominant + aa ab v.
 * E1 narrows the heading but its bias is the larger plateau; E2 keeps the
 * bias low (repeated consistent observations) but cannot be narrower than
 * the dominant trapezoid.  Special cases:
 *   - a core covering every heading: mu is flat, the product is exactly the
 *     other trapezoid scaled (bias included).  A trapezoid with bias =
 *     height is flat too and is treated the same way;
 *   - supports overlapping on both sides of the circle: the narrower of the
 *     two shapes (min <= each), height ha hb, bias e;
 *   - disjoint supports: at every heading one of ta, tb is 0, so the
 *     dominant plateau over the weaker one as bias, or the flat maximum of
 *     the two plateaus.  The first argument's (in the grid: the cell's)
 *     shape is kept when its plateau dominates, else the result is flat: a
 *     contradicting observation never replaces a cell's heading.
 * Heights round up and widths round outward everywhere, so the result is
 * >= the exact product at every heading: it never rules out a possibility
 * (host_tests/test_fuzzy.c checks it on 30,000 random pairs against a
 * double evaluation, through the 8-byte cell coding too, and reports how
 * much area it adds).
 * Union: height max(ha, hb), bias max(ba, bb); the lower trapezoid is
 * dropped when its height is at most that bias, else the arc hull of the
 * two cores and of the two supports.
 *
 * Invariant: every function is total; outputs have 0 <= bias <= height <=
 * 65536 and widths in [0, 32768].  Memory: no tables, a few words of
 * stack.  Cost: O(1), at most two 64-bit divisions (isect).
 */
#include "fieldloc/fuzzy.h"

#define HT 32768          /* half turn, binary angle units */
#define ONE 65536u        /* 1.0 in Q16 */

typedef struct {
    int32_t c, w, s;      /* centre (int32 copy), core, slope */
    uint32_t h, b;
} ntrap_t;

static int32_t clamp_w(int32_t v)
{
    return v < 0 ? 0 : v > HT ? HT : v;
}

static void normalize(const fl_fuzzy_trap_t *t, ntrap_t *n)
{
    n->c = t->centre;
    n->w = clamp_w(t->core);
    n->s = clamp_w(t->slope);
    n->h = t->height_q16 > ONE ? ONE : t->height_q16;
    n->b = t->bias_q16 > n->h ? n->h : t->bias_q16;
    if (n->b == n->h)
        n->w = HT;      /* flat: the shape says nothing (exactly mu = h) */
}

/* Scaling and overflow: x, y in [0, 65536] Q16; product < 2^33 in uint64;
 * result ceil(x y / 65536) in [0, 65536]. */
static uint32_t mul_q16_ceil(uint32_t x, uint32_t y)
{
    return (uint32_t)(((uint64_t)x * y + 65535u) >> 16);
}

static int32_t iabs32(int32_t v)
{
    return v < 0 ? -v : v;   /* callers pass |v| <= 65536 */
}

/* Scaling and overflow: delta = |wrapped theta - centre| in [0, 32768];
 * (L - delta) < slope <= 32768, so (L - delta) << 16 < 2^31; t in Q16. */
uint32_t fl_fuzzy_trap_eval(const fl_fuzzy_trap_t *t, fl_angle_t theta)
{
    ntrap_t n;
    int32_t delta, L;
    uint32_t tq;
    if (t == NULL)
        return 0;
    normalize(t, &n);
    if (n.w >= HT)
        return n.h;
    delta = iabs32(fl_angle_sub(theta, t->centre));
    if (delta <= n.w)
        return n.h;
    L = n.w + n.s;
    if (delta >= L)
        return n.b;
    tq = (uint32_t)(((uint32_t)(L - delta) << 16) / (uint32_t)n.s);
    return n.b + (uint32_t)(((uint64_t)(n.h - n.b) * tq) >> 16);
}

/* Integral of mu over the circle, in Q16 x binary-angle units (for
 * choosing the tighter of two valid envelopes). */
static uint64_t area(const fl_fuzzy_trap_t *t)
{
    uint64_t w = (uint64_t)(2 * t->core) + (uint64_t)t->slope;
    if (w > 65536u || t->core >= HT)
        w = 65536u;
    return (uint64_t)t->bias_q16 * 65536u + (uint64_t)(t->height_q16 - t->bias_q16) * w;
}

static void set_out(fl_fuzzy_trap_t *o, int32_t centre, int32_t core,
                    int32_t slope, uint32_t h, uint32_t b)
{
    o->centre = fl_angle_wrap(centre);
    o->core = clamp_w(core);
    o->slope = clamp_w(slope);
    o->height_q16 = h > ONE ? ONE : h;
    o->bias_q16 = b > o->height_q16 ? o->height_q16 : b;
}

/* Scaling and overflow: widths <= 32768 and supports <= 65536 as int32;
 * v in Q16 [0, 65536] from a 64-bit quotient; v * slope < 2^32 in uint64;
 * every envelope bound is rounded outward (core ends floor/ceil away from
 * the centre, v and the heights up). */
void fl_fuzzy_trap_isect(const fl_fuzzy_trap_t *a, const fl_fuzzy_trap_t *b,
                         fl_fuzzy_trap_t *out)
{
    ntrap_t na, nb;
    const ntrap_t *shape, *dom;
    uint32_t top, e, v, pdom, pweak, alt_bias, alt_h, bump;
    int32_t d, ad, La, Lb, sign;
    if (a == NULL || b == NULL || out == NULL)
        return;
    normalize(a, &na);
    normalize(b, &nb);
    top = mul_q16_ceil(na.h, nb.h);
    e = mul_q16_ceil(na.b, nb.h);
    if (mul_q16_ceil(na.h, nb.b) > e)
        e = mul_q16_ceil(na.h, nb.b);
    if (e > top)
        e = top;
    if (na.w >= HT) {
        /* mu_a is flat at ha: the product is exactly b scaled by ha */
        set_out(out, nb.c, nb.w, nb.s, top, mul_q16_ceil(na.h, nb.b));
        return;
    }
    if (nb.w >= HT) {
        set_out(out, na.c, na.w, na.s, top, mul_q16_ceil(na.b, nb.h));
        return;
    }
    d = fl_angle_sub(b->centre, a->centre);
    ad = iabs32(d);
    La = na.w + na.s;
    Lb = nb.w + nb.s;
    if (La >= HT || Lb >= HT || La + Lb > 2 * HT - ad) {
        /* supports meet on both sides of the circle: keep the narrower */
        shape = (La < Lb || (La == Lb && na.w <= nb.w)) ? &na : &nb;
        set_out(out, shape->c, shape->w, shape->s, top, e);
        return;
    }
    {
        /* the alternative envelope: P = bb + pa ta + pb tb + aa ab ta tb
         * with bb = ba bb, pa = (ha - ba) bb (a's plateau, a's shape), pb
         * likewise; the weaker plateau goes into the bias, the dominant one
         * keeps its shape (hulled with the intersection bump below) */
        uint32_t aa = na.h - na.b, ab = nb.h - nb.b;
        uint32_t b2 = mul_q16_ceil(na.b, nb.b);
        uint32_t pa = mul_q16_ceil(aa, nb.b), pb = mul_q16_ceil(na.b, ab);
        dom = pa >= pb ? &na : &nb;
        pdom = pa >= pb ? pa : pb;
        pweak = pa >= pb ? pb : pa;
        alt_bias = b2 + pweak;
        alt_h = alt_bias + pdom;
        bump = mul_q16_ceil(aa, ab);
    }
    if (La + Lb <= ad) {
        /* disjoint supports: at every heading one of ta, tb is 0, so the
         * dominant plateau alone over the weaker one as bias is an
         * envelope, and so is the flat max of the two plateaus.  The first
         * argument's (the cell's) shape is kept when it dominates, else the
         * result is flat: a contradicting second argument (an observation)
         * never replaces a cell's heading. */
        if (dom == &na)
            set_out(out, dom->c, dom->w, dom->s, e, alt_bias);
        else
            set_out(out, na.c, 0, 0, e, e);
        return;
    }
    {
        /* a at 0, b at ad >= 0 on the line; mirrored back by sign */
        int32_t ss = na.s + nb.s, A, B, sA, sB, a1, b1, c, w, L;
        uint32_t hgt;
        sign = d < 0 ? -1 : 1;
        if (ss == 0) {
            v = ONE;   /* supports overlap and L == core: cores overlap */
        } else {
            uint64_t num = (uint64_t)(uint32_t)(La + Lb - ad) << 16;
            uint64_t q = (num + (uint64_t)(uint32_t)ss - 1u) / (uint32_t)ss;
            v = q > ONE ? ONE : (uint32_t)q;
        }
        if (-La > ad - Lb) {
            A = -La;
            sA = na.s;
        } else if (-La < ad - Lb) {
            A = ad - Lb;
            sA = nb.s;
        } else {
            A = -La;
            sA = na.s < nb.s ? na.s : nb.s;
        }
        if (La < ad + Lb) {
            B = La;
            sB = na.s;
        } else if (La > ad + Lb) {
            B = ad + Lb;
            sB = nb.s;
        } else {
            B = La;
            sB = na.s < nb.s ? na.s : nb.s;
        }
        a1 = A + (int32_t)(((uint64_t)v * (uint32_t)sA) >> 16);
        b1 = B - (int32_t)(((uint64_t)v * (uint32_t)sB) >> 16);
        if (a1 > b1) {
            a1 = (a1 + b1) >> 1;   /* steeper ramps on both sides: still >= */
            b1 = a1;
        }
        c = (a1 + b1) >> 1;        /* floor (arithmetic shift) */
        w = c - a1 > b1 - c ? c - a1 : b1 - c;
        L = c - A > B - c ? c - A : B - c;
        hgt = e + (uint32_t)(((uint64_t)(top - e) * v + 65535u) >> 16);
        set_out(out, na.c + sign * c, w, L - w, hgt, e);
        {
            /* alternative: hull(dominant, intersection), height alt_h + bump
             * v, bias alt_bias; keep the envelope of smaller area */
            fl_fuzzy_trap_t d1, d2, alt;
            d1.centre = fl_angle_wrap(dom->c);
            d1.core = dom->w;
            d1.slope = dom->s;
            d1.height_q16 = alt_h + mul_q16_ceil(bump, v);
            d1.bias_q16 = alt_bias;
            d2 = *out;
            d2.height_q16 = d1.height_q16;
            d2.bias_q16 = alt_bias;
            fl_fuzzy_trap_union(&d1, &d2, &alt);
            if (area(&alt) < area(out))
                *out = alt;
        }
    }
}

void fl_fuzzy_trap_union(const fl_fuzzy_trap_t *a, const fl_fuzzy_trap_t *b,
                         fl_fuzzy_trap_t *out)
{
    ntrap_t na, nb;
    const ntrap_t *hi, *lo;
    uint32_t h, bias;
    if (a == NULL || b == NULL || out == NULL)
        return;
    normalize(a, &na);
    normalize(b, &nb);
    hi = na.h >= nb.h ? &na : &nb;
    lo = na.h >= nb.h ? &nb : &na;
    h = hi->h;
    bias = na.b > nb.b ? na.b : nb.b;
    if (lo->h <= bias) {
        set_out(out, hi->c, hi->w, hi->s, h, bias);
        return;
    }
    if (hi->w >= HT || lo->w >= HT) {
        set_out(out, hi->c, HT, 0, h, bias);
        return;
    }
    {
        int32_t d = fl_angle_sub(fl_angle_wrap(lo->c), fl_angle_wrap(hi->c));
        int32_t Lh = hi->w + hi->s, Ll = lo->w + lo->s;
        int32_t c0 = -hi->w < d - lo->w ? -hi->w : d - lo->w;
        int32_t c1 = hi->w > d + lo->w ? hi->w : d + lo->w;
        int32_t s0 = -Lh < d - Ll ? -Lh : d - Ll;
        int32_t s1 = Lh > d + Ll ? Lh : d + Ll;
        int32_t c, w, L;
        if (c1 - c0 >= 2 * HT) {
            set_out(out, hi->c, HT, 0, h, bias);
            return;
        }
        c = (c0 + c1) >> 1;
        w = c - c0 > c1 - c ? c - c0 : c1 - c;
        L = c - s0 > s1 - c ? c - s0 : s1 - c;
        set_out(out, hi->c + c, w, L - w, h, bias);
    }
}

/* Scaling and overflow: Q0.8 h -> Q16 h*257 + h/128 (255 -> 65536, never
 * above h * 65536 / 255 + 1); widths code * 128, code 255 -> 32768. */
void fl_fuzzy_trap_from_cell(const fl_fuzzy_cell_t *c, fl_fuzzy_trap_t *t)
{
    if (c == NULL || t == NULL)
        return;
    t->centre = c->centre;
    t->core = c->core >= FL_FUZZY_WFULL ? HT : (int32_t)c->core * FL_FUZZY_AUNIT;
    t->slope = c->slope >= FL_FUZZY_WFULL ? HT : (int32_t)c->slope * FL_FUZZY_AUNIT;
    t->height_q16 = (uint32_t)c->height * 257u + (uint32_t)(c->height >> 7);
    t->bias_q16 = (uint32_t)c->bias * 257u + (uint32_t)(c->bias >> 7);
}

/* Scaling and overflow: Q16 [0, 65536] -> Q0.8 ceil(x * 255 / 65536) (x *
 * 255 < 2^24); core code ceil(core / 128), support code ceil((core + slope)
 * / 128), slope code their difference, each saturated to 255 (= 180 deg or
 * more): the coded trapezoid contains the expanded one. */
void fl_fuzzy_trap_to_cell(const fl_fuzzy_trap_t *t, fl_fuzzy_cell_t *c)
{
    ntrap_t n;
    int32_t cc, sc;
    if (t == NULL || c == NULL)
        return;
    normalize(t, &n);
    cc = (n.w + FL_FUZZY_AUNIT - 1) / FL_FUZZY_AUNIT;
    sc = (n.w + n.s + FL_FUZZY_AUNIT - 1) / FL_FUZZY_AUNIT;
    if (cc > FL_FUZZY_WFULL)
        cc = FL_FUZZY_WFULL;
    sc -= cc;
    if (sc > FL_FUZZY_WFULL)
        sc = FL_FUZZY_WFULL;
    c->centre = t->centre;
    c->core = (uint8_t)cc;
    c->slope = (uint8_t)sc;
    c->height = (uint8_t)((n.h * 255u + 65535u) >> 16);
    c->bias = (uint8_t)((n.b * 255u + 65535u) >> 16);
}

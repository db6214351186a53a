/*
 * src/model/homography.c - normalised DLT in integers (homography.h).
 *
 * Numbers of the 8 x 8 solve are "mantissa x 2^exponent" pairs (hf_t):
 * a 30-bit signed mantissa (2^29 <= |m| < 2^30, or 0) and an int32
 * exponent.  Products and quotients of two mantissas fit int64; sums align
 * the smaller operand to the larger one's exponent with 32 guard bits.
 * Every operation rounds once, so the relative error per step is about
 * 2^-30 (1e-9), amplified by the condition of the system (squared for the
 * normal equations; the normalisation keeps it small): against a double
 * DLT on the same inputs the fitted map agrees within 0.05 mm over a 9 x 6 m
 * field seen from 640 x 480 (host_tests/test_homography.c).  All of it is
 * integer arithmetic, identical on every target.
 *
 * Scaling of the mappings.  A pixel is |u| <= 2^20 (Q4), its offset from
 * the centroid below 2^21, the entries |h| <= 2^30 and 2^shift <= 2^21, so
 * each of the three sums h0 dx + h1 dy + h2 2^shift is below 2^53.
 */
#include "fieldloc/homography.h"
#include "fieldloc/fixed.h"

#include <string.h>
#include <limits.h>

typedef struct {
    int32_t m;
    int32_t e;
} hf_t;

#define HF_HI (1L << 30)
/* a pivot this many binary orders below the largest entry: singular */
#define SINGULAR_BITS 24

static uint64_t mag64(int64_t v)
{
    return v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
}

static int bitlen64(uint64_t a)
{
    int n = 0;
    while (a) {
        a >>= 1;
        n++;
    }
    return n;
}

/* v / 2^s rounded half away from zero (s <= 63) */
static int64_t rsh_round64(int64_t v, int s)
{
    uint64_t a;
    if (s <= 0)
        return v;
    if (s > 63)
        return 0;
    a = mag64(v);
    a = (a >> s) + ((a >> (s - 1)) & 1u);
    return v < 0 ? -(int64_t)a : (int64_t)a;
}

static hf_t hf_norm(int64_t v, int32_t e)
{
    hf_t r = {0, 0};
    uint64_t a = mag64(v);
    int s;
    if (a == 0)
        return r;
    s = bitlen64(a) - 30;
    if (s > 0) {
        a = (a >> s) + ((a >> (s - 1)) & 1u);
        e += s;
        if (a >= (uint64_t)HF_HI) {
            a >>= 1;
            e++;
        }
    } else {
        a <<= -s;
        e += s;
    }
    r.m = v < 0 ? -(int32_t)a : (int32_t)a;
    r.e = e;
    return r;
}

static hf_t hf_int(int64_t v, int32_t e) { return hf_norm(v, e); }

static hf_t hf_mul(hf_t a, hf_t b) { return hf_norm((int64_t)a.m * b.m, a.e + b.e); }

static hf_t hf_neg(hf_t a)
{
    a.m = -a.m;
    return a;
}

static hf_t hf_add(hf_t a, hf_t b)
{
    int64_t va, vb;
    int32_t d;
    if (b.m == 0)
        return a;
    if (a.m == 0)
        return b;
    if (a.e < b.e) {
        hf_t t = a;
        a = b;
        b = t;
    }
    d = a.e - b.e;
    va = (int64_t)a.m * ((int64_t)1 << 32);
    vb = d > 62 ? 0 : rsh_round64((int64_t)b.m * ((int64_t)1 << 32), (int)d);
    return hf_norm(va + vb, a.e - 32);
}

static hf_t hf_sub(hf_t a, hf_t b) { return hf_add(a, hf_neg(b)); }

/* b.m != 0 */
static hf_t hf_div(hf_t a, hf_t b)
{
    return hf_norm(((int64_t)a.m * ((int64_t)1 << 32)) / b.m, a.e - b.e - 32);
}

/* |a| > |b| */
static bool hf_abs_gt(hf_t a, hf_t b)
{
    if (a.m == 0)
        return false;
    if (b.m == 0)
        return true;
    if (a.e != b.e)
        return a.e > b.e;
    return mag64(a.m) > mag64(b.m);
}

/* Gaussian elimination with partial pivoting of m (8 x 8 | right side);
 * false when a pivot is zero or SINGULAR_BITS below the largest entry. */
static bool solve8(hf_t m[8][9], hf_t x[8])
{
    hf_t big = {0, 0};
    int i, r, c;
    for (r = 0; r < 8; r++)
        for (c = 0; c < 8; c++)
            if (hf_abs_gt(m[r][c], big))
                big = m[r][c];
    if (big.m == 0)
        return false;
    for (i = 0; i < 8; i++) {
        int p = i;
        for (r = i + 1; r < 8; r++)
            if (hf_abs_gt(m[r][i], m[p][i]))
                p = r;
        if (m[p][i].m == 0 || m[p][i].e < big.e - SINGULAR_BITS)
            return false;
        if (p != i)
            for (c = 0; c < 9; c++) {
                hf_t t = m[i][c];
                m[i][c] = m[p][c];
                m[p][c] = t;
            }
        for (r = i + 1; r < 8; r++) {
            hf_t f;
            if (m[r][i].m == 0)
                continue;
            f = hf_div(m[r][i], m[i][i]);
            for (c = i; c < 9; c++)
                m[r][c] = hf_sub(m[r][c], hf_mul(f, m[i][c]));
        }
    }
    for (i = 7; i >= 0; i--) {
        hf_t s = m[i][8];
        for (c = i + 1; c < 8; c++)
            s = hf_sub(s, hf_mul(m[i][c], x[c]));
        x[i] = hf_div(s, m[i][i]);
    }
    return true;
}

/* ---- normalisation ------------------------------------------------------ */

typedef struct {
    int32_t c[2];   /* centroid, input units */
    int32_t shift;  /* mean distance from it in [2^shift, 2^(shift+1)) */
} norm_t;

/* centroid and power-of-two scale of the image (img) or field points */
static void normalise(const fl_homog_pair_t *p, size_t n, int img, norm_t *out)
{
    int64_t sx = 0, sy = 0;
    uint64_t dsum = 0, mean;
    size_t i;
    for (i = 0; i < n; i++) {
        sx += img ? p[i].u_q4 : p[i].x_mm;
        sy += img ? p[i].v_q4 : p[i].y_mm;
    }
    out->c[0] = (int32_t)(sx / (int64_t)n);
    out->c[1] = (int32_t)(sy / (int64_t)n);
    for (i = 0; i < n; i++) {
        int32_t dx = (img ? p[i].u_q4 : p[i].x_mm) - out->c[0];
        int32_t dy = (img ? p[i].v_q4 : p[i].y_mm) - out->c[1];
        dsum += fl_hypot(dx, dy);
    }
    mean = dsum / n;
    out->shift = mean ? bitlen64(mean) - 1 : 0;
}

/* ---- checks ------------------------------------------------------------- */

static void pt_of(const fl_homog_pair_t *p, int img, int32_t *x, int32_t *y)
{
    *x = img ? p->u_q4 : p->x_mm;
    *y = img ? p->v_q4 : p->y_mm;
}

/* c nearly on the line through a and b: |sin| of the angle at a below
 * 1/1024 (or c == a) */
static bool collinear3(const fl_homog_pair_t *a, const fl_homog_pair_t *b,
                       const fl_homog_pair_t *c, int img)
{
    int32_t ax, ay, bx, by, cx, cy;
    int64_t cr;
    uint64_t lb, lc;
    pt_of(a, img, &ax, &ay);
    pt_of(b, img, &bx, &by);
    pt_of(c, img, &cx, &cy);
    cr = (int64_t)(bx - ax) * (cy - ay) - (int64_t)(by - ay) * (cx - ax);
    lb = fl_hypot(bx - ax, by - ay);
    lc = fl_hypot(cx - ax, cy - ay);
    return mag64(cr) * 1024u <= lb * lc;
}

static fl_homog_status_t check_points(const fl_homog_pair_t *p, size_t n)
{
    size_t i, j, k;
    int img;
    for (i = 0; i < n; i++) {
        if (p[i].u_q4 > FL_HOMOG_MAX_Q4 || p[i].u_q4 < -FL_HOMOG_MAX_Q4 ||
            p[i].v_q4 > FL_HOMOG_MAX_Q4 || p[i].v_q4 < -FL_HOMOG_MAX_Q4 ||
            p[i].x_mm > FL_HOMOG_MAX_MM || p[i].x_mm < -FL_HOMOG_MAX_MM ||
            p[i].y_mm > FL_HOMOG_MAX_MM || p[i].y_mm < -FL_HOMOG_MAX_MM)
            return FL_HOMOG_RANGE;
    }
    for (img = 0; img < 2; img++) {
        size_t far = 1;
        int32_t x0, y0, x1, y1;
        for (i = 0; i < n; i++)
            for (j = i + 1; j < n; j++) {
                pt_of(&p[i], img, &x0, &y0);
                pt_of(&p[j], img, &x1, &y1);
                if (x0 == x1 && y0 == y1)
                    return FL_HOMOG_DEGENERATE;
            }
        if (n == 4) {
            for (i = 0; i < 4; i++)
                for (j = i + 1; j < 4; j++)
                    for (k = j + 1; k < 4; k++)
                        if (collinear3(&p[i], &p[j], &p[k], img))
                            return FL_HOMOG_DEGENERATE;
            continue;
        }
        /* all on one line: the line through p[0] and the point farthest from it */
        pt_of(&p[0], img, &x0, &y0);
        for (i = 1, k = 0; i < n; i++) {
            uint32_t d, dfar;
            pt_of(&p[i], img, &x1, &y1);
            d = fl_hypot(x1 - x0, y1 - y0);
            pt_of(&p[far], img, &x1, &y1);
            dfar = fl_hypot(x1 - x0, y1 - y0);
            if (d > dfar)
                far = i;
        }
        for (i = 1; i < n; i++)
            if (i != far && !collinear3(&p[0], &p[far], &p[i], img))
                k++;
        if (k == 0)
            return FL_HOMOG_DEGENERATE;
    }
    return FL_HOMOG_OK;
}

/* ---- the linear system ---------------------------------------------------- */

/* The two rows (8 coefficients | right side) of one pair in normalised
 * coordinates, h33 = 1:
 *   h1 x + h2 y + h3 - h7 x X - h8 y X = X
 *   h4 x + h5 y + h6 - h7 x Y - h8 y Y = Y */
static void pair_rows(const fl_homog_pair_t *p, const norm_t nm[2], hf_t r[2][9])
{
    hf_t x = hf_int((int64_t)p->u_q4 - nm[0].c[0], -nm[0].shift);
    hf_t y = hf_int((int64_t)p->v_q4 - nm[0].c[1], -nm[0].shift);
    hf_t X = hf_int((int64_t)p->x_mm - nm[1].c[0], -nm[1].shift);
    hf_t Y = hf_int((int64_t)p->y_mm - nm[1].c[1], -nm[1].shift);
    hf_t zero = {0, 0}, one = hf_int(1, 0);
    int c;
    for (c = 0; c < 9; c++)
        r[0][c] = r[1][c] = zero;
    r[0][0] = x; r[0][1] = y; r[0][2] = one;
    r[1][3] = x; r[1][4] = y; r[1][5] = one;
    r[0][6] = hf_neg(hf_mul(x, X));
    r[0][7] = hf_neg(hf_mul(y, X));
    r[1][6] = hf_neg(hf_mul(x, Y));
    r[1][7] = hf_neg(hf_mul(y, Y));
    r[0][8] = X;
    r[1][8] = Y;
}

/* Four pairs: the 8 x 8 system itself; more: the normal equations
 * A^T A h = A^T b (the right side is column 8 of each row). */
static void build_system(const fl_homog_pair_t *p, size_t n, const norm_t nm[2], hf_t m[8][9])
{
    hf_t r[2][9];
    hf_t zero = {0, 0};
    size_t i;
    int a, b, k;
    if (n == 4) {
        for (i = 0; i < 4; i++) {
            pair_rows(&p[i], nm, r);
            for (b = 0; b < 9; b++) {
                m[2 * i][b] = r[0][b];
                m[2 * i + 1][b] = r[1][b];
            }
        }
        return;
    }
    for (a = 0; a < 8; a++)
        for (b = 0; b < 9; b++)
            m[a][b] = zero;
    for (i = 0; i < n; i++) {
        pair_rows(&p[i], nm, r);
        for (k = 0; k < 2; k++)
            for (a = 0; a < 8; a++) {
                if (r[k][a].m == 0)
                    continue;
                for (b = 0; b < 9; b++)
                    m[a][b] = hf_add(m[a][b], hf_mul(r[k][a], r[k][b]));
            }
    }
}

/* nine int64 values -> int32 with one shared right shift, largest |v| at
 * most 2^30; false when all are zero */
static bool to_block(const int64_t v[9], int32_t out[9])
{
    uint64_t big = 0;
    int i, s;
    for (i = 0; i < 9; i++)
        if (mag64(v[i]) > big)
            big = mag64(v[i]);
    if (big == 0)
        return false;
    s = bitlen64(big) - 30;
    for (i = 0; i < 9; i++)
        out[i] = (int32_t)(s > 0 ? rsh_round64(v[i], s) : v[i] * ((int64_t)1 << -s));
    return true;
}

/* the solution (h33 = 1) as nine mantissas with one exponent */
static bool solution_block(const hf_t x[8], int32_t h[9])
{
    hf_t all[9];
    int64_t v[9];
    int32_t emax = INT32_MIN;
    int i;
    for (i = 0; i < 8; i++)
        all[i] = x[i];
    all[8] = hf_int(1, 0);
    for (i = 0; i < 9; i++)
        if (all[i].m != 0 && all[i].e > emax)
            emax = all[i].e;
    for (i = 0; i < 9; i++) {
        int32_t d = emax - all[i].e;
        v[i] = (all[i].m == 0 || d > 62) ? 0 : rsh_round64(all[i].m, (int)d);
    }
    return to_block(v, h);
}

/* hinv = adjugate of h (its inverse up to scale), signed so that w at the
 * field centroid is positive */
static bool invert(const int32_t a[9], int32_t out[9])
{
    int64_t c[9];
    int i;
    c[0] = (int64_t)a[4] * a[8] - (int64_t)a[5] * a[7];
    c[1] = (int64_t)a[2] * a[7] - (int64_t)a[1] * a[8];
    c[2] = (int64_t)a[1] * a[5] - (int64_t)a[2] * a[4];
    c[3] = (int64_t)a[5] * a[6] - (int64_t)a[3] * a[8];
    c[4] = (int64_t)a[0] * a[8] - (int64_t)a[2] * a[6];
    c[5] = (int64_t)a[2] * a[3] - (int64_t)a[0] * a[5];
    c[6] = (int64_t)a[3] * a[7] - (int64_t)a[4] * a[6];
    c[7] = (int64_t)a[1] * a[6] - (int64_t)a[0] * a[7];
    c[8] = (int64_t)a[0] * a[4] - (int64_t)a[1] * a[3];
    if (c[8] == 0)
        return false;
    if (c[8] < 0)
        for (i = 0; i < 9; i++)
            c[i] = -c[i];
    return to_block(c, out);
}

/* ---- mapping -------------------------------------------------------------- */

typedef struct {
    const int32_t *h;
    const int32_t *src_c, *dst_c;
    int32_t src_shift, dst_shift;
    int32_t out_shift;   /* output in dst units * 2^out_shift */
    int64_t limit;       /* largest |output| */
} map_t;

static int64_t div_round64(int64_t n, int64_t d)
{
    /* d > 0 */
    return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

static fl_homog_status_t map_point(const map_t *mp, int32_t in_x, int32_t in_y,
                                   int64_t *ox, int64_t *oy)
{
    const int32_t *h = mp->h;
    int64_t dx = (int64_t)in_x - mp->src_c[0], dy = (int64_t)in_y - mp->src_c[1];
    int64_t one = (int64_t)1 << mp->src_shift;
    int64_t nx = h[0] * dx + h[1] * dy + h[2] * one;
    int64_t ny = h[3] * dx + h[4] * dy + h[5] * one;
    int64_t w = h[6] * dx + h[7] * dy + h[8] * one;
    int32_t g = mp->dst_shift + mp->out_shift;
    uint64_t big = mag64(nx) > mag64(ny) ? mag64(nx) : mag64(ny);
    int s;
    if (w <= 0)
        return FL_HOMOG_HORIZON;
    s = bitlen64(big) + g - 62;
    if (s > 0) {
        nx = rsh_round64(nx, s);
        ny = rsh_round64(ny, s);
        w = rsh_round64(w, s);
        if (w <= 0)
            return FL_HOMOG_RANGE;
    }
    *ox = (int64_t)mp->dst_c[0] * ((int64_t)1 << mp->out_shift) +
          div_round64(nx * ((int64_t)1 << g), w);
    *oy = (int64_t)mp->dst_c[1] * ((int64_t)1 << mp->out_shift) +
          div_round64(ny * ((int64_t)1 << g), w);
    if (*ox > mp->limit || *ox < -mp->limit || *oy > mp->limit || *oy < -mp->limit)
        return FL_HOMOG_RANGE;
    return FL_HOMOG_OK;
}

static fl_homog_status_t to_field_q4(const fl_homog_t *h, int32_t u_q4, int32_t v_q4,
                                     int64_t *x, int64_t *y)
{
    map_t mp;
    if (h->valid != 1)
        return FL_HOMOG_NOT_FITTED;
    if (u_q4 > FL_HOMOG_MAX_Q4 || u_q4 < -FL_HOMOG_MAX_Q4 ||
        v_q4 > FL_HOMOG_MAX_Q4 || v_q4 < -FL_HOMOG_MAX_Q4)
        return FL_HOMOG_RANGE;
    mp.h = h->h;
    mp.src_c = h->img_c_q4;
    mp.dst_c = h->fld_c_mm;
    mp.src_shift = h->img_shift;
    mp.dst_shift = h->fld_shift;
    mp.out_shift = 4;
    mp.limit = (int64_t)FL_HOMOG_MAX_MM * 16;
    return map_point(&mp, u_q4, v_q4, x, y);
}

static fl_homog_status_t to_image(const fl_homog_t *h, int32_t x_mm, int32_t y_mm,
                                  int64_t *u, int64_t *v)
{
    map_t mp;
    if (h->valid != 1)
        return FL_HOMOG_NOT_FITTED;
    if (x_mm > FL_HOMOG_MAX_MM || x_mm < -FL_HOMOG_MAX_MM ||
        y_mm > FL_HOMOG_MAX_MM || y_mm < -FL_HOMOG_MAX_MM)
        return FL_HOMOG_RANGE;
    mp.h = h->hinv;
    mp.src_c = h->fld_c_mm;
    mp.dst_c = h->img_c_q4;
    mp.src_shift = h->fld_shift;
    mp.dst_shift = h->img_shift;
    mp.out_shift = 0;
    mp.limit = FL_HOMOG_MAX_Q4;
    return map_point(&mp, x_mm, y_mm, u, v);
}

/* ---- public --------------------------------------------------------------- */

fl_homog_status_t fl_homog_fit(fl_homog_t *h, const fl_homog_pair_t *pairs, size_t n)
{
    norm_t nm[2];   /* image, field */
    hf_t m[8][9], x[8];
    fl_homog_status_t st;
    size_t i;
    if (h == NULL)
        return FL_HOMOG_ERR_NULL;
    memset(h, 0, sizeof *h);
    if (pairs == NULL && n > 0)
        return FL_HOMOG_ERR_NULL;
    if (n < FL_HOMOG_MIN_POINTS)
        return FL_HOMOG_TOO_FEW;
    if (n > FL_HOMOG_MAX_POINTS)
        return FL_HOMOG_RANGE;
    st = check_points(pairs, n);
    if (st != FL_HOMOG_OK)
        return st;
    normalise(pairs, n, 1, &nm[0]);
    normalise(pairs, n, 0, &nm[1]);
    build_system(pairs, n, nm, m);
    if (!solve8(m, x) || !solution_block(x, h->h) || h->h[8] <= 0 || !invert(h->h, h->hinv))
        return FL_HOMOG_DEGENERATE;
    h->img_c_q4[0] = nm[0].c[0];
    h->img_c_q4[1] = nm[0].c[1];
    h->fld_c_mm[0] = nm[1].c[0];
    h->fld_c_mm[1] = nm[1].c[1];
    h->img_shift = nm[0].shift;
    h->fld_shift = nm[1].shift;
    h->valid = 1;
    /* every fitted point must lie in front of the camera both ways */
    for (i = 0; i < n; i++) {
        int64_t a, b;
        if (to_field_q4(h, pairs[i].u_q4, pairs[i].v_q4, &a, &b) != FL_HOMOG_OK ||
            to_image(h, pairs[i].x_mm, pairs[i].y_mm, &a, &b) != FL_HOMOG_OK) {
            memset(h, 0, sizeof *h);
            return FL_HOMOG_DEGENERATE;
        }
    }
    return FL_HOMOG_OK;
}

fl_homog_status_t fl_homog_image_to_field_q4(const fl_homog_t *h, int32_t u_q4, int32_t v_q4,
                                             int32_t *x_mm_q4, int32_t *y_mm_q4)
{
    int64_t x, y;
    fl_homog_status_t st;
    if (h == NULL || x_mm_q4 == NULL || y_mm_q4 == NULL)
        return FL_HOMOG_ERR_NULL;
    st = to_field_q4(h, u_q4, v_q4, &x, &y);
    if (st == FL_HOMOG_OK) {
        *x_mm_q4 = (int32_t)x;
        *y_mm_q4 = (int32_t)y;
    }
    return st;
}

fl_homog_status_t fl_homog_image_to_field(const fl_homog_t *h, int32_t u_q4, int32_t v_q4,
                                          fl_point_t *field)
{
    int64_t x, y;
    fl_homog_status_t st;
    if (h == NULL || field == NULL)
        return FL_HOMOG_ERR_NULL;
    st = to_field_q4(h, u_q4, v_q4, &x, &y);
    if (st == FL_HOMOG_OK) {
        field->x_mm = (int32_t)rsh_round64(x, 4);
        field->y_mm = (int32_t)rsh_round64(y, 4);
    }
    return st;
}

fl_homog_status_t fl_homog_field_to_image(const fl_homog_t *h, fl_point_t field,
                                          int32_t *u_q4, int32_t *v_q4)
{
    int64_t u, v;
    fl_homog_status_t st;
    if (h == NULL || u_q4 == NULL || v_q4 == NULL)
        return FL_HOMOG_ERR_NULL;
    st = to_image(h, field.x_mm, field.y_mm, &u, &v);
    if (st == FL_HOMOG_OK) {
        *u_q4 = (int32_t)u;
        *v_q4 = (int32_t)v;
    }
    return st;
}

fl_homog_status_t fl_homog_error(const fl_homog_t *h, const fl_homog_pair_t *pairs, size_t n,
                                 fl_homog_error_t *err)
{
    uint64_t s_mm = 0, s_px = 0;
    size_t i;
    if (h == NULL || err == NULL || (pairs == NULL && n > 0))
        return FL_HOMOG_ERR_NULL;
    memset(err, 0, sizeof *err);
    if (h->valid != 1)
        return FL_HOMOG_NOT_FITTED;
    if (n > FL_HOMOG_MAX_POINTS)
        return FL_HOMOG_RANGE;
    for (i = 0; i < n; i++) {
        const fl_homog_pair_t *p = &pairs[i];
        int64_t x, y, u, v;
        uint32_t e_mm, e_px;
        if (to_field_q4(h, p->u_q4, p->v_q4, &x, &y) != FL_HOMOG_OK ||
            to_image(h, p->x_mm, p->y_mm, &u, &v) != FL_HOMOG_OK) {
            err->n_failed++;
            continue;
        }
        /* both differences are below 2^26 (outputs within the limits) */
        e_mm = fl_hypot((int32_t)(x - (int64_t)p->x_mm * 16), (int32_t)(y - (int64_t)p->y_mm * 16));
        e_px = fl_hypot((int32_t)(u - p->u_q4), (int32_t)(v - p->v_q4));
        s_mm += (uint64_t)e_mm * e_mm;
        s_px += (uint64_t)e_px * e_px;
        if (e_mm > err->max_mm_q4)
            err->max_mm_q4 = e_mm;
        if (e_px > err->max_px_q4)
            err->max_px_q4 = e_px;
        err->n_used++;
    }
    if (err->n_used) {
        err->rms_mm_q4 = fl_isqrt64(s_mm / err->n_used);
        err->rms_px_q4 = fl_isqrt64(s_px / err->n_used);
    }
    return FL_HOMOG_OK;
}

static void put_point(fl_homog_field_point_t *out, size_t cap, size_t *k, const char *name,
                      int32_t x, int32_t y)
{
    if (*k < cap) {
        out[*k].name = name;
        out[*k].x_mm = x;
        out[*k].y_mm = y;
        (*k)++;
    }
}

size_t fl_homog_field_points(const fl_field_t *f, fl_homog_field_point_t *out, size_t cap)
{
    size_t k = 0;
    int32_t L, W, d, pw;
    if (f == NULL || out == NULL)
        return 0;
    L = f->length_mm / 2;
    W = f->width_mm / 2;
    d = f->penalty_area_depth_mm;
    pw = f->penalty_area_width_mm / 2;
    /* "pos"/"neg": the end at +x / -x; "left"/"right": y > 0 / y < 0 */
    put_point(out, cap, &k, "corner_pos_left", L, W);
    put_point(out, cap, &k, "corner_pos_right", L, -W);
    put_point(out, cap, &k, "corner_neg_left", -L, W);
    put_point(out, cap, &k, "corner_neg_right", -L, -W);
    if (d > 0 && pw > 0) {
        /* "goal": on the goal line (T); "front": the field side (L) */
        put_point(out, cap, &k, "penalty_pos_goal_left", L, pw);
        put_point(out, cap, &k, "penalty_pos_goal_right", L, -pw);
        put_point(out, cap, &k, "penalty_pos_front_left", L - d, pw);
        put_point(out, cap, &k, "penalty_pos_front_right", L - d, -pw);
        put_point(out, cap, &k, "penalty_neg_goal_left", -L, pw);
        put_point(out, cap, &k, "penalty_neg_goal_right", -L, -pw);
        put_point(out, cap, &k, "penalty_neg_front_left", -(L - d), pw);
        put_point(out, cap, &k, "penalty_neg_front_right", -(L - d), -pw);
    }
    if (f->penalty_mark_x_mm > 0) {
        put_point(out, cap, &k, "penalty_mark_pos", f->penalty_mark_x_mm, 0);
        put_point(out, cap, &k, "penalty_mark_neg", -f->penalty_mark_x_mm, 0);
    }
    put_point(out, cap, &k, "halfway_left", 0, W);
    put_point(out, cap, &k, "halfway_right", 0, -W);
    if (fl_field_count_kind(f, FL_LM_CENTRE_MARK) > 0)
        put_point(out, cap, &k, "centre_mark", 0, 0);
    return k;
}

const char *fl_homog_status_str(fl_homog_status_t s)
{
    switch (s) {
    case FL_HOMOG_OK: return "ok";
    case FL_HOMOG_ERR_NULL: return "NULL argument";
    case FL_HOMOG_TOO_FEW: return "too few points";
    case FL_HOMOG_DEGENERATE: return "degenerate points";
    case FL_HOMOG_RANGE: return "out of range";
    case FL_HOMOG_HORIZON: return "at or beyond the horizon";
    case FL_HOMOG_NOT_FITTED: return "not fitted";
    }
    return "unknown status";
}

/*
 * src/vision/skeleton_cross.c - nodes, spur removal, crossings and the
 * sample of skeleton pixels over the thinned image (skeleton.h).
 *
 * Algorithm.  (1) Spurs: from every end (degree 1) walk along the
 * skeleton, edge neighbours before corner ones (so a 4-connected turn is
 * walked through its corner pixel), at most spur_px pixels; when the walk
 * meets a node (degree >= 3) before that, the walked pixels are deleted,
 * and K3M's final phase runs again (the node may have become thinnable).
 * (2) Nodes: the skeleton pixels of degree >= 3.  (3) Clusters: union-find
 * over the node pairs within merge_px (Chebyshev); then clusters whose
 * floods (below) reach each other's node pixels are joined (the skeleton
 * piece between them is shorter than an arm: at an acute X the thinned
 * junction is two T nodes far apart).  (4) Per cluster, a
 * flood over the skeleton from its node pixels inside its node box grown
 * by arm_px; the runs of flooded pixels along the box's border are the
 * arms (a branch shorter than arm_px, or one that comes back, never
 * reaches it).  An arm on a side clipped by the mask edge leaves the image
 * before it is known to be an arm: the cluster is rejected.  (5) Position:
 * X, the intersection of the two lines through opposite arms' points; T,
 * the bar's line (the straightest pair's points) meets the stem's (its
 * border point to its walk's end), or the node centroid projected onto
 * the bar; L, the node centroid.  (6) The sample: a partial
 * Fisher-Yates shuffle of the skeleton list by xorshift32 (Marsaglia
 * 2003) seeded from the caller's seed.
 *
 * Scaling.  Working coordinates < 2^12 + 2, Q4 < 2^17; cross products of
 * Q4 differences < 2^36 and their products with a difference < 2^54, in
 * int64.  The flood's queue is the free tail of the contour list (it
 * holds every flooded pixel, so the flags are cleared from it after).
 * Cost: see skeleton.h.  Stack < 400 B.
 */
#include "skeleton_int.h"

#include <string.h>

#define SK_NONE 0xFFFFFFFFu
#define SK_MAX_SPAN 32        /* node box side above which a cluster is a
                                 tangle (a blob's skeleton), not a crossing */
#define SK_SPUR_MAX 32        /* params.spur_px range */
#define SK_JOIN_PASSES 4      /* cluster joining passes */

static int32_t sk_min(int32_t a, int32_t b) { return a < b ? a : b; }
static int32_t sk_max(int32_t a, int32_t b) { return a > b ? a : b; }
static int32_t sk_abs(int32_t a) { return a < 0 ? -a : a; }

static int sk_degree_at(const fl_skel_t *s, uint32_t i)
{
    return fl_skel_degree((uint8_t)sk_weight(s, i));
}

/* The next pixel of a walk: the first white, unvisited neighbour, edge
 * neighbours first; SK_NONE when there is none. */
static uint32_t sk_next(const fl_skel_t *s, uint32_t i, const int32_t off[8])
{
    static const uint8_t order[8] = {0, 2, 4, 6, 1, 3, 5, 7};
    int k;
    for (k = 0; k < 8; k++) {
        uint32_t j = (uint32_t)((int32_t)i + off[order[k]]);
        if ((s->px[j] & (SK_WHITE | SK_SEEN)) == SK_WHITE)
            return j;
    }
    return SK_NONE;
}

/* Walk from end e; delete the walked pixels when a node comes within
 * spur_px of them. */
static void sk_spur(fl_skel_t *s, uint32_t e, const int32_t off[8])
{
    uint32_t path[SK_SPUR_MAX];
    int32_t len = 0, k;
    int spur = 0;
    uint32_t cur = e;
    path[len++] = e;
    s->px[e] |= SK_SEEN;
    for (;;) {
        uint32_t nx = sk_next(s, cur, off);
        if (nx == SK_NONE)
            break;
        if (sk_degree_at(s, nx) >= 3) {
            spur = 1;
            break;
        }
        if (len >= s->params.spur_px)
            break;
        path[len++] = nx;
        s->px[nx] |= SK_SEEN;
        cur = nx;
    }
    for (k = 0; k < len; k++) {
        if (spur)
            fl_skel_erase(s, path[k]);
        else
            s->px[path[k]] = (uint8_t)(s->px[path[k]] & ~SK_SEEN);
    }
    if (spur)
        s->spurs++;
}

static void sk_prune(fl_skel_t *s, const int32_t off[8])
{
    int32_t r, n = s->n_contour;
    if (s->params.spur_px < 1)
        return;
    for (r = 0; r < n; r++) {
        uint32_t i = s->contour[r];
        if ((s->px[i] & SK_WHITE) && sk_degree_at(s, i) == 1)
            sk_spur(s, i, off);
    }
    fl_skel_compact(s);
    if (s->spurs > 0)
        fl_skel_one_pixel(s);
}

/* Node pixels, packed as y << 16 | x (working coordinates). */
static void sk_nodes(fl_skel_t *s)
{
    const uint32_t ps = (uint32_t)s->pstride;
    int32_t r;
    for (r = 0; r < s->n_contour; r++) {
        uint32_t i = s->contour[r];
        if (sk_degree_at(s, i) < 3)
            continue;
        if (s->n_nodes < FL_SKEL_MAX_NODES) {
            s->px[i] |= SK_NODE;
            s->node[s->n_nodes] = (i / ps) << 16 | (i % ps);
            s->parent[s->n_nodes] = (uint16_t)s->n_nodes;
            s->n_nodes++;
        } else {
            s->nodes_dropped++;
        }
    }
}

static uint16_t sk_find(fl_skel_t *s, uint16_t k)
{
    while (s->parent[k] != k) {
        s->parent[k] = s->parent[s->parent[k]];
        k = s->parent[k];
    }
    return k;
}

static void sk_cluster(fl_skel_t *s)
{
    int32_t a, b, m = s->params.merge_px;
    for (a = 0; a < s->n_nodes; a++) {
        int32_t ax = (int32_t)(s->node[a] & 0xFFFFu), ay = (int32_t)(s->node[a] >> 16);
        for (b = a + 1; b < s->n_nodes; b++) {
            int32_t bx = (int32_t)(s->node[b] & 0xFFFFu), by = (int32_t)(s->node[b] >> 16);
            if (sk_abs(ax - bx) <= m && sk_abs(ay - by) <= m) {
                uint16_t ra = sk_find(s, (uint16_t)a), rb = sk_find(s, (uint16_t)b);
                if (ra != rb) {   /* the smaller index stays the root */
                    if (ra < rb)
                        s->parent[rb] = ra;
                    else
                        s->parent[ra] = rb;
                }
            }
        }
    }
}

/* One cluster under examination. */
typedef struct {
    int32_t x0, y0, x1, y1;       /* node box, working coordinates */
    int32_t bx0, by0, bx1, by1;   /* flood box (clipped to the mask) */
    int32_t clip;                 /* bit 0..3: left, top, right, bottom clipped */
    int32_t n;                    /* node pixels */
    int32_t cx_q4, cy_q4;         /* node centroid, working coordinates */
    int32_t n_arms;
    int32_t ax_q4[4], ay_q4[4];   /* arm points: the end of a walk out of
                                     the box, else the border run's centre */
    int32_t rx_q4[4], ry_q4[4];   /* the border run's centre */
    uint32_t mid[4];              /* a pixel of each border run */
    fl_angle_t arm[4];
} sk_cluster_t;

/* Flood the skeleton from the cluster's nodes inside its box.  Returns the
 * pixels flooded (they are listed from queue[0]), -1 when the queue was
 * too short (flags cleared then). */
static int32_t sk_flood(fl_skel_t *s, uint16_t root, const sk_cluster_t *c,
                        const int32_t off[8])
{
    const uint32_t ps = (uint32_t)s->pstride;
    uint32_t *q = s->contour + s->n_contour;
    int32_t cap = FL_SKEL_MAX_CONTOUR - s->n_contour, n = 0, head = 0, k;
    for (k = 0; k < s->n_nodes; k++) {
        uint32_t i;
        if (sk_find(s, (uint16_t)k) != root)
            continue;
        i = (s->node[k] >> 16) * ps + (s->node[k] & 0xFFFFu);
        if (n >= cap)
            goto full;
        s->px[i] |= SK_SEEN;
        q[n++] = i;
    }
    while (head < n) {
        uint32_t i = q[head++];
        for (k = 0; k < 8; k++) {
            uint32_t j = (uint32_t)((int32_t)i + off[k]);
            int32_t x = (int32_t)(j % ps), y = (int32_t)(j / ps);
            if ((s->px[j] & (SK_WHITE | SK_SEEN)) != SK_WHITE ||
                x < c->bx0 || x > c->bx1 || y < c->by0 || y > c->by1)
                continue;
            if (n >= cap)
                goto full;
            s->px[j] |= SK_SEEN;
            q[n++] = j;
        }
    }
    return n;
full:
    for (k = 0; k < n; k++)
        s->px[q[k]] = (uint8_t)(s->px[q[k]] & ~SK_SEEN);
    return -1;
}

/* Position p (0 .. perimeter - 1) along the flood box's border, clockwise
 * from the top-left corner; *side: 0 top, 1 right, 2 bottom, 3 left. */
static void sk_ring_xy(const sk_cluster_t *c, int32_t p, int32_t *x, int32_t *y, int32_t *side)
{
    int32_t w = c->bx1 - c->bx0, h = c->by1 - c->by0;
    if (p < w) {
        *x = c->bx0 + p; *y = c->by0; *side = 0;
    } else if (p < w + h) {
        *x = c->bx1; *y = c->by0 + (p - w); *side = 1;
    } else if (p < 2 * w + h) {
        *x = c->bx1 - (p - w - h); *y = c->by1; *side = 2;
    } else {
        *x = c->bx0; *y = c->by1 - (p - 2 * w - h); *side = 3;
    }
}

/* Walk out of the box along an arm from its border pixel, at most
 * arm_px pixels, listing the walked pixels (flagged) in q from *n (cap:
 * cap); the arm point becomes the walk's end when it went at least
 * arm_px / 2 pixels (a longer baseline for the direction). */
static void sk_arm_walk(fl_skel_t *s, sk_cluster_t *c, int32_t a, uint32_t *q, int32_t *n,
                        int32_t cap, const int32_t off[8])
{
    const uint32_t ps = (uint32_t)s->pstride;
    uint32_t cur = c->mid[a];
    int32_t len = 0;
    while (len < s->params.arm_px && *n < cap) {
        uint32_t nx = sk_next(s, cur, off);
        if (nx == SK_NONE)
            break;
        s->px[nx] |= SK_SEEN;
        q[(*n)++] = nx;
        cur = nx;
        len++;
    }
    if (len * 2 >= s->params.arm_px) {
        c->ax_q4[a] = (int32_t)(cur % ps) * 16;
        c->ay_q4[a] = (int32_t)(cur / ps) * 16;
    }
}

/* The arms: runs of flooded pixels along the box border, then a walk out
 * along each (its pixels appended to the flood's list q, *n).  Returns 0
 * when the cluster is to be rejected (an arm at a clipped side, more than
 * 4 arms, the whole border flooded). */
static int sk_arms(fl_skel_t *s, sk_cluster_t *c, uint32_t *q, int32_t *n, int32_t cap,
                   const int32_t off[8])
{
    static const int32_t side_clip[4] = {2, 4, 8, 1};   /* top right bottom left */
    const uint32_t ps = (uint32_t)s->pstride;
    int32_t per = 2 * ((c->bx1 - c->bx0) + (c->by1 - c->by0));
    int32_t p, p0 = -1, x, y, side, sx = 0, sy = 0, cnt = 0, k;
    uint32_t first = 0;
    if (per < 4)
        return 0;
    for (p = 0; p < per && p0 < 0; p++) {
        sk_ring_xy(c, p, &x, &y, &side);
        if (!(s->px[(uint32_t)y * ps + (uint32_t)x] & SK_SEEN))
            p0 = p;
    }
    if (p0 < 0)
        return 0;
    c->n_arms = 0;
    for (k = 1; k <= per; k++) {
        uint32_t i;
        sk_ring_xy(c, (p0 + k) % per, &x, &y, &side);
        i = (uint32_t)y * ps + (uint32_t)x;
        if (s->px[i] & SK_SEEN) {
            if (c->clip & side_clip[side])
                return 0;
            if (cnt == 0)
                first = i;
            sx += x;
            sy += y;
            cnt++;
        } else if (cnt > 0) {
            if (c->n_arms >= 4)
                return 0;
            c->ax_q4[c->n_arms] = c->rx_q4[c->n_arms] = (sx * 16 + cnt / 2) / cnt;
            c->ay_q4[c->n_arms] = c->ry_q4[c->n_arms] = (sy * 16 + cnt / 2) / cnt;
            c->mid[c->n_arms] = first;
            c->n_arms++;
            sx = sy = cnt = 0;
        }
    }
    for (k = 0; k < c->n_arms; k++) {
        sk_arm_walk(s, c, k, q, n, cap, off);
        c->arm[k] = fl_atan2(c->ay_q4[k] - c->cy_q4, c->ax_q4[k] - c->cx_q4);
    }
    return 1;
}

/* 0 when a and b point exactly opposite, up to 32768 (the same way). */
static int32_t sk_bend(fl_angle_t a, fl_angle_t b)
{
    return 32768 - sk_abs((int32_t)fl_angle_sub(a, b));
}

/* Intersection of line a0-a1 with b0-b1 (Q4); 0 when (nearly) parallel. */
static int sk_intersect(const int32_t a[4], const int32_t b[4], int32_t *x, int32_t *y)
{
    int64_t dax = a[2] - a[0], day = a[3] - a[1], dbx = b[2] - b[0], dby = b[3] - b[1];
    int64_t den = dax * dby - day * dbx;
    int64_t num = (int64_t)(b[0] - a[0]) * dby - (int64_t)(b[1] - a[1]) * dbx;
    int64_t len2 = dax * dax + day * day;
    if (den == 0 || len2 == 0)
        return 0;
    /* parallel within about 10 degrees: |den| < 0.17 |da| |db| */
    if (den * den * 36 < len2 * (dbx * dbx + dby * dby))
        return 0;
    *x = a[0] + (int32_t)(dax * num / den);
    *y = a[1] + (int32_t)(day * num / den);
    return 1;
}

/* Foot of (px, py) on line a0-a1 (Q4); 0 when the line is a point. */
static int sk_project(const int32_t a[4], int32_t *px, int32_t *py)
{
    int64_t dx = a[2] - a[0], dy = a[3] - a[1];
    int64_t len2 = dx * dx + dy * dy;
    int64_t t = (int64_t)(*px - a[0]) * dx + (int64_t)(*py - a[1]) * dy;
    if (len2 == 0)
        return 0;
    *px = a[0] + (int32_t)(dx * t / len2);
    *py = a[1] + (int32_t)(dy * t / len2);
    return 1;
}

/* Kind, confidence and position of a cluster with its arms; 0: rejected. */
static int sk_classify(const fl_skel_t *s, sk_cluster_t *c, fl_skel_crossing_t *out)
{
    int32_t i, j, x = c->cx_q4, y = c->cy_q4, conf, bend;
    memset(out, 0, sizeof *out);
    for (i = 1; i < c->n_arms; i++) {    /* ascending angles */
        for (j = i; j > 0 && c->arm[j - 1] > c->arm[j]; j--) {
            fl_angle_t ta = c->arm[j];
            int32_t tx = c->ax_q4[j], ty = c->ay_q4[j], ux = c->rx_q4[j], uy = c->ry_q4[j];
            c->arm[j] = c->arm[j - 1]; c->ax_q4[j] = c->ax_q4[j - 1]; c->ay_q4[j] = c->ay_q4[j - 1];
            c->rx_q4[j] = c->rx_q4[j - 1]; c->ry_q4[j] = c->ry_q4[j - 1];
            c->arm[j - 1] = ta; c->ax_q4[j - 1] = tx; c->ay_q4[j - 1] = ty;
            c->rx_q4[j - 1] = ux; c->ry_q4[j - 1] = uy;
        }
    }
    if (c->n_arms == 4) {
        int32_t la[4] = {c->ax_q4[0], c->ay_q4[0], c->ax_q4[2], c->ay_q4[2]};
        int32_t lb[4] = {c->ax_q4[1], c->ay_q4[1], c->ax_q4[3], c->ay_q4[3]};
        bend = sk_bend(c->arm[0], c->arm[2]) + sk_bend(c->arm[1], c->arm[3]);
        if (!sk_intersect(la, lb, &x, &y)) {
            x = c->cx_q4;
            y = c->cy_q4;
        }
    } else if (c->n_arms == 3) {
        int32_t best = 0, b;
        bend = 65536;
        for (i = 0; i < 3; i++) {
            b = sk_bend(c->arm[i], c->arm[(i + 1) % 3]);
            if (b < bend) {
                bend = b;
                best = i;
            }
        }
        {   /* the bar's line meets the stem's (its border point to the
               end of its walk); without a walk, the node centroid onto
               the bar */
            int32_t k = (best + 1) % 3, st = (best + 2) % 3;
            int32_t la[4] = {c->ax_q4[best], c->ay_q4[best], c->ax_q4[k], c->ay_q4[k]};
            int32_t lb[4] = {c->rx_q4[st], c->ry_q4[st], c->ax_q4[st], c->ay_q4[st]};
            if (!sk_intersect(la, lb, &x, &y)) {
                x = c->cx_q4;
                y = c->cy_q4;
                (void)sk_project(la, &x, &y);
            }
        }
    } else if (c->n_arms == 2) {
        bend = sk_bend(c->arm[0], c->arm[1]);
        if (!s->params.report_l || bend < FL_ANGLE_45 * 2 / 3)   /* < 30 deg: a line */
            return 0;
        bend = sk_max(0, FL_ANGLE_90 - bend);   /* confidence: a right angle best */
    } else {
        return 0;
    }
    /* stay within the node box grown by one pixel */
    x = sk_max((c->x0 - 1) * 16, sk_min((c->x1 + 1) * 16, x));
    y = sk_max((c->y0 - 1) * 16, sk_min((c->y1 + 1) * 16, y));
    for (i = 0; i < c->n_arms; i++)    /* directions from the position found */
        c->arm[i] = fl_atan2(c->ay_q4[i] - y, c->ax_q4[i] - x);
    for (i = 1; i < c->n_arms; i++)
        for (j = i; j > 0 && c->arm[j - 1] > c->arm[j]; j--) {
            fl_angle_t ta = c->arm[j];
            c->arm[j] = c->arm[j - 1];
            c->arm[j - 1] = ta;
        }
    conf = 255 - (int32_t)((int64_t)bend * 255 / FL_ANGLE_45);
    out->kind = (uint8_t)c->n_arms;
    out->n_nodes = (uint8_t)sk_min(c->n, 255);
    out->confidence = (uint8_t)sk_max(0, sk_min(255, conf));
    out->x_q4 = x - 16;   /* working -> mask coordinates */
    out->y_q4 = y - 16;
    for (i = 0; i < c->n_arms; i++)
        out->arm[i] = c->arm[i];
    return 1;
}

/* Node box, centroid and flood box of the cluster rooted at root. */
static void sk_cluster_box(fl_skel_t *s, uint16_t root, sk_cluster_t *c)
{
    int32_t k, sx = 0, sy = 0, a = s->params.arm_px;
    memset(c, 0, sizeof *c);
    c->x0 = c->y0 = INT32_MAX;
    c->x1 = c->y1 = -1;
    for (k = root; k < s->n_nodes; k++) {
        int32_t x, y;
        if (sk_find(s, (uint16_t)k) != root)
            continue;
        x = (int32_t)(s->node[k] & 0xFFFFu);
        y = (int32_t)(s->node[k] >> 16);
        c->x0 = sk_min(c->x0, x); c->x1 = sk_max(c->x1, x);
        c->y0 = sk_min(c->y0, y); c->y1 = sk_max(c->y1, y);
        sx += x;
        sy += y;
        c->n++;
    }
    c->cx_q4 = (sx * 16 + c->n / 2) / c->n;
    c->cy_q4 = (sy * 16 + c->n / 2) / c->n;
    c->bx0 = sk_max(1, c->x0 - a);
    c->by0 = sk_max(1, c->y0 - a);
    c->bx1 = sk_min(s->width, c->x1 + a);
    c->by1 = sk_min(s->height, c->y1 + a);
    c->clip = (c->bx0 != c->x0 - a) | (c->by0 != c->y0 - a) << 1 |
              (c->bx1 != c->x1 + a) << 2 | (c->by1 != c->y1 + a) << 3;
}

/* Clear the flood flags of q[0 .. n). */
static void sk_unflag(fl_skel_t *s, const uint32_t *q, int32_t n)
{
    int32_t f;
    for (f = 0; f < n; f++)
        s->px[q[f]] = (uint8_t)(s->px[q[f]] & ~SK_SEEN);
}

/* Join the clusters whose floods reach each other's node pixels: nodes
 * linked by a skeleton path inside the grown box are one crossing (the
 * piece between them is shorter than an arm).  Passes until none joins,
 * at most SK_JOIN_PASSES.  Returns the joins. */
static int32_t sk_join(fl_skel_t *s, const int32_t off[8])
{
    const uint32_t ps = (uint32_t)s->pstride;
    uint32_t *q = s->contour + s->n_contour;
    int32_t pass, k, joins = 0;
    for (pass = 0; pass < SK_JOIN_PASSES; pass++) {
        int32_t before = joins;
        for (k = 0; k < s->n_nodes; k++) {
            sk_cluster_t c;
            int32_t n, f, m;
            if (sk_find(s, (uint16_t)k) != (uint16_t)k)
                continue;
            sk_cluster_box(s, (uint16_t)k, &c);
            if (c.x1 - c.x0 >= SK_MAX_SPAN || c.y1 - c.y0 >= SK_MAX_SPAN)
                continue;
            n = sk_flood(s, (uint16_t)k, &c, off);
            for (f = 0; f < n; f++) {
                if (!(s->px[q[f]] & SK_NODE))
                    continue;
                for (m = 0; m < s->n_nodes; m++) {
                    uint32_t i = (s->node[m] >> 16) * ps + (s->node[m] & 0xFFFFu);
                    uint16_t r = sk_find(s, (uint16_t)m);
                    if (i == q[f] && r != (uint16_t)k) {
                        if (r < (uint16_t)k)
                            s->parent[k] = r;
                        else
                            s->parent[r] = (uint16_t)k;
                        joins++;
                        break;
                    }
                }
                if (sk_find(s, (uint16_t)k) != (uint16_t)k)
                    break;    /* k joined an earlier cluster */
            }
            if (n > 0)
                sk_unflag(s, q, n);
        }
        if (joins == before)
            break;
    }
    return joins;
}

static void sk_crossings(fl_skel_t *s, const int32_t off[8])
{
    int32_t k;
    for (k = 0; k < s->n_nodes; k++) {
        sk_cluster_t c;
        fl_skel_crossing_t out;
        int32_t n, ok;
        if (sk_find(s, (uint16_t)k) != (uint16_t)k)
            continue;
        sk_cluster_box(s, (uint16_t)k, &c);
        if (c.x1 - c.x0 >= SK_MAX_SPAN || c.y1 - c.y0 >= SK_MAX_SPAN) {
            s->rejected++;
            continue;
        }
        n = sk_flood(s, (uint16_t)k, &c, off);
        if (n < 0) {
            s->rejected++;
            continue;
        }
        ok = sk_arms(s, &c, s->contour + s->n_contour, &n, FL_SKEL_MAX_CONTOUR - s->n_contour, off);
        sk_unflag(s, s->contour + s->n_contour, n);
        if (!ok || !sk_classify(s, &c, &out)) {
            s->rejected++;
            continue;
        }
        if (s->n_crossings < FL_SKEL_MAX_CROSSINGS)
            s->crossing[s->n_crossings++] = out;
        else
            s->crossings_dropped++;
    }
}

/* n_points distinct skeleton pixels, a deterministic function of seed. */
static void sk_sample(fl_skel_t *s, uint32_t seed)
{
    const uint32_t ps = (uint32_t)s->pstride;
    uint32_t r = seed * 2654435761u ^ 0x6d2b79f5u;
    int32_t k, n = sk_min(s->params.n_points, s->n_contour);
    if (r == 0)
        r = 0x6d2b79f5u;
    for (k = 0; k < n; k++) {
        uint32_t j, t;
        r ^= r << 13;
        r ^= r >> 17;
        r ^= r << 5;
        j = (uint32_t)k + r % (uint32_t)(s->n_contour - k);
        t = s->contour[j];
        s->contour[j] = s->contour[k];
        s->contour[k] = t;
        s->point[k].x = (int16_t)(t % ps - 1u);
        s->point[k].y = (int16_t)(t / ps - 1u);
    }
    s->n_points = n;
}

void fl_skel_find_crossings(fl_skel_t *s, uint32_t seed)
{
    int32_t off[8];
    sk_offsets(s->pstride, off);
    sk_prune(s, off);
    s->n_skeleton = s->n_contour;
    sk_nodes(s);
    sk_cluster(s);
    (void)sk_join(s, off);
    sk_crossings(s, off);
    sk_sample(s, seed);
}

/*
 * src/vision/corners_feat.c - seed 004's colour filter, corner labels,
 * pairing into C / T-field / T-net and the nets (corners.h).
 * Memory: the caller's fl_corners_t; stack < 500 B with callees (make stack).
 */
#include "corners_int.h"

#include <string.h>

/* Colour class of pixel (x, y) by the scanner's table: RGB frames through
 * the RGB table, the others through Y, Cb, Cr (as fl_scan_frame does). */
static fl_color_class_t cn_class(const fl_image_t *img, const fl_color_table_t *colors, int32_t x,
                                 int32_t y)
{
    uint8_t px[3];
    if (img->format == FL_FMT_RGB888) {
        const uint8_t *p = img->plane[0] + y * img->stride[0] + 3 * x;
        return fl_color_class_rgb(colors, p[0], p[1], p[2]);
    }
    fl_image_ycbcr_at(img, x, y, px);
    return fl_color_class_ycbcr(colors, px[0], px[1], px[2]);
}

/* Pixels that mm millimetres span at the ground range of pixel (x, y):
 * focal * mm / range; 0 without a camera or a ground point.  (Six
 * arguments at most: a seventh goes on the stack by push on x86-64, which
 * `make stack` cannot bound statically.) */
static int32_t cn_px_raw(const fl_camera_t *camera, int32_t x, int32_t y, int32_t mm)
{
    fl_point_t g;
    int32_t range;
    if (!camera || mm <= 0 || !fl_camera_pixel_to_ground(camera, x * 16, y * 16, &g))
        return 0;
    range = (int32_t)fl_hypot(g.x_mm, g.y_mm);
    if (range < 1)
        range = 1;
    return (int32_t)(((int64_t)camera->model.focal_q4 * mm / range + 8) >> 4);
}

/* cn_px_raw limited to lo..hi; dflt when it is 0 (no camera or ground). */
static int32_t cn_px_lim(int32_t raw, int32_t dflt, int32_t lo, int32_t hi)
{
    if (raw == 0)
        return dflt;
    return raw < lo ? lo : raw > hi ? hi : raw;
}

/* Seed 004's label from the window's white count (of area pixels) and
 * the net samples. */
static int32_t cn_label_of(const fl_corners_params_t *p, int32_t nw, int32_t area, int32_t nn)
{
    if (nw * 100 < p->closed_white_pct * area)
        return FL_CORNER_OPEN;
    return p->net_r > 0 && nn >= p->min_net ? FL_CORNER_NET_CLOSED : FL_CORNER_CLOSED;
}

/* With a camera: does the net seen above corner k stand at it?  (fx, fy)
 * is the lowest net sample; the net's foot is found below it pixel by
 * pixel (the samples are up to net_mm / 10 apart) and projected to the
 * ground.  A T at the net is a box line meeting the goal line 200 mm
 * beside a post, so the foot lies within net_mm of the corner's ground
 * point; a net behind the corner (the far goal above the centre circle's
 * crossings or the halfway line's T's, seen along the field) has its
 * foot metres beyond it and made T-nets of T-fields (eval-detect: 23 of
 * the 117 detections).  A foot without a ground point (at or above the
 * horizon) is not at the corner. */
static bool cn_net_near(const fl_corners_params_t *p, const fl_image_t *img, const fl_camera_t *camera,
                        const fl_corner_t *k, int32_t fx, int32_t fy)
{
    fl_point_t gk, gf;
    while (fy + 1 < k->y) {
        const fl_color_t col = fl_beacon_pixel_color(&p->net, img, fx, fy + 1);
        if (col != FL_COLOR_YELLOW && col != FL_COLOR_SKYBLUE)
            break;
        fy++;
    }
    if (!fl_camera_pixel_to_ground(camera, k->x * 16, k->y * 16, &gk) ||
        !fl_camera_pixel_to_ground(camera, fx * 16, fy * 16 + 8, &gf))
        return false;
    return (int32_t)fl_hypot(gf.x_mm - gk.x_mm, gf.y_mm - gk.y_mm) <= p->net_mm;
}

bool fl_corners_int_color_label(const fl_corners_t *c, const fl_image_t *img, const fl_color_table_t *colors,
                    const fl_camera_t *camera, fl_corner_t *k)
{
    const fl_corners_params_t *p = &c->params;
    /* radius: label_r, or with a camera label_mm at the corner's range
     * when that is more (at most 4: 9 x 9) */
    const int32_t r = cn_px_lim(cn_px_raw(camera, k->x, k->y, p->label_mm), p->label_r, p->label_r, 4);
    int32_t dx, dy, nw = 0, ng = 0, nn = 0, area = 0;
    for (dy = -r; dy <= r; dy++)
        for (dx = -r; dx <= r; dx++) {
            const int32_t x = k->x + dx, y = k->y + dy;
            fl_color_class_t cl;
            if (x < 0 || y < 0 || x >= img->width || y >= img->height)
                continue;
            area++;
            cl = cn_class(img, colors, x, y);
            nw += cl == FL_CLASS_WHITE;
            ng += cl == FL_CLASS_GREEN;
        }
    k->n_white = (uint8_t)nw;
    k->n_green = (uint8_t)ng;
    k->n_area = (uint8_t)area;
    if (nw < p->min_white || ng < p->min_green)
        return false;
    if (p->net_r > 0) {
        /* samples of the rows above the corner, within net_r px (with a
         * camera: net_mm at the corner's range), about 20 x 10 of them */
        const int32_t nr = cn_px_lim(cn_px_raw(camera, k->x, k->y, p->net_mm), p->net_r, 4, 64);
        const int32_t step = nr >= 20 ? nr / 10 : 2;
        int32_t fx = 0, fy = 0;   /* lowest net sample: near the net's foot */
        for (dy = -nr; dy < 0; dy += step)
            for (dx = -nr; dx <= nr; dx += step) {
                const fl_color_t col = fl_beacon_pixel_color(&p->net, img, k->x + dx, k->y + dy);
                if (col == FL_COLOR_YELLOW || col == FL_COLOR_SKYBLUE) {
                    nn++;
                    fx = k->x + dx;
                    fy = k->y + dy;
                }
            }
        if (nn > 0 && camera && !cn_net_near(p, img, camera, k, fx, fy))
            nn = 0;
        k->n_net = (uint8_t)(nn > 255 ? 255 : nn);
    }
    k->label = (uint8_t)cn_label_of(p, nw, area, nn);
    return true;
}

/* Feature type of a pair of labels; 0 when they make none. */
static int32_t cn_pair_type(int32_t la, int32_t lb)
{
    if (la > lb) {
        const int32_t t = la;
        la = lb;
        lb = t;
    }
    if (la == FL_CORNER_OPEN)
        return lb == FL_CORNER_OPEN ? 0 : FL_CFEAT_C;
    if (la == FL_CORNER_CLOSED && lb == FL_CORNER_CLOSED)
        return FL_CFEAT_T_FIELD;
    return FL_CFEAT_T_NET;
}

/* The view a pair is typed in. */
typedef struct {
    const fl_image_t *img;
    const fl_color_table_t *colors;
    const fl_camera_t *camera;
} cn_view_t;

/* label_mode 3: how many white lines leave the pair's joint?  On the
 * ground, around the midpoint M of the two corners, CN_RING_N probes on a
 * circle of CN_RING_MM (60 mm: 2.4 line widths of 25 mm, outside the
 * joint's square, whose half diagonal is 18 mm; a line crosses the
 * circle over 24 degrees, more than the probes' 15 degree spacing), each
 * projected into the image and classified; the white runs around the
 * circle are the arms.  An L (C) has 2, at 90 degrees on the ground; a T
 * 3; an X 4 (the centre circle's crossings; a pair of its opposite
 * corners has no line between its corners and looked like an L to a
 * test across the pair).  Two arms in line (150..210 degrees apart) are
 * a straight line: two corners of one line (a dent, noise) and no
 * feature.  Geometry on the ground, independent of how wide the line
 * looks: the white counts of the label windows (label_mode 1) compared a
 * thin line's corners with a thick one's across the view and typed
 * about half the T-fields and X's as C (eval-detect, EVC_DEBUG).
 * A pair of at most 2 arms is looked at again on a circle of
 * CN_RING2_MM (100 mm) and typed a T when that shows 3 or more: beyond
 * 1.5 m the 60 mm circle spans only a few pixels of depth and an X's or
 * a T's arm along the view falls between its probes (eval-detect: C
 * precision 0.60 -> 0.80, overall 0.77 -> 0.80; 80 and 130 mm: 0.79).
 * Fewer than 2 arms (a line's end, a white blob such as the wall's foot,
 * or a line too thin for the probes) make no feature either: eval-detect
 * precision 0.64 (95 detections) when they fell back to label_mode 1,
 * 0.75 (75) without, recall 0.43 and 0.39.  Ring radius 45 mm: precision
 * 0.66, recall 0.37; 80 mm: 0.69, 0.39.  Returns the arms (0..CN_RING_N /
 * 2), CN_ARMS_STRAIGHT for a straight line, -1 when a corner has no
 * ground point. */
#define CN_RING_N 24
#define CN_RING_MM 60
#define CN_RING2_MM 100
#define CN_ARMS_STRAIGHT 100
static int32_t cn_shape_arms(const cn_view_t *v, const fl_corner_t *a, const fl_corner_t *b,
                             int32_t ring_mm)
{
    static const int16_t cs[CN_RING_N] = { 256,  247,  222,  181,  128,  66,   0,    -66,
                                           -128, -181, -222, -247, -256, -247, -222, -181,
                                           -128, -66,  0,    66,   128,  181,  222,  247 };
    fl_point_t ga, gb;
    uint8_t white[CN_RING_N];
    int32_t k, arms = 0, start[2] = { 0, 0 }, len[2] = { 0, 0 };
    if (!fl_camera_pixel_to_ground(v->camera, a->x * 16, a->y * 16, &ga) ||
        !fl_camera_pixel_to_ground(v->camera, b->x * 16, b->y * 16, &gb))
        return -1;
    for (k = 0; k < CN_RING_N; k++) {
        fl_point_t g;
        int32_t u, w;
        /* sin = cos 90 degrees (6 steps) earlier */
        g.x_mm = (ga.x_mm + gb.x_mm) / 2 + cs[k] * ring_mm / 256;
        g.y_mm = (ga.y_mm + gb.y_mm) / 2 + cs[(k + CN_RING_N - 6) % CN_RING_N] * ring_mm / 256;
        white[k] = 0;
        if (!fl_camera_ground_to_pixel(v->camera, g, &u, &w))
            continue;
        u = (u + 8) / 16;
        w = (w + 8) / 16;
        if (u >= 0 && w >= 0 && u < v->img->width && w < v->img->height)
            white[k] = cn_class(v->img, v->colors, u, w) == FL_CLASS_WHITE;
    }
    /* runs, circularly: start where a white probe follows a dark one */
    for (k = 0; k < CN_RING_N; k++)
        if (white[k] && !white[(k + CN_RING_N - 1) % CN_RING_N]) {
            int32_t n = 0;
            while (n < CN_RING_N && white[(k + n) % CN_RING_N])
                n++;
            if (arms < 2) {
                start[arms] = k;
                len[arms] = n;
            }
            arms++;
        }
    if (arms == 0 && white[0])
        return 1;   /* all white: no arm structure (a blob of white) */
    if (arms == 2) {
        /* twice the centres' distance in steps: 24 = opposite */
        int32_t d2 = (2 * start[1] + len[1]) - (2 * start[0] + len[0]);
        if (d2 < 0)
            d2 = -d2;
        if (d2 > CN_RING_N)
            d2 = 2 * CN_RING_N - d2;
        if (d2 >= CN_RING_N - 4)
            return CN_ARMS_STRAIGHT;
    }
    return arms;
}

/* Feature type of a pair of corners: with label_mode 3 and a camera by
 * the arms on the ground (2: C, 3 or more: a T, T-net when either corner
 * saw the net at it); else by their labels (rel_pct 0), or (rel_pct > 0)
 * relative to each other: C when one has less than rel_pct % of the
 * other's white pixels (that one convex, the other concave), else a T
 * (T-net when either saw the net).  0 when they make none. */
static int32_t cn_pair_type_of(const fl_corners_params_t *p, const cn_view_t *v, const fl_corner_t *a,
                               const fl_corner_t *b)
{
    int32_t lo, hi;
    if (p->label_mode == 3 && v->camera) {   /* by the shape on the ground */
        const bool net = p->net_r > 0 && (a->n_net >= p->min_net || b->n_net >= p->min_net);
        int32_t arms = cn_shape_arms(v, a, b, CN_RING_MM);
        if (arms >= 0 && arms <= 2) {
            const int32_t far = cn_shape_arms(v, a, b, CN_RING2_MM);
            if (far >= 3 && far != CN_ARMS_STRAIGHT)
                arms = far;
        }
        if (arms >= 0) {
            /* the net at the pair (its foot within net_mm: only the box
             * lines meet the goal line there) makes a T-net of 1 or 2
             * arms too: the goal line runs along the net's foot, 1 px thin
             * or out of the image, and its arms are often lost
             * (eval-detect: precision 0.75 -> 0.77, recall 0.39 -> 0.42) */
            if (net && arms >= 1)
                return FL_CFEAT_T_NET;
            if (arms < 2)
                return 0;
            if (arms == CN_ARMS_STRAIGHT)
                return 0;
            return arms == 2 ? FL_CFEAT_C : FL_CFEAT_T_FIELD;
        }
    }
    if (p->label_mode == 2) {   /* by convexity: convex + concave = C */
        if (a->convex == 0 || b->convex == 0 || (a->convex > 0 && b->convex > 0))
            return 0;
        if (a->convex != b->convex)
            return FL_CFEAT_C;
        return p->net_r > 0 && (a->n_net >= p->min_net || b->n_net >= p->min_net) ? FL_CFEAT_T_NET
                                                                                 : FL_CFEAT_T_FIELD;
    }
    if (p->rel_pct == 0 || p->label_mode == 0)
        return cn_pair_type(a->label, b->label);
    /* white fractions, a's and b's, over the common denominator */
    lo = a->n_white * b->n_area;
    hi = b->n_white * a->n_area;
    if (lo > hi) {
        const int32_t t = lo;
        lo = hi;
        hi = t;
    }
    if (lo * 100 < p->rel_pct * hi)
        return FL_CFEAT_C;
    return p->net_r > 0 && (a->n_net >= p->min_net || b->n_net >= p->min_net) ? FL_CFEAT_T_NET
                                                                             : FL_CFEAT_T_FIELD;
}

/* Range and bearing of pixel (u_q4, v_q4) into f (has_ground false when
 * it has no ground point or there is no camera). */
static void cn_ground(fl_cfeat_t *f, const fl_camera_t *camera)
{
    fl_point_t g;
    f->has_ground = false;
    f->range_mm = 0;
    f->bearing = 0;
    if (!camera || !fl_camera_pixel_to_ground(camera, f->u_q4, f->v_q4, &g))
        return;
    f->has_ground = true;
    f->ground = g;
    f->range_mm = (int32_t)fl_hypot(g.x_mm, g.y_mm);
    f->bearing = fl_atan2(g.y_mm, g.x_mm);
}

static fl_cfeat_t *cn_new_feature(fl_corners_t *c)
{
    fl_cfeat_t *f;
    if (c->n_features >= FL_CORNERS_MAX_FEATURES) {
        c->features_dropped++;
        return NULL;
    }
    f = &c->feature[c->n_features++];
    memset(f, 0, sizeof *f);
    f->a = -1;
    f->b = -1;
    return f;
}

/* White pixels of the 3 x 3 square around (x, y): the two corners of a
 * C (an L's outer and inner corner) have the L's joint between them, the
 * two of a T the stem's end: white; two corners of different lines have
 * carpet there. */
static int32_t cn_mid_white(const fl_image_t *img, const fl_color_table_t *colors, int32_t x,
                            int32_t y)
{
    int32_t dx, dy, n = 0;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++)
            if (x + dx >= 0 && y + dy >= 0 && x + dx < img->width && y + dy < img->height)
                n += cn_class(img, colors, x + dx, y + dy) == FL_CLASS_WHITE;
    return n;
}

/* A chosen pair: corners ia, ib, their squared distance and type. */
typedef struct {
    int32_t ia, ib, d2, type;
} cn_pick_t;

/* The strongest unpaired pair that makes a feature (T-field and T-net
 * only when t_only), within the pair distance of the first corner
 * (pair_lim, px); false when none is left.  The type is asked last (the
 * shape test projects 20 probes). */
static bool cn_closest_pair(const fl_corners_t *c, const cn_view_t *v, bool t_only, cn_pick_t *pk)
{
    int32_t i, j, best = -1;
    uint32_t best_key = 0;
    for (i = 0; i < c->n_corners; i++) {
        const fl_corner_t *a = &c->corner[i];
        if (a->paired)
            continue;
        for (j = i + 1; j < c->n_corners; j++) {
            const fl_corner_t *b = &c->corner[j];
            const int32_t dx = b->x - a->x, dy = b->y - a->y, dd = dx * dx + dy * dy;
            int32_t ty;
            uint32_t key;
            if (b->paired || dd > a->pair_lim * a->pair_lim)
                continue;
            /* order: the pair's weaker response, largest first (a weak
             * duplicate maximum beside a strong corner pairs last);
             * ties: nearest, then first */
            key = a->response < b->response ? a->response : b->response;
            if (best >= 0 && (key < best_key || (key == best_key && dd >= best)))
                continue;
            if (cn_mid_white(v->img, v->colors, (a->x + b->x) / 2, (a->y + b->y) / 2) <
                c->params.min_mid_white)
                continue;
            ty = cn_pair_type_of(&c->params, v, a, b);
            if (ty == 0 || (t_only && ty == FL_CFEAT_C))
                continue;
            best = dd;
            best_key = key;
            pk->ia = i;
            pk->ib = j;
            pk->type = ty;
        }
    }
    pk->d2 = best;
    return best >= 0;
}

/* One net feature per goal colour from the beacon stage's posts. */
static void cn_nets(fl_corners_t *c, const fl_beacon_t *beacons)
{
    static const fl_color_t col[2] = { FL_COLOR_YELLOW, FL_COLOR_SKYBLUE };
    int32_t k, i;
    for (k = 0; k < 2; k++) {
        int64_t gx = 0, gy = 0, u = 0, v = 0;
        int32_t n = 0, conf = 0;
        fl_cfeat_t *f;
        for (i = 0; i < beacons->n && i < FL_BEACON_MAX_FOUND; i++) {
            const fl_beacon_found_t *b = &beacons->found[i];
            if (b->kind != FL_LM_POST || b->color != col[k] || b->range_mm <= 0)
                continue;
            gx += b->ground.x_mm;
            gy += b->ground.y_mm;
            u += b->u_q4;
            v += b->v_q4;
            conf = b->confidence > conf ? b->confidence : conf;
            n++;
        }
        if (n == 0 || conf < c->params.min_confidence)
            continue;
        f = cn_new_feature(c);
        if (!f)
            return;
        f->type = (uint8_t)(k == 0 ? FL_CFEAT_NET_YELLOW : FL_CFEAT_NET_SKYBLUE);
        f->confidence = (uint8_t)conf;
        f->u_q4 = (int32_t)(u / n);
        f->v_q4 = (int32_t)(v / n);
        f->has_ground = true;
        f->ground.x_mm = (int32_t)(gx / n);
        f->ground.y_mm = (int32_t)(gy / n);
        f->range_mm = (int32_t)fl_hypot(f->ground.x_mm, f->ground.y_mm);
        f->bearing = fl_atan2(f->ground.y_mm, f->ground.x_mm);
    }
}

/* Feature of corners ia and ib (d2: their squared distance). */
static void cn_add_pair(fl_corners_t *c, const fl_camera_t *camera, const cn_pick_t *pk)
{
    const int32_t ia = pk->ia, ib = pk->ib, d2 = pk->d2;
    fl_corner_t *a = &c->corner[ia], *b = &c->corner[ib];
    int32_t conf = a->var < b->var ? a->var : b->var;
    fl_cfeat_t *f;
    a->paired = 1;
    b->paired = 1;
    if (4 * d2 > a->pair_lim * a->pair_lim)
        conf /= 2;
    if (conf < c->params.min_confidence)
        return;
    f = cn_new_feature(c);
    if (!f)
        return;
    f->type = (uint8_t)pk->type;
    if (c->params.label_mode > 0 && (c->params.rel_pct > 0 || c->params.label_mode >= 2)) {
        /* the labels the pair says */
        if (f->type == FL_CFEAT_C) {
            fl_corner_t *lo = c->params.label_mode == 2 ? (a->convex > 0 ? a : b)
                              : a->n_white * b->n_area < b->n_white * a->n_area ? a : b;
            a->label = FL_CORNER_CLOSED;
            b->label = FL_CORNER_CLOSED;
            lo->label = FL_CORNER_OPEN;
        } else {
            a->label = (uint8_t)(a->n_net >= c->params.min_net && c->params.net_r > 0 ? FL_CORNER_NET_CLOSED
                                                                                   : FL_CORNER_CLOSED);
            b->label = (uint8_t)(b->n_net >= c->params.min_net && c->params.net_r > 0 ? FL_CORNER_NET_CLOSED
                                                                                   : FL_CORNER_CLOSED);
        }
    }
    f->confidence = (uint8_t)conf;
    f->a = (int16_t)ia;
    f->b = (int16_t)ib;
    f->u_q4 = (a->x + b->x) * 8;   /* midpoint, Q4: (xa + xb) / 2 * 16 */
    f->v_q4 = (a->y + b->y) * 8;
    cn_ground(f, camera);
}

void fl_corners_int_pair(fl_corners_t *c, const fl_image_t *img, const fl_color_table_t *colors,
             const fl_camera_t *camera, const fl_beacon_t *beacons)
{
    const cn_view_t v = { img, colors, camera };
    cn_pick_t pk = { 0, 0, 0, 0 };
    int32_t guard = 0, i, pass;
    for (i = 0; i < c->n_corners; i++)
        c->corner[i].pair_lim = (uint8_t)cn_px_lim(
            cn_px_raw(camera, c->corner[i].x, c->corner[i].y, c->params.pair_mm),
            c->params.pair_px, c->params.pair_px, 64);
    for (pass = c->params.t_first ? 0 : 1; pass < 2; pass++)
        while (guard++ < 2 * FL_CORNERS_MAX_CORNERS &&
               cn_closest_pair(c, &v, pass == 0, &pk))
            cn_add_pair(c, camera, &pk);
    if (beacons)
        cn_nets(c, beacons);
}

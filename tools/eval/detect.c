/*
 * tools/eval/detect.c - host helpers around fl_vision_frame (see detect.h).
 */
#include "eval/detect.h"
#include "io/textfile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Color parameter override for experiments (eval-detect --white-s). */
int det_white_s_hi = -1;

int det_ctx_init_params(det_ctx_t *c, const fl_vision_params_t *p)
{
    fl_color_params_t cp;
    memset(c, 0, sizeof *c);
    c->colors = malloc(sizeof *c->colors);
    c->vis = malloc(sizeof *c->vis);
    if (!c->colors || !c->vis) {
        det_ctx_free(c);
        return -1;
    }
    fl_color_params_default(&cp);
    if (det_white_s_hi >= 0) {
        cp.white.s_hi = (uint8_t)det_white_s_hi;
        cp.green.s_lo = (uint8_t)(det_white_s_hi + 1);
    }
    if (fl_color_init(c->colors, &cp) != FL_OK || fl_vision_init(c->vis, p) != FL_OK) {
        det_ctx_free(c);
        return -1;
    }
    c->params = *p;
    c->colors_built = COLORS_DEFAULT;
    return 0;
}

int det_ctx_init(det_ctx_t *c)
{
    fl_vision_params_t p;
    fl_vision_params_default(&p);
    return det_ctx_init_params(c, &p);
}

void det_ctx_free(det_ctx_t *c)
{
    free(c->colors);
    free(c->vis);
    c->colors = NULL;
    c->vis = NULL;
}

int det_colors_load(const char *path, fl_color_params_t *p, char *err, int err_len)
{
    char text[FL_COLOR_TEXT_MAX + 1];
    size_t n;
    int32_t line = 0;
    const char *why = "";
    fl_color_params_default(p);
    if (tf_read(path, text, sizeof text, &n, err, err_len) != 0)
        return -1;
    if (fl_color_params_parse(text, n, p, &line, &why) == FL_OK)
        return 0;
    tf_parse_err(err, err_len, path, line, why);
    return -1;
}

/* The explanation of each key of the colour text, in fl_color_params_format's
 * order (color.h has the measurements behind the defaults). */
static const char *const det_colors_help[][2] = {
    {"fieldloc-colors",
     "# fieldloc colour classes: `fieldloc detect|scan|localize --colors FILE`.\n"
     "# HSV in OpenCV's 8-bit convention: hue 0..179 (2 degrees per unit, green\n"
     "# 60, yellow 30), saturation and value 0..255.  A box is H_LO H_HI S_LO\n"
     "# S_HI V_LO V_HI, bounds included; H_LO > H_HI wraps through red (0).\n"
     "# A pixel takes the first box that holds it, in the order yellow, green,\n"
     "# white; none: other.  Keys left out keep the built-in defaults.\n"},
    {"green",
     "\n# field carpet.  The hue range is re-centred every frame on the measured\n"
     "# carpet (by up to adapt_max_hue); S_LO also admits the pale far carpet.\n"},
    {"green_sat_ref",
     "# carpet saturation the green box was made for: a paler carpet lowers\n"
     "# green S_LO in proportion (never below half).  1..255\n"},
    {"white",
     "\n# line candidates: grey and bright.  S_HI should meet green S_LO (the\n"
     "# boxes touch at S 48 / 49); V_LO admits lines at half the light.\n"},
    {"white_contrast_pct",
     "# a white run must be (100 + this) % as bright (luma) as the green next\n"
     "# to it.  0..200\n"},
    {"white_line_pct",
     "# line brightness / field brightness, %: on bright frames white S_HI is\n"
     "# capped where the clipped line edges turn grey.  0 (off) or 100..255\n"},
    {"yellow",
     "\n# goal posts (coloured goals).  Shifted with the green hue.\n"},
    {"adapt_max_hue",
     "\n# largest hue re-centring of green and yellow, hue units (0: never).\n"
     "# 0..30\n"},
    {"field_auto",
     "\n# 1: the boxes above are relative to the carpet below (field_hue,\n"
     "# field_val, green_sat_ref) and follow it frame by frame; what\n"
     "# `fieldloc calibrate-colors` writes.  0: fixed boxes.  0..1\n"},
    {"field_hue", "# carpet hue the boxes were made for.  0..179\n"},
    {"field_val", "# carpet median V (brightness) they were made for.  1..255\n"},
    {"auto_margin",
     "# hue units added on each side of the measured carpet hue spread when\n"
     "# the boxes are derived from a frame (--colors auto).  0..30\n"},
    {"auto_shadow_pct",
     "# green V_LO as % of the carpet's darkest V (hard shadows).  10..100\n"},
    {"auto_yellow",
     "# 1: yellow goals (yellow box kept clear of the carpet hue); 0: white\n"
     "# goals, no yellow class (with field_auto 1).  0..1\n"},
};

size_t det_colors_text(const fl_color_params_t *p, char *buf, size_t cap)
{
    char plain[FL_COLOR_TEXT_MAX];
    size_t n = fl_color_params_format(p, plain, sizeof plain), pos = 0, out = 0;
    if (n == 0 || buf == NULL || cap == 0)
        return 0;
    while (pos < n) {
        size_t len = strcspn(plain + pos, "\n"), k, w = strcspn(plain + pos, " \n");
        const char *help = "";
        int m;
        for (k = 0; k < sizeof det_colors_help / sizeof det_colors_help[0]; k++)
            if (strlen(det_colors_help[k][0]) == w &&
                !strncmp(det_colors_help[k][0], plain + pos, w))
                help = det_colors_help[k][1];
        m = snprintf(buf + out, cap - out, "%s%.*s\n", help, (int)len, plain + pos);
        if (m < 0 || (size_t)m >= cap - out) {
            buf[0] = '\0';
            return 0;
        }
        out += (size_t)m;
        pos += len + 1;
    }
    return out;
}

int det_ctx_set_colors(det_ctx_t *c, const fl_color_params_t *p)
{
    return fl_color_init(c->colors, p) == FL_OK ? 0 : -1;
}

fl_status_t det_camera(fl_camera_t *cam, const fl_camera_model_t *m,
                       double head_pitch_rad, double head_yaw_rad)
{
    fl_camera_pose_t pose;
    if (!m)
        return FL_ERR_NULL;
    memset(&pose, 0, sizeof pose);
    pose.neck_height_mm = m->default_neck_height_mm;
    pose.pitch_offset = m->default_pitch_offset;
    pose.head_pitch = fl_angle_from_urad((int32_t)lround(head_pitch_rad * 1e6));
    pose.head_yaw = fl_angle_from_urad((int32_t)lround(head_yaw_rad * 1e6));
    return fl_camera_init(cam, m, &pose);
}

static double det_deg(fl_angle_t a) { return a * (360.0 / 65536.0); }

static void det_add(det_feature_t *out, int *n, int max, char kind, int32_t u_q4,
                    int32_t v_q4, int conf, int32_t range, fl_angle_t bearing,
                    fl_landmark_kind_t lm)
{
    if (*n >= max)
        return;
    out[*n].kind = kind;
    out[*n].u = u_q4 / 16.0;
    out[*n].v = v_q4 / 16.0;
    out[*n].confidence = conf / 255.0;
    out[*n].range_mm = range;
    out[*n].bearing_deg = det_deg(bearing);
    out[*n].lm = lm;
    (*n)++;
}

int det_run(det_ctx_t *c, const fl_image_t *img, const fl_camera_t *cam,
            const fl_field_t *field, fl_obs_list_t *obs, det_feature_t *out,
            int max)
{
    fl_obs_list_t local;
    const fl_vision_t *v = c->vis;
    int n = 0, i;
    if (c->colors_each != NULL) {
        colors_opt_t o = *c->colors_each;
        colors_opt_resolve(&o, field, NULL);
        if (o.mode == COLORS_AUTO || (int)o.mode != c->colors_built) {
            if (colors_opt_setup(&o, c->colors, field, img, cam, NULL) < 0)
                return 0;
            c->colors_built = (int)o.mode;
        }
    }
    fl_vision_frame(c->vis, c->colors, img, cam, field, obs ? obs : &local);
    for (i = 0; i < v->crossings.n; i++) {
        const fl_crossing_t *x = &v->crossings.c[i];
        char k = x->kind == FL_LM_L ? 'L' : x->kind == FL_LM_T ? 'T' : 'X';
        if (x->confidence < c->params.min_confidence)
            continue;
        det_add(out, &n, max, k, x->u_q4, x->v_q4, x->confidence, x->range_mm,
                x->bearing, x->kind);
    }
    for (i = 0; i < v->posts.n; i++) {
        const fl_post_t *p = &v->posts.post[i];
        if (p->confidence < c->params.min_confidence)
            continue;
        if (p->foot_visible)
            det_add(out, &n, max, 'G', p->foot_u_q4, p->foot_v_q4, p->confidence,
                    p->range_mm, p->bearing, FL_LM_POST);
        if (p->top_visible)
            det_add(out, &n, max, 'U', p->top_u_q4, p->top_v_q4, p->confidence,
                    p->range_mm, p->bearing, FL_LM_POST);
    }
    if (v->circle.found && v->circle.has_pixel &&
        v->circle.confidence >= c->params.min_confidence && v->circle.u_q4 >= -8 &&
        v->circle.v_q4 >= -8 && v->circle.u_q4 < 16 * img->width - 8 &&
        v->circle.v_q4 < 16 * img->height - 8)
        det_add(out, &n, max, 'C', v->circle.u_q4, v->circle.v_q4, v->circle.confidence,
                v->circle.range_mm, v->circle.bearing, FL_LM_CENTRE_CIRCLE);
    return n;
}

/* ---- picture ---------------------------------------------------------------- */

static void px(uint8_t *rgb, int w, int h, int u, int v, const uint8_t *col)
{
    if (u < 0 || v < 0 || u >= w || v >= h)
        return;
    memcpy(rgb + 3 * ((size_t)v * (size_t)w + (size_t)u), col, 3);
}

static void line(uint8_t *rgb, int w, int h, double u0, double v0, double u1,
                 double v1, const uint8_t *col)
{
    double du = u1 - u0, dv = v1 - v0, n = fmax(fabs(du), fabs(dv));
    int k, steps = (int)ceil(n);
    if (steps > 8192)
        steps = 8192;
    for (k = 0; k <= steps; k++) {
        double t = steps ? (double)k / steps : 0;
        px(rgb, w, h, (int)lround(u0 + t * du), (int)lround(v0 + t * dv), col);
    }
}

static void box(uint8_t *rgb, int w, int h, double u, double v, int r, const uint8_t *col)
{
    line(rgb, w, h, u - r, v - r, u + r, v - r, col);
    line(rgb, w, h, u + r, v - r, u + r, v + r, col);
    line(rgb, w, h, u + r, v + r, u - r, v + r, col);
    line(rgb, w, h, u - r, v + r, u - r, v - r, col);
}

static void cross(uint8_t *rgb, int w, int h, double u, double v, int r, const uint8_t *col)
{
    line(rgb, w, h, u - r, v - r, u + r, v + r, col);
    line(rgb, w, h, u - r, v + r, u + r, v - r, col);
}

void det_draw(const det_ctx_t *c, uint8_t *rgb, int width, int height,
              const fl_camera_t *cam, const fl_field_t *field)
{
    static const uint8_t grey[3] = {160, 160, 160}, blue[3] = {40, 80, 255},
                         cyan[3] = {0, 230, 230}, red[3] = {255, 0, 0},
                         orange[3] = {255, 150, 0}, magenta[3] = {255, 0, 255},
                         purple[3] = {150, 60, 255}, green[3] = {0, 255, 0},
                         lime[3] = {200, 255, 0}, white[3] = {255, 255, 255};
    const fl_vision_t *v = c->vis;
    int i;
    for (i = 0; i < v->lines.n_points; i++) {
        static const uint8_t pink[3] = {255, 150, 200}; /* luma points */
        const fl_line_point_t *p = &v->lines.points[i];
        px(rgb, width, height, p->u_q1 / 2, p->v_q1 / 2,
           (p->flags & FL_LINE_POINT_LUMA) ? pink : grey);
    }
    for (i = 0; i < v->lines.n_segments; i++) {
        const fl_segment_t *s = &v->lines.segments[i];
        line(rgb, width, height, s->u0_q4 / 16.0, s->v0_q4 / 16.0, s->u1_q4 / 16.0,
             s->v1_q4 / 16.0, (s->flags & FL_SEG_CIRCLE) ? cyan : blue);
    }
    if (v->circle.found && cam && field) {
        int k;
        double prev_u = 0, prev_v = 0;
        int prev = 0;
        for (k = 0; k <= 72; k++) {
            double a = k * (2 * M_PI / 72);
            fl_point_t g;
            int32_t u, vv;
            g.x_mm = v->circle.centre.x_mm + (int32_t)lround(field->circle_radius_mm * cos(a));
            g.y_mm = v->circle.centre.y_mm + (int32_t)lround(field->circle_radius_mm * sin(a));
            if (fl_camera_ground_to_pixel(cam, g, &u, &vv)) {
                if (prev)
                    line(rgb, width, height, prev_u, prev_v, u / 16.0, vv / 16.0, cyan);
                prev_u = u / 16.0;
                prev_v = vv / 16.0;
                prev = 1;
            } else {
                prev = 0;
            }
        }
        if (v->circle.has_pixel)
            cross(rgb, width, height, v->circle.u_q4 / 16.0, v->circle.v_q4 / 16.0, 5, cyan);
    }
    for (i = 0; i < v->crossings.n; i++) {
        const fl_crossing_t *x = &v->crossings.c[i];
        const uint8_t *col = x->kind == FL_LM_L ? red : x->kind == FL_LM_T ? orange
                           : x->kind == FL_LM_X ? magenta : purple;
        double u = x->u_q4 / 16.0, vv = x->v_q4 / 16.0;
        int a;
        box(rgb, width, height, u, vv, 3, col);
        for (a = 0; a < x->n_arms; a++)
            line(rgb, width, height, u, vv, u + 9 * cos(x->arm[a] * M_PI / 32768),
                 vv + 9 * sin(x->arm[a] * M_PI / 32768), col);
    }
    for (i = 0; i < v->posts.n; i++) {
        const fl_post_t *p = &v->posts.post[i];
        double fu = p->foot_u_q4 / 16.0, fv = p->foot_v_q4 / 16.0, hw = p->width_q4 / 32.0;
        box(rgb, width, height, fu, fv, 3, p->foot_visible ? green : white);
        line(rgb, width, height, fu - hw, fv, fu + hw, fv, green);
        if (p->top_visible)
            box(rgb, width, height, p->top_u_q4 / 16.0, p->top_v_q4 / 16.0, 3, lime);
        if (p->side != FL_SIDE_UNKNOWN)
            line(rgb, width, height, fu, fv - 6, fu + (p->side == FL_SIDE_LEFT ? 8 : -8),
                 fv - 6, lime);
    }
}

uint8_t *det_rgb_copy(const fl_image_t *img)
{
    uint8_t *rgb;
    int u, v;
    if (!img || img->width <= 0 || img->height <= 0)
        return NULL;
    rgb = malloc((size_t)img->width * (size_t)img->height * 3);
    if (!rgb)
        return NULL;
    for (v = 0; v < img->height; v++)
        for (u = 0; u < img->width; u++)
            fl_image_get_rgb(img, u, v, rgb + 3 * ((size_t)v * (size_t)img->width + (size_t)u));
    return rgb;
}

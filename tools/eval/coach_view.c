/*
 * tools/eval/coach_view.c - `fieldloc coach`'s path and its picture
 * (coach_view.h).
 */
#include "eval/coach_view.h"

#include "eval/detect.h"
#include "eval/picture.h"
#include "fieldloc/coach.h"
#include "io/font.h"
#include "world/coach_scene.h"
#include "world/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CV_PI 3.14159265358979323846

int coach_homog_matrix(const fl_homog_t *h, double m[9])
{
    /* fl_homog_t's documented private parts: normalised image
     * (p_q4 - img_c) / 2^img_shift maps through h (homogeneous) to the
     * normalised field (p_mm - fld_c) / 2^fld_shift; pixels are Q4 */
    double is, fs, row_w[3], row_x[3], row_y[3], s, big = 0;
    int k;
    if (!h || !m || h->valid != 1)
        return -1;
    is = ldexp(1.0, h->img_shift);
    fs = ldexp(1.0, h->fld_shift);
    for (k = 0; k < 3; k++) {
        const int32_t *r = h->h + 3 * k;
        double *o = k == 0 ? row_x : k == 1 ? row_y : row_w;
        o[0] = 16.0 * r[0];
        o[1] = 16.0 * r[1];
        o[2] = (double)r[2] * is - (double)r[0] * h->img_c_q4[0] - (double)r[1] * h->img_c_q4[1];
    }
    for (k = 0; k < 3; k++) {
        m[k] = fs * row_x[k] + h->fld_c_mm[0] * row_w[k];
        m[3 + k] = fs * row_y[k] + h->fld_c_mm[1] * row_w[k];
        m[6 + k] = row_w[k];
    }
    for (k = 0; k < 9; k++)
        if (fabs(m[k]) > big)
            big = fabs(m[k]);
    s = fabs(m[8]) > 1e-9 * big ? m[8] : big;
    for (k = 0; k < 9; k++)
        m[k] = m[k] / s + 0.0; /* + 0.0: no "-0" in the printout */
    return 0;
}

static double top_half_x(const fl_field_t *f) { return fl_field_carpet_half_x_mm(f); }
static double top_half_y(const fl_field_t *f) { return fl_field_carpet_half_y_mm(f); }

void coach_topview_px(const fl_field_t *f, int mm_per_px, double x_mm, double y_mm, double *u,
                      double *v)
{
    double s = mm_per_px > 0 ? mm_per_px : COACH_TOP_MM_PER_PX;
    *u = (x_mm + top_half_x(f)) / s;
    *v = (top_half_y(f) - y_mm) / s;
}

static void put_px(host_image_t *im, int u, int v, const uint8_t *c)
{
    if (u >= 0 && v >= 0 && u < im->width && v < im->height)
        memcpy(im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u), c, 3);
}

static void draw_seg(host_image_t *im, double u0, double v0, double u1, double v1, const uint8_t *c)
{
    double n = fmax(fabs(u1 - u0), fabs(v1 - v0));
    int k, steps;
    if (!isfinite(n))
        return;
    steps = n > 16384 ? 16384 : (int)ceil(n);
    for (k = 0; k <= steps; k++) {
        double t = steps ? (double)k / steps : 0;
        put_px(im, (int)lround(u0 + t * (u1 - u0)), (int)lround(v0 + t * (v1 - v0)), c);
    }
}

int coach_topview(const fl_homog_t *h, const host_image_t *img, const fl_field_t *f,
                  int mm_per_px, host_image_t *out)
{
    int s = mm_per_px > 0 ? mm_per_px : COACH_TOP_MM_PER_PX, W, H, u, v;
    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    if (!h || !img || !img->rgb || !f || s > 1000)
        return -1;
    W = (int)(2 * top_half_x(f) / s) + 1;
    H = (int)(2 * top_half_y(f) / s) + 1;
    *out = host_image_new(W, H, 48, 48, 48);
    if (!out->rgb)
        return -1;
    for (v = 0; v < H; v++)
        for (u = 0; u < W; u++) {
            fl_point_t p;
            int32_t iu, iv;
            double fu, fv, au, av;
            int u0, v0, k;
            uint8_t *o = out->rgb + 3 * ((size_t)v * (size_t)W + (size_t)u);
            p.x_mm = (int32_t)lround(-top_half_x(f) + (double)u * s);
            p.y_mm = (int32_t)lround(top_half_y(f) - (double)v * s);
            if (fl_homog_field_to_image(h, p, &iu, &iv) != FL_HOMOG_OK)
                continue;
            fu = iu / 16.0;
            fv = iv / 16.0;
            if (fu < 0 || fv < 0 || fu > img->width - 1 || fv > img->height - 1)
                continue;
            u0 = (int)fu;
            v0 = (int)fv;
            if (u0 > img->width - 2) u0 = img->width - 2;
            if (v0 > img->height - 2) v0 = img->height - 2;
            if (u0 < 0) u0 = 0;
            if (v0 < 0) v0 = 0;
            au = fu - u0;
            av = fv - v0;
            for (k = 0; k < 3; k++) {
                const uint8_t *a = img->rgb + 3 * ((size_t)v0 * (size_t)img->width + (size_t)u0) + k;
                size_t st = 3 * (size_t)img->width;
                double x = (img->width > 1 ? (1 - au) * a[0] + au * a[3] : a[0]);
                double y = img->height > 1 ? ((img->width > 1 ? (1 - au) * a[st] + au * a[st + 3] : a[st])) : x;
                o[k] = (uint8_t)lround((1 - av) * x + av * y);
            }
        }
    return 0;
}

void coach_topview_lines(host_image_t *top, const fl_field_t *f, int mm_per_px)
{
    static const uint8_t white[3] = {255, 255, 255};
    double s = mm_per_px > 0 ? mm_per_px : COACH_TOP_MM_PER_PX;
    int i, k, n;
    if (!top || !top->rgb || !f)
        return;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *l = &f->lines[i];
        double u0, v0, u1, v1;
        coach_topview_px(f, mm_per_px, l->x0_mm, l->y0_mm, &u0, &v0);
        coach_topview_px(f, mm_per_px, l->x1_mm, l->y1_mm, &u1, &v1);
        draw_seg(top, u0, v0, u1, v1, white);
    }
    if (f->circle_radius_mm > 0) {
        double cu, cv, r = f->circle_radius_mm / s;
        coach_topview_px(f, mm_per_px, 0, 0, &cu, &cv);
        n = (int)(2 * CV_PI * r) + 8;
        for (k = 0; k < n; k++) {
            double a = 2 * CV_PI * k / n;
            put_px(top, (int)lround(cu + r * cos(a)), (int)lround(cv + r * sin(a)), white);
        }
    }
}

void coach_mark(host_image_t *im, double u, double v, fl_color_t team)
{
    static const uint8_t red[3] = {255, 40, 40}, blue[3] = {60, 120, 255}, other[3] = {255, 230, 0},
                         dark[3] = {0, 0, 0};
    const uint8_t *c = team == FL_COLOR_RED ? red : team == FL_COLOR_BLUE ? blue : other;
    int k, n = 64;
    double r;
    if (!im || !im->rgb)
        return;
    for (r = 5.0; r <= 8.0; r += 1.0)
        for (k = 0; k < n; k++) {
            double a = 2 * CV_PI * k / n;
            put_px(im, (int)lround(u + r * cos(a)), (int)lround(v + r * sin(a)),
                   r == 5.0 || r == 8.0 ? dark : c);
        }
    draw_seg(im, u - 3, v, u + 3, v, c);
    draw_seg(im, u, v - 3, u, v + 3, c);
}

/* ---- the command --------------------------------------------------------------- */

static const char *team_name(fl_color_t c)
{
    return c == FL_COLOR_RED ? "red" : c == FL_COLOR_BLUE ? "blue" : "?";
}

static int ends_with(const char *s, const char *suf)
{
    size_t a = strlen(s), b = strlen(suf);
    return a >= b && !strcmp(s + a - b, suf);
}

/* The frame (left, feet marked, the field lines through the homography)
 * beside the top view (feet marked), with a caption. */
static int write_picture(const coach_cli_opts_t *o, const fl_field_t *f, const fl_homog_t *h,
                         const host_image_t *img, const fl_coach_result_t *r, const char *caption,
                         char *err, int err_len)
{
    static const uint8_t line_c[3] = {255, 255, 0};
    host_image_t top, frame, both;
    int i, rc;
    if (coach_topview(h, img, f, o->mm_per_px, &top) != 0) {
        snprintf(err, (size_t)err_len, "%s: cannot make the top view", o->out);
        return -1;
    }
    coach_topview_lines(&top, f, o->mm_per_px);
    frame = host_image_new(img->width, img->height, 0, 0, 0);
    if (!frame.rgb) {
        host_image_free(&top);
        return -1;
    }
    memcpy(frame.rgb, img->rgb, 3 * (size_t)img->width * (size_t)img->height);
    /* the model's lines seen through the fit: dotted where they map */
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *l = &f->lines[i];
        int k, n = 200;
        for (k = 0; k <= n; k++) {
            fl_point_t p;
            int32_t u, v;
            if (k & 2)
                continue;
            p.x_mm = l->x0_mm + (int32_t)lround((double)(l->x1_mm - l->x0_mm) * k / n);
            p.y_mm = l->y0_mm + (int32_t)lround((double)(l->y1_mm - l->y0_mm) * k / n);
            if (fl_homog_field_to_image(h, p, &u, &v) == FL_HOMOG_OK)
                put_px(&frame, (int)lround(u / 16.0), (int)lround(v / 16.0), line_c);
        }
    }
    for (i = 0; r && i < r->n_feet; i++) {
        double u, v;
        coach_mark(&frame, r->feet[i].u_q4 / 16.0, r->feet[i].v_q4 / 16.0, r->feet[i].team);
        coach_topview_px(f, o->mm_per_px, r->feet[i].x_mm, r->feet[i].y_mm, &u, &v);
        coach_mark(&top, u, v, r->feet[i].team);
    }
    rc = pic_side_by_side(&frame, &top, 8, &both);
    host_image_free(&frame);
    host_image_free(&top);
    if (rc != 0)
        return -1;
    if (pic_legend_inplace(&both, 0, caption) != 0) {
        host_image_free(&both);
        return -1;
    }
    rc = ends_with(o->out, ".png") ? png_write(o->out, both.rgb, both.width, both.height)
                                   : ppm_write(o->out, both.rgb, both.width, both.height);
    host_image_free(&both);
    if (rc != 0)
        snprintf(err, (size_t)err_len, "%s: cannot write the picture", o->out);
    return rc != 0 ? -1 : 0;
}

/* A frame file in any of the renderer's formats (PPM, or the FLRAW
 * container of YUYV422 / planar frames: what a robot's camera gives): the
 * firmware gets it in its format, the picture an RGB copy.  -1 with the
 * reason in err. */
static int load_frame(const char *what, const char *path, render_frame_t *fr, host_image_t *rgb,
                      char *err, int err_len)
{
    char e[256];
    rgb->rgb = NULL;
    if (render_read_frame(path, fr, e, sizeof e) != 0) {
        snprintf(err, (size_t)err_len, "%s %s", what, e);
        return -1;
    }
    rgb->width = fr->width;
    rgb->height = fr->height;
    rgb->rgb = det_rgb_copy(&fr->view);
    if (!rgb->rgb) {
        snprintf(err, (size_t)err_len, "%s %s: out of memory", what, path);
        render_frame_free(fr);
        return -1;
    }
    return 0;
}

int coach_cli_run(const coach_cli_opts_t *o, FILE *out, char *err, int err_len)
{
    const fl_field_t *f;
    fl_homog_pair_t pairs[COACH_POINTS_MAX];
    const char *names[COACH_POINTS_MAX];
    int n = 0, i, rc = 2;
    fl_homog_t h;
    fl_homog_error_t e;
    fl_homog_status_t hs;
    double m[9];
    host_image_t img = {0, 0, NULL}, bg = {0, 0, NULL};
    render_frame_t img_fr, bg_fr;
    fl_coach_t *c = NULL;
    fl_coach_params_t cp;
    fl_coach_result_t res;
    fl_image_t view;
    fl_status_t st;
    char caption[512];

    if (!o || !out || !err || err_len < 1)
        return 2;
    err[0] = 0;
    if (!o->image || !o->points) {
        snprintf(err, (size_t)err_len, "needs IMAGE.ppm and --points FILE");
        return 2;
    }
    f = fl_field_find(o->field ? o->field : "spl2016");
    if (!f) {
        snprintf(err, (size_t)err_len, "--field: unknown field \"%s\"", o->field);
        return 2;
    }
    memset(&img_fr, 0, sizeof img_fr);
    memset(&bg_fr, 0, sizeof bg_fr);
    if (load_frame("image", o->image, &img_fr, &img, err, err_len) != 0)
        return 2;
    if (coach_points_load(o->points, f, pairs, names, COACH_POINTS_MAX, &n, err, err_len) != 0)
        goto done;
    hs = fl_homog_fit(&h, pairs, (size_t)n);
    fprintf(out, "# fieldloc coach %s (%d x %d), points %s (%d), field %s\n", o->image, img.width,
            img.height, o->points, n, f->name);
    fprintf(out, "homography_status %s\n", fl_homog_status_str(hs));
    if (hs != FL_HOMOG_OK) {
        snprintf(err, (size_t)err_len, "%s: %d points give no homography: %s%s", o->points, n,
                 fl_homog_status_str(hs),
                 hs == FL_HOMOG_TOO_FEW ? " (needs at least 4)"
                 : hs == FL_HOMOG_DEGENERATE ? " (collinear, repeated, or both sides of the horizon)"
                                             : "");
        goto done;
    }
    coach_homog_matrix(&h, m);
    fprintf(out, "homography_image_to_field %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g\n", m[0],
            m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8]);
    fprintf(out, "# (x_mm, y_mm, w) = H (u_px, v_px, 1), pixel centres; field = (x / w, y / w)\n");
    fl_homog_error(&h, pairs, (size_t)n, &e);
    fprintf(out, "reprojection_rms_px %.3f\nreprojection_max_px %.3f\nreprojection_rms_mm %.1f\n"
                 "reprojection_max_mm %.1f\n",
            e.rms_px_q4 / 16.0, e.max_px_q4 / 16.0, e.rms_mm_q4 / 16.0, e.max_mm_q4 / 16.0);
    for (i = 0; i < n; i++) {
        int32_t u, v;
        fl_point_t p;
        p.x_mm = pairs[i].x_mm;
        p.y_mm = pairs[i].y_mm;
        if (fl_homog_field_to_image(&h, p, &u, &v) == FL_HOMOG_OK)
            fprintf(out, "point %s %.2f %.2f -> %d %d, back %.2f %.2f px\n",
                    names[i] ? names[i] : "-", pairs[i].u_q4 / 16.0, pairs[i].v_q4 / 16.0,
                    (int)p.x_mm, (int)p.y_mm, u / 16.0, v / 16.0);
    }

    /* the firmware's coach path */
    c = (fl_coach_t *)malloc(sizeof *c);
    if (!c) {
        snprintf(err, (size_t)err_len, "out of memory");
        goto done;
    }
    fl_coach_params_default(&cp);
    st = fl_coach_init(c, &cp);
    if (st == FL_OK)
        st = fl_coach_set_homography(c, &h, f);
    if (st != FL_OK) {
        snprintf(err, (size_t)err_len, "%s: the coach refuses the homography: %s (does the "
                 "bottom of the frame show the ground?)", o->points, fl_status_str(st));
        goto done;
    }
    if (o->background) {
        fl_image_t bview;
        if (load_frame("background", o->background, &bg_fr, &bg, err, err_len) != 0)
            goto done;
        if (bg.width != img.width || bg.height != img.height) {
            snprintf(err, (size_t)err_len, "background %s is %d x %d, the image %d x %d",
                     o->background, bg.width, bg.height, img.width, img.height);
            goto done;
        }
        bview = bg_fr.view;
        st = fl_coach_set_background(c, &bview);
        if (st != FL_OK) {
            snprintf(err, (size_t)err_len, "background %s refused: %s", o->background,
                     fl_status_str(st));
            goto done;
        }
    }
    view = img_fr.view;
    {
        long r;
        st = fl_coach_frame(c, &view, &res);
        for (r = 1; r < o->repeat; r++)
            (void)fl_coach_frame(c, &view, &res);
    }
    fprintf(out, "coach_status %s\n", fl_status_str(st));
    if (st != FL_OK) {
        snprintf(err, (size_t)err_len, "%s: the coach path refuses the frame: %s%s", o->image,
                 fl_status_str(st),
                 st == FL_ERR_NOT_FOUND ? " (no field in the frame)"
                 : st == FL_ERR_SIZE ? " (frame size beyond the coach's capacity)" : "");
        rc = 1;
        goto done;
    }
    fprintf(out, "otsu_a %d\nbackground %s\nregions red %d blue %d\nfeet %d\n", res.otsu,
            res.has_background ? "yes" : "no", res.regions[0], res.regions[1], res.n_feet);
    fprintf(out, "# foot TEAM X_MM Y_MM CONFIDENCE U_PX V_PX SD_MM\n");
    for (i = 0; i < res.n_feet; i++) {
        const fl_coach_foot_t *ft = &res.feet[i];
        fprintf(out, "foot %s %d %d %.2f %.2f %.2f %d\n", team_name(ft->team), (int)ft->x_mm,
                (int)ft->y_mm, ft->confidence / 255.0, ft->u_q4 / 16.0, ft->v_q4 / 16.0,
                (int)ft->sd_mm);
    }
    rc = 0;
    if (o->out) {
        snprintf(caption, sizeof caption,
                 "fieldloc coach: %d points, reprojection %.2f px rms; %d feet (ring: red / blue "
                 "jersey); left the frame with the field lines through the homography, right "
                 "the top view at %d mm per pixel",
                 n, e.rms_px_q4 / 16.0, res.n_feet,
                 o->mm_per_px > 0 ? o->mm_per_px : COACH_TOP_MM_PER_PX);
        if (write_picture(o, f, &h, &img, &res, caption, err, err_len) != 0) {
            rc = 2;
            goto done;
        }
        fprintf(out, "picture %s\n", o->out);
    }
done:
    free(c);
    host_image_free(&img);
    host_image_free(&bg);
    render_frame_free(&img_fr);
    render_frame_free(&bg_fr);
    return rc;
}

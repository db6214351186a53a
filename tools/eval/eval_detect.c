/*
 * tools/eval/eval_detect.c - scoring the vision path against ground truth
 * (the rendered fixtures and the UvA 2013 hand labels), for `fieldloc
 * eval-detect` and the tests; the rules are in tools/cli/cmd_eval_detect.c.
 */
#include "eval/detect.h"
#include "eval/picture.h"
#include "io/ppm.h"
#include "io/realdata.h"
#include "world/render.h"
#include "world/truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *evd_pic_dir; /* --pictures DIR (host tool only) */

void evd_set_pictures(const char *dir) { evd_pic_dir = dir; }

/* ---- matching ----------------------------------------------------------------- */

typedef struct {
    char kind;       /* 'L' 'T' 'X' 'G' 'U' */
    double u, v;
    double range_mm; /* truth: true range; det: estimated (0: none) */
    int required;    /* truth: counts for recall */
    int match;       /* index of the matched partner, -1 */
} evd_item_t;

static int evd_is_cross(char k) { return k == 'L' || k == 'T' || k == 'X'; }

/* Greedy one-to-one matching of det[] to tru[] within tol px, only pairs
 * whose classes agree (crossing vs crossing, G vs G, U vs U). */
static void evd_match(evd_item_t *det, int nd, evd_item_t *tru, int nt)
{
    int i, j;
    for (i = 0; i < nd; i++)
        det[i].match = -1;
    for (j = 0; j < nt; j++)
        tru[j].match = -1;
    for (;;) {
        double best = 1e30;
        int bi = -1, bj = -1;
        for (i = 0; i < nd; i++) {
            if (det[i].match >= 0)
                continue;
            for (j = 0; j < nt; j++) {
                double d, tol;
                int same;
                if (tru[j].match >= 0)
                    continue;
                same = evd_is_cross(det[i].kind) ? evd_is_cross(tru[j].kind)
                                                 : det[i].kind == tru[j].kind;
                if (!same)
                    continue;
                tol = evd_is_cross(det[i].kind) || det[i].kind == 'C' ? 8.0 : 6.0;
                d = hypot(det[i].u - tru[j].u, det[i].v - tru[j].v);
                if (d <= tol && d < best) {
                    best = d;
                    bi = i;
                    bj = j;
                }
            }
        }
        if (bi < 0)
            break;
        det[bi].match = bj;
        tru[bj].match = bi;
    }
}

static const double evd_bins[] = {0, 1000, 2000, 3000, 4500, 6000, 1e9};
#define EVD_NBINS 6

void evd_stats_clear(evd_stats_t *s)
{
    memset(s, 0, sizeof *s);
}

/* Accumulate one frame. */
static void evd_score(evd_stats_t *s, evd_item_t *det, int nd, evd_item_t *tru,
                      int nt, double max_range, int real)
{
    int i, j, k;
    evd_match(det, nd, tru, nt);
    s->frames++;
    for (j = 0; j < nt; j++) {
        if (!tru[j].required)
            continue;
        if (evd_is_cross(tru[j].kind))
            s->type_truth[tru[j].kind == 'L' ? 0 : tru[j].kind == 'T' ? 1 : 2]++;
    }
    for (i = 0; i < nd; i++) {
        char dk = det[i].kind;
        int t = det[i].match, tk;
        if (t < 0) {
            if (!real && det[i].range_mm > max_range)
                continue;
            if (evd_is_cross(dk)) {
                s->cross_fp++;
                s->type_det[dk == 'L' ? 0 : dk == 'T' ? 1 : 2]++;
            } else if (dk == 'G') {
                s->foot_fp++;
            } else if (dk == 'U') {
                s->top_fp++;
            } else if (dk == 'C') {
                s->circle_fp++;
            }
            continue;
        }
        if (!tru[t].required)
            continue;
        if (evd_is_cross(dk)) {
            s->cross_tp++;
            tk = tru[t].kind == 'L' ? 0 : tru[t].kind == 'T' ? 1 : 2;
            k = dk == 'L' ? 0 : dk == 'T' ? 1 : 2;
            s->type_det[k]++;
            if (tk == k) {
                s->type_ok++;
                s->type_hit[k]++;
            }
        } else if (dk == 'G') {
            s->foot_tp++;
        } else if (dk == 'U') {
            s->top_tp++;
        } else if (dk == 'C') {
            s->circle_tp++;
        }
        if (!real && (evd_is_cross(dk) || dk == 'G') && tru[t].range_mm > 0 &&
            det[i].range_mm > 0) {
            double e = fabs(det[i].range_mm - tru[t].range_mm) / tru[t].range_mm;
            for (k = 0; k < EVD_NBINS; k++)
                if (tru[t].range_mm >= evd_bins[k] && tru[t].range_mm < evd_bins[k + 1])
                    break;
            if (k < EVD_NBINS) {
                s->rng_n[k]++;
                s->rng_sum[k] += e;
                if (e > s->rng_max[k])
                    s->rng_max[k] = e;
            }
        }
    }
    for (j = 0; j < nt; j++)
        if (tru[j].required && evd_is_cross(tru[j].kind) && !real) {
            for (k = 0; k < EVD_NBINS; k++)
                if (tru[j].range_mm >= evd_bins[k] && tru[j].range_mm < evd_bins[k + 1])
                    break;
            if (k < EVD_NBINS) {
                s->cross_bin_truth[k]++;
                if (tru[j].match >= 0)
                    s->cross_bin_hit[k]++;
            }
        }
    for (j = 0; j < nt; j++)
        if (tru[j].required && tru[j].match < 0) {
            if (evd_is_cross(tru[j].kind))
                s->cross_fn++;
            else if (tru[j].kind == 'G')
                s->foot_fn++;
            else if (tru[j].kind == 'U')
                s->top_fn++;
            else if (tru[j].kind == 'C')
                s->circle_fn++;
        }
}

static int evd_det_items(const det_feature_t *f, int n, evd_item_t *out)
{
    int i, m = 0;
    for (i = 0; i < n; i++) {
        out[m].kind = f[i].kind;
        out[m].u = f[i].u;
        out[m].v = f[i].v;
        out[m].range_mm = f[i].range_mm;
        out[m].required = 0;
        m++;
    }
    return m;
}

static void evd_verbose_frame(const char *name, const evd_item_t *det, int nd,
                              const evd_item_t *tru, int nt)
{
    int i;
    printf("  %s:", name);
    for (i = 0; i < nt; i++)
        if (tru[i].required && tru[i].match < 0)
            {
            if (tru[i].range_mm > 0)
                printf(" miss %c(%.0f,%.0f)@%.1fm", tru[i].kind, tru[i].u, tru[i].v,
                       tru[i].range_mm / 1000);
            else
                printf(" miss %c(%.0f,%.0f)", tru[i].kind, tru[i].u, tru[i].v);
        }
    for (i = 0; i < nd; i++)
        if (det[i].match < 0)
            printf(" fp %c(%.0f,%.0f)", det[i].kind, det[i].u, det[i].v);
        else if (det[i].kind != tru[det[i].match].kind)
            printf(" type %c->%c(%.0f,%.0f)", tru[det[i].match].kind, det[i].kind, det[i].u,
                   det[i].v);
    printf("\n");
}

/* Picture of one evaluated frame: stages plus truth (white ring: matched,
 * red ring: missed, grey: not required), the legend strip below. */
static void evd_picture(det_ctx_t *ctx, const fl_image_t *img, const fl_camera_t *cam,
                        const fl_field_t *field, const evd_item_t *tru, int nt,
                        const char *name)
{
    char path[1024];
    uint8_t *rgb;
    int i, k;
    if (!evd_pic_dir)
        return;
    rgb = det_rgb_copy(img);
    if (!rgb)
        return;
    det_draw(ctx, rgb, img->width, img->height, cam, field);
    for (i = 0; i < nt; i++) {
        static const uint8_t wh[3] = {255, 255, 255}, rd[3] = {255, 40, 40},
                             gy[3] = {120, 120, 120};
        const uint8_t *col = !tru[i].required ? gy : tru[i].match >= 0 ? wh : rd;
        for (k = 0; k < 24; k++) {
            int u = (int)lround(tru[i].u + 6 * cos(k * M_PI / 12));
            int v = (int)lround(tru[i].v + 6 * sin(k * M_PI / 12));
            if (u >= 0 && v >= 0 && u < img->width && v < img->height)
                memcpy(rgb + 3 * ((size_t)v * (size_t)img->width + (size_t)u), col, 3);
        }
    }
    snprintf(path, sizeof path, "%s/%s.ppm", evd_pic_dir, name);
    {
        host_image_t pic, out;
        char caption[256];
        pic.width = img->width;
        pic.height = img->height;
        pic.rgb = rgb;
        snprintf(caption, sizeof caption, "eval-detect %s (field %s)", name, field->name);
        if (pic_add_legend(&pic, PIC_LEGEND_DETECT | PIC_LEGEND_EVAL, caption, &out) == 0) {
            ppm_write(path, out.rgb, out.width, out.height);
            host_image_free(&out);
        }
    }
    free(rgb);
}

/* ---- rendered fixtures ---------------------------------------------------------- */

int evd_fixtures(det_ctx_t *ctx, const char *dir, double max_range, int verbose,
                 evd_stats_t *s, const char *only_prefix)
{
    char path[1024], line[1024];
    FILE *idx;
    int frames = 0;
    snprintf(path, sizeof path, "%s/frames/index.txt", dir);
    idx = fopen(path, "r");
    if (!idx)
        return -1;
    while (fgets(line, sizeof line, idx)) {
        char name[256], file[256], fmt[32], fieldn[64], camn[64], err[256];
        render_frame_t fr;
        static truth_t tr;
        fl_camera_t cam;
        const fl_field_t *field;
        const fl_camera_model_t *m;
        det_feature_t feat[DET_MAX_FEATURES];
        evd_item_t det[DET_MAX_FEATURES], tru[TRUTH_MAX_FEATURES];
        int nd, nt = 0, i;
        if (line[0] == '#' || sscanf(line, "%255s %255s %31s %63s %63s", name, file, fmt,
                                     fieldn, camn) != 5)
            continue;
        if (only_prefix && strncmp(name, only_prefix, strlen(only_prefix)) != 0)
            continue;
        field = fl_field_find(fieldn);
        m = fl_camera_model_find(camn);
        snprintf(path, sizeof path, "%s/frames/%s.truth", dir, name);
        if (!field || !m || truth_load(path, &tr, err, sizeof err) != 0)
            continue;
        snprintf(path, sizeof path, "%s/frames/%s", dir, file);
        if (render_read_frame(path, &fr, err, sizeof err) != 0)
            continue;
        if (fl_camera_init(&cam, m, &tr.head) != FL_OK) {
            render_frame_free(&fr);
            continue;
        }
        nd = det_run(ctx, &fr.view, &cam, field, NULL, feat, DET_MAX_FEATURES);
        nd = evd_det_items(feat, nd, det);
        for (i = 0; i < tr.n && nt < TRUTH_MAX_FEATURES; i++) {
            const truth_feature_t *f = &tr.f[i];
            char k;
            switch (f->kind) {
            case TRUTH_L: k = 'L'; break;
            case TRUTH_T: k = 'T'; break;
            case TRUTH_X: case TRUTH_PENALTY_MARK: case TRUTH_CENTRE_MARK: k = 'X'; break;
            case TRUTH_POST_FOOT: k = 'G'; break;
            case TRUTH_POST_TOP: k = 'U'; break;
            case TRUTH_CIRCLE_CENTRE: k = 'C'; break;
            default: k = 0;
            }
            if (!k)
                continue;
            tru[nt].kind = k;
            tru[nt].u = f->u;
            tru[nt].v = f->v;
            tru[nt].range_mm = f->range_mm;
            tru[nt].required = !f->occluded && f->range_mm <= max_range;
            /* posts: the yellow goals and, where the goals are white,
             * the white ones are detected (coloured aibo goals are not) */
            if ((k == 'G' || k == 'U') && f->landmark >= 0 &&
                field->landmarks[f->landmark].color != FL_COLOR_YELLOW &&
                field->landmarks[f->landmark].color != FL_COLOR_WHITE)
                tru[nt].required = 0;
            nt++;
        }
        evd_score(s, det, nd, tru, nt, max_range, 0);
        if (verbose)
            evd_verbose_frame(name, det, nd, tru, nt);
        evd_picture(ctx, &fr.view, &cam, field, tru, nt, name);
        render_frame_free(&fr);
        frames++;
    }
    fclose(idx);
    return frames;
}

/* ---- UvA 2013 ------------------------------------------------------------------- */

int evd_uva(det_ctx_t *ctx, const char *dir, int verbose, evd_stats_t *s)
{
    char path[1024], err[256];
    rd_uva_set_t set;
    const fl_field_t *field = fl_field_find("uva2013");
    const fl_camera_model_t *m = fl_camera_model_find("uva2013");
    int r, frames = 0;
    if (!dir || rd_path(path, sizeof path, dir, RD_UVA_CSV) != 0 ||
        rd_uva_load(path, &set, err, sizeof err) != 0)
        return -1;
    for (r = 0; r < set.n; r++) {
        const rd_uva_record_t *rec = &set.rec[r];
        host_image_t img;
        fl_image_t view;
        fl_camera_pose_t pose;
        fl_camera_t cam;
        det_feature_t feat[DET_MAX_FEATURES];
        evd_item_t det[DET_MAX_FEATURES], tru[RD_MAX_FEATURES];
        int nd, nt = 0, i;
        if (!rec->in_realdata || rd_read_ppm(dir, rec->file, &img, err, sizeof err) != 0)
            continue;
        if (rd_image_view(&img, &view) != FL_OK) {
            host_image_free(&img);
            continue;
        }
        rd_uva_camera_pose(rec, m, &pose);
        if (fl_camera_init(&cam, m, &pose) != FL_OK) {
            host_image_free(&img);
            continue;
        }
        nd = det_run(ctx, &view, &cam, field, NULL, feat, DET_MAX_FEATURES);
        nd = evd_det_items(feat, nd, det);
        for (i = 0; i < rec->n_features; i++) {
            tru[nt].kind = rec->feat[i].type;
            tru[nt].u = rec->feat[i].u;
            tru[nt].v = rec->feat[i].v;
            tru[nt].range_mm = 0;
            tru[nt].required = 1;
            nt++;
        }
        evd_score(s, det, nd, tru, nt, 1e9, 1);
        {
            char nm[64];
            snprintf(nm, sizeof nm, "uva_%s_%s", rec->set, rec->index);
            evd_picture(ctx, &view, &cam, field, tru, nt, nm);
        }
        if (verbose)
            evd_verbose_frame(rec->file + (strncmp(rec->file, "IntelligentRoboticsLab_Datasets_", 32) ? 0 : 32),
                              det, nd, tru, nt);
        host_image_free(&img);
        frames++;
    }
    rd_uva_free(&set);
    return frames;
}

/* ---- modern real frames (hand labels in the repository) ----------------------- */

void evd_border_clear(evd_border_t *b)
{
    memset(b, 0, sizeof *b);
}

/* The scanner's border at pixel column u of the last frame: linear between
 * the two grid columns around u (the nearer one when only it has a border),
 * the image height when neither has one (the scanner's "none"). */
static double evd_border_at(const fl_scan_t *sc, double u)
{
    int32_t step = sc->params.col_step > 0 ? sc->params.col_step : 1;
    double g = u / step, t;
    int i0 = (int)floor(g), i1 = i0 + 1;
    int ok0, ok1;
    if (sc->cols <= 0)
        return sc->height;
    if (i0 < 0)
        i0 = 0;
    if (i0 > sc->cols - 1)
        i0 = sc->cols - 1;
    if (i1 > sc->cols - 1)
        i1 = sc->cols - 1;
    t = g - i0;
    if (t < 0)
        t = 0;
    if (t > 1)
        t = 1;
    ok0 = sc->border_v[i0] < sc->height;
    ok1 = sc->border_v[i1] < sc->height;
    if (ok0 && ok1)
        return (1 - t) * sc->border_v[i0] + t * sc->border_v[i1];
    if (ok0 && (t < 0.5 || !ok1))
        return sc->border_v[i0];
    if (ok1)
        return sc->border_v[i1];
    return sc->height;
}

/* Score the B labels of one frame against the scanner's border. */
static void evd_border_score(evd_border_t *b, const fl_scan_t *sc, const rd_modern_record_t *rec,
                             int verbose)
{
    int i, n = 0, ok = 0;
    for (i = 0; i < rec->n_features; i++) {
        const rd_feature_t *f = &rec->feat[i];
        double bv, e;
        if (f->type != 'B')
            continue;
        bv = evd_border_at(sc, f->u);
        e = fabs(bv - f->v);
        n++;
        b->n++;
        b->sum += e;
        if (e <= EVD_BORDER_TOL_PX) {
            ok++;
            b->within++;
        }
        if (bv >= sc->height)
            b->none++;
        if (e > b->worst) {
            b->worst = e;
            snprintf(b->worst_at, sizeof b->worst_at, "%s u %.0f", rec->index, f->u);
        }
        if (verbose && e > EVD_BORDER_TOL_PX)
            printf("    border %s u %.0f: label %.0f, found %s%.1f\n", rec->index, f->u, f->v,
                   bv >= sc->height ? "none " : "", bv);
    }
    if (verbose && n)
        printf("    border %s: %d/%d columns within %.0f px\n", rec->index, ok, n,
               EVD_BORDER_TOL_PX);
}

int evd_modern(det_ctx_t *ctx, const char *dir, const char *csv, int verbose, evd_stats_t *s,
               evd_border_t *b)
{
    char err[256];
    rd_modern_set_t set;
    const fl_field_t *field = fl_field_find("spl2020");
    int r, frames = 0;
    if (!dir || !csv || !field || rd_modern_load(csv, &set, err, sizeof err) != 0)
        return -1;
    for (r = 0; r < set.n; r++) {
        const rd_modern_record_t *rec = &set.rec[r];
        const fl_camera_model_t *m = fl_camera_model_find(rec->camera);
        host_image_t img;
        fl_image_t view;
        fl_camera_pose_t pose;
        fl_camera_t cam;
        det_feature_t feat[DET_MAX_FEATURES];
        evd_item_t det[DET_MAX_FEATURES], tru[RD_MODERN_MAX_FEATURES];
        int nd, nt = 0, i;
        if (!m || !rec->in_realdata || rd_read_ppm(dir, rec->file, &img, err, sizeof err) != 0)
            continue;
        if ((int32_t)img.width != m->width_px || (int32_t)img.height != m->height_px ||
            rd_image_view(&img, &view) != FL_OK) {
            host_image_free(&img);
            continue;
        }
        rd_modern_camera_pose(rec, m, &pose);
        if (fl_camera_init(&cam, m, &pose) != FL_OK) {
            host_image_free(&img);
            continue;
        }
        nd = det_run(ctx, &view, &cam, field, NULL, feat, DET_MAX_FEATURES);
        nd = evd_det_items(feat, nd, det);
        for (i = 0; i < rec->n_features; i++) {
            if (rec->feat[i].type == 'B')
                continue;
            tru[nt].kind = rec->feat[i].type;
            tru[nt].u = rec->feat[i].u;
            tru[nt].v = rec->feat[i].v;
            tru[nt].range_mm = 0;
            tru[nt].required = 1;
            nt++;
        }
        evd_score(s, det, nd, tru, nt, 1e9, 1);
        {
            char nm[128];
            snprintf(nm, sizeof nm, "modern_%s_%s", rec->set, rec->index);
            evd_picture(ctx, &view, &cam, field, tru, nt, nm);
        }
        if (verbose) {
            char nm[128];
            snprintf(nm, sizeof nm, "%s %s", rec->set, rec->index);
            evd_verbose_frame(nm, det, nd, tru, nt);
        }
        evd_border_score(b, &ctx->vis->scan, rec, verbose);
        host_image_free(&img);
        frames++;
    }
    rd_modern_free(&set);
    return frames;
}

void evd_border_print(const evd_border_t *b)
{
    if (b->n == 0) {
        printf("  field border  no labelled columns\n");
        return;
    }
    printf("  field border  %.3f of %d labelled columns within %.0f px  (mean %.1f px, worst "
           "%.1f px at %s; no border in %d)\n",
           (double)b->within / b->n, b->n, EVD_BORDER_TOL_PX, b->sum / b->n, b->worst,
           b->worst_at, b->none);
}

/* ---- report ------------------------------------------------------------------- */

static double evd_ratio(int a, int b) { return b > 0 ? (double)a / b : 0.0; }

void evd_print(const char *title, const evd_stats_t *s, int ranges)
{
    static const char tn[3] = {'L', 'T', 'X'};
    int k;
    printf("%s: %d frames\n", title, s->frames);
    printf("  crossings  precision %.3f  recall %.3f  type accuracy %.3f  (tp %d fp %d fn %d)\n",
           evd_ratio(s->cross_tp, s->cross_tp + s->cross_fp),
           evd_ratio(s->cross_tp, s->cross_tp + s->cross_fn), evd_ratio(s->type_ok, s->cross_tp),
           s->cross_tp, s->cross_fp, s->cross_fn);
    for (k = 0; k < 3; k++)
        printf("    %c        precision %.3f  recall %.3f  (hits %d, detected %d, truth %d)\n", tn[k],
               evd_ratio(s->type_hit[k], s->type_det[k]), evd_ratio(s->type_hit[k], s->type_truth[k]),
               s->type_hit[k], s->type_det[k], s->type_truth[k]);
    printf("  post feet  precision %.3f  recall %.3f  (tp %d fp %d fn %d)\n",
           evd_ratio(s->foot_tp, s->foot_tp + s->foot_fp),
           evd_ratio(s->foot_tp, s->foot_tp + s->foot_fn), s->foot_tp, s->foot_fp, s->foot_fn);
    printf("  post tops  precision %.3f  recall %.3f  (tp %d fp %d fn %d)\n",
           evd_ratio(s->top_tp, s->top_tp + s->top_fp),
           evd_ratio(s->top_tp, s->top_tp + s->top_fn), s->top_tp, s->top_fp, s->top_fn);
    if (ranges)
        printf("  circle     precision %.3f  recall %.3f  (tp %d fp %d fn %d; centre pixel within 8 px)\n",
               evd_ratio(s->circle_tp, s->circle_tp + s->circle_fp),
               evd_ratio(s->circle_tp, s->circle_tp + s->circle_fn), s->circle_tp,
               s->circle_fp, s->circle_fn);
    if (!ranges)
        return;
    printf("  crossing recall by true distance:");
    for (k = 0; k < EVD_NBINS; k++)
        if (s->cross_bin_truth[k] > 0)
            printf("  %.1f-%.1f m %d/%d", evd_bins[k] / 1000, evd_bins[k + 1] / 1000,
                   s->cross_bin_hit[k], s->cross_bin_truth[k]);
    printf("\n");
    printf("  range error (crossings and feet) by true distance:\n");
    for (k = 0; k < EVD_NBINS; k++)
        if (s->rng_n[k] > 0)
            printf("    %4.1f-%4.1f m  n %3d  mean %5.2f %%  max %5.2f %%\n", evd_bins[k] / 1000,
                   evd_bins[k + 1] > 1e8 ? 99.0 : evd_bins[k + 1] / 1000, s->rng_n[k],
                   100 * s->rng_sum[k] / s->rng_n[k], 100 * s->rng_max[k]);
}

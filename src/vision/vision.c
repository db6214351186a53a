/*
 * src/vision/vision.c - the per-frame vision path: scanner, line points,
 * segments, circle, crossings, posts, observations (see vision.h).
 *
 * Algorithm: the stages in data-flow order; the circle runs before the
 * crossings so that its chords are flagged (no L/T from two chords).  The
 * scanner is re-initialised only when the effective grid changes (an
 * automatic grid follows the image width).
 * Invariant: after the call every stage result describes this frame (or
 * is empty), out->n <= FL_OBS_MAX.
 * Memory: the caller's fl_vision_t; stack < 1 KB (the crossing stage's
 * visited bitmap and arm table).
 * Cost: the sum of the stages (see their files); measured per frame by
 * bench_vision (`make bench`).
 * Scaling: no arithmetic of its own beyond copying (confidences Q0.8).
 */
#include "fieldloc/vision.h"

#include <string.h>

void fl_vision_params_default(fl_vision_params_t *p)
{
    if (!p)
        return;
    fl_scan_params_default(&p->scan);
    p->scan.col_step = 0;
    p->scan.row_step = 0;
    /* far field lines (a 1-2 px strip of carpet between them) sit above a
     * border that needs 8 green pixels; with the camera's horizon bounding
     * the search, 4 is safe (eval-detect: recall +0.1 at equal precision) */
    p->scan.border_run_px = 4;
    fl_lines_params_default(&p->lines);
    fl_crossings_params_default(&p->crossings);
    p->min_confidence = 40;
    p->posts = 1;
    p->circle = 1;
    p->beacons = 1;
    fl_beacon_params_default(&p->beacon);
}

bool fl_vision_wants_beacons(const fl_field_t *field)
{
    int32_t k;
    if (!field)
        return false;
    if (field->beacon_height_mm > 0 ||
        fl_field_count_kind(field, FL_LM_BEACON) > 0)
        return true;
    for (k = 0; k < 2; k++)
        if (field->goal_color[k] == FL_COLOR_SKYBLUE ||
            field->goal_color[k] == FL_COLOR_PINK)
            return true;
    return false;
}

/* Effective scan params for an image width. */
static void vi_scan_params(const fl_vision_params_t *p, int32_t width,
                           fl_scan_params_t *out)
{
    int32_t g = width > 320 ? (width + 319) / 320 : 1;
    *out = p->scan;
    if (out->col_step == 0)
        out->col_step = g;
    if (out->row_step == 0)
        out->row_step = g;
}

fl_status_t fl_vision_init_cfg(fl_vision_t *v, const fl_vision_params_t *p, uint32_t caller_cfg)
{
    fl_status_t st;
    fl_scan_params_t sp;
    fl_lines_t *l;
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *v has another layout: no write is safe */
    if (!v || !p)
        return FL_ERR_NULL;
    v->frames = 0;
    v->obs_dropped = 0;
    v->status = FL_OK;
    fl_vision_params_default(&v->params);
    if (p->min_confidence < 0 || p->min_confidence > 255 || p->posts < 0 ||
        p->posts > 1 || p->circle < 0 || p->circle > 1 || p->beacons < 0 ||
        p->beacons > 1 ||
        p->scan.col_step < 0 || p->scan.row_step < 0)
        return FL_ERR_RANGE;
    vi_scan_params(p, 320, &sp);
    st = fl_scan_init(&v->scan, &sp);
    if (st != FL_OK)
        return st;
    v->scan_active = sp;
    l = &v->lines;
    st = fl_lines_init(l, &p->lines);
    if (st != FL_OK)
        return st;
    st = fl_crossings_init(&v->crossings, &p->crossings);
    if (st != FL_OK)
        return st;
    memset(&v->circle, 0, sizeof v->circle);
    memset(&v->posts, 0, sizeof v->posts);
    st = fl_beacon_init(&v->beacons, &p->beacon);
    if (st != FL_OK)
        return st;
    v->params = *p;
    return FL_OK;
}

/* An observation with the fields every kind has; the rest zero (side and
 * colors unknown, no orientation). */
static void vi_obs(fl_obs_t *o, fl_landmark_kind_t kind, int32_t range_mm, fl_angle_t bearing,
                   uint8_t confidence, int32_t u_q4, int32_t v_q4)
{
    memset(o, 0, sizeof *o);
    o->kind = kind;
    o->range_mm = range_mm;
    o->bearing = bearing;
    o->confidence = confidence;
    o->u_q4 = u_q4;
    o->v_q4 = v_q4;
}

/* The camera model must describe this frame: a zeroed camera (its
 * fl_camera_init failed) projects nothing, and a model of another size
 * would put every ground point, the horizon and the line widths in the
 * wrong place.  NULL: no camera, nothing to compare. */
static fl_status_t vi_camera_check(const fl_image_t *img, const fl_camera_t *camera)
{
    if (camera == NULL)
        return FL_OK;
    if (camera->model.width_px <= 0 || camera->model.height_px <= 0 ||
        camera->model.focal_q4 <= 0)
        return FL_ERR_CAMERA;
    if (img->width != camera->model.width_px || img->height != camera->model.height_px)
        return FL_ERR_MISMATCH;
    return FL_OK;
}

static int32_t vi_push(fl_obs_list_t *out, const fl_obs_t *o, int32_t min_conf)
{
    if (o->confidence < min_conf)
        return 0;
    return fl_obs_list_push(out, o) ? 1 : 0;
}

int32_t fl_vision_frame(fl_vision_t *v, const fl_color_table_t *colors,
                        const fl_image_t *img, const fl_camera_t *camera,
                        const fl_field_t *field, fl_obs_list_t *out)
{
    fl_scan_params_t sp;
    int32_t i, k, lw;
    uint8_t done[FL_CROSSINGS_MAX];
    fl_obs_t o;
    if (!v)
        return 0;
    if (out)
        fl_obs_list_clear(out);
    v->lines.n_points = v->lines.n_segments = 0;
    v->lines.width = 0;
    v->crossings.n = 0;
    v->posts.n = 0;
    v->beacons.n = 0;
    v->circle.found = false;
    if (!out || !colors || !img || !field) {
        v->status = FL_ERR_NULL;
        return 0;
    }
    /* a format of image.h (each stage reads all of them) with a valid size
     * and stride */
    v->status = fl_image_validate(img);
    if (v->status != FL_OK)
        return 0;
    v->status = vi_camera_check(img, camera);
    if (v->status != FL_OK)
        return 0;
    v->frames++;
    vi_scan_params(&v->params, img->width, &sp);
    if (memcmp(&sp, &v->scan_active, sizeof sp) != 0) {
        if (fl_scan_init(&v->scan, &sp) != FL_OK) {
            v->status = FL_ERR_RANGE;
            return 0;
        }
        v->scan_active = sp;
    }
    fl_scan_frame(&v->scan, colors, img, camera);
    if (v->scan.width <= 0) {
        v->status = v->scan.status != FL_OK ? v->scan.status : FL_ERR_SIZE;
        return 0;
    }
    lw = field->line_width_mm;
    fl_lines_find_points(&v->lines, &v->scan, img, camera, lw);
    fl_lines_find_segments(&v->lines, &v->scan);
    if (v->params.circle)
        fl_circle_find(&v->circle, &v->lines, camera, field);
    fl_crossings_find(&v->crossings, &v->lines, &v->scan, camera, field);
    if (v->params.circle)
        fl_crossings_add_circle(&v->crossings, &v->circle, &v->lines, &v->scan,
                                camera, field);
    if (v->params.posts) {
        if (field->goal_color[0] == FL_COLOR_WHITE)
            fl_goal_find_white(&v->posts, &v->scan, img, camera, field);
        else
            fl_goal_find(&v->posts, &v->scan, img, colors, camera, field);
    }

    /* observations: posts, circle, crossings by confidence */
    for (i = 0; i < v->posts.n; i++) {
        const fl_post_t *p = &v->posts.post[i];
        if (!camera || p->range_mm <= 0)
            continue;
        vi_obs(&o, FL_LM_POST, p->range_mm, p->bearing, p->confidence, p->foot_u_q4,
               p->foot_v_q4);
        o.side = p->side;
        o.color = field->goal_color[0] == field->goal_color[1]
                       ? field->goal_color[0] : FL_COLOR_YELLOW;
        vi_push(out, &o, v->params.min_confidence);
    }
    if (v->circle.found) {
        vi_obs(&o, FL_LM_CENTRE_CIRCLE, v->circle.range_mm, v->circle.bearing,
               v->circle.confidence, v->circle.has_pixel ? v->circle.u_q4 : -1,
               v->circle.has_pixel ? v->circle.v_q4 : -1);
        o.orientation = v->circle.orientation;
        o.has_orientation = v->circle.has_orientation;
        vi_push(out, &o, v->params.min_confidence);
    }
    memset(done, 0, sizeof done);
    for (k = 0; k < v->crossings.n; k++) {
        int32_t best = -1;
        const fl_crossing_t *x;
        for (i = 0; i < v->crossings.n; i++)
            if (!done[i] && (best < 0 ||
                             v->crossings.c[i].confidence > v->crossings.c[best].confidence))
                best = i;
        done[best] = 1;
        x = &v->crossings.c[best];
        if (!camera || x->range_mm <= 0)
            continue;
        vi_obs(&o, x->kind, x->range_mm, x->bearing, x->confidence, x->u_q4, x->v_q4);
        o.orientation = x->orientation;
        o.has_orientation = x->has_orientation;
        vi_push(out, &o, v->params.min_confidence);
    }
    /* colored landmarks (beacon.h), appended: only on fields that have
     * them, so that every other field's output is what it was */
    if (v->params.beacons && fl_vision_wants_beacons(field)) {
        fl_beacon_find(&v->beacons, &v->scan, img, colors, camera, field);
        for (i = 0; i < v->beacons.n; i++) {
            const fl_beacon_found_t *f = &v->beacons.found[i];
            bool dup = false;
            if (!camera || f->range_mm <= 0)
                continue;
            /* a yellow post goal.c found already (within its width + 4 px) */
            for (k = 0; k < v->posts.n && f->kind == FL_LM_POST; k++) {
                int32_t d = v->posts.post[k].foot_u_q4 - f->u_q4;
                if ((d < 0 ? -d : d) <= v->posts.post[k].width_q4 + f->width_q4 + 64)
                    dup = true;
            }
            if (dup)
                continue;
            vi_obs(&o, f->kind, f->range_mm, f->bearing, f->confidence, f->u_q4, f->v_q4);
            o.side = f->side;
            o.color = f->color;
            o.color2 = f->color2;
            vi_push(out, &o, v->params.min_confidence);
        }
    }
    v->obs_dropped += out->dropped;
    v->status = FL_OK;
    return out->n;
}

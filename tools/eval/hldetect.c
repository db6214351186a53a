/*
 * tools/eval/hldetect.c - seed 002's vision path for the tools
 * (hldetect.h).
 */
#include "eval/hldetect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int hld_field_wants(const fl_field_t *field)
{
    return field != NULL && field->name != NULL && !strcmp(field->name, "hl3x2");
}

fl_hlv_t *hld_new(const fl_field_t *field)
{
    fl_hlv_params_t p;
    fl_hlv_t *hv = malloc(sizeof *hv);
    if (!hv)
        return NULL;
    fl_hlv_params_default(&p, field);
    if (fl_hlv_init(hv, &p) != FL_OK) {
        free(hv);
        return NULL;
    }
    return hv;
}

int hld_run(fl_hlv_t *hv, const fl_image_t *img, const fl_camera_t *cam, fl_obs_list_t *obs,
            det_feature_t *out, int max)
{
    int i, n = 0;
    fl_hlv_frame(hv, img, cam, obs);
    for (i = 0; i < obs->n && n < max; i++) {
        const fl_obs_t *o = &obs->obs[i];
        det_feature_t *f = &out[n];
        switch (o->kind) {
        case FL_LM_POST: f->kind = 'G'; break;
        case FL_LM_BEACON: f->kind = 'P'; break;
        case FL_LM_X: f->kind = 'X'; break;
        case FL_LM_T: f->kind = 'T'; break;
        default: continue;
        }
        f->u = o->u_q4 / 16.0;
        f->v = o->v_q4 / 16.0;
        f->confidence = o->confidence / 255.0;
        f->range_mm = o->range_mm;
        f->bearing_deg = fl_angle_to_mdeg(o->bearing) / 1000.0;
        f->lm = o->kind;
        n++;
    }
    return n;
}

static void put(uint8_t *rgb, int w, int h, int u, int v, const uint8_t *c)
{
    if (u < 0 || v < 0 || u >= w || v >= h)
        return;
    memcpy(rgb + 3 * ((size_t)v * (size_t)w + (size_t)u), c, 3);
}

/* Outline of the rectangle u0..u1 x v0..v1. */
static void rect(uint8_t *rgb, int w, int h, int u0, int v0, int u1, int v1, const uint8_t *c)
{
    int u, v;
    for (u = u0; u <= u1; u++) {
        put(rgb, w, h, u, v0, c);
        put(rgb, w, h, u, v1, c);
    }
    for (v = v0; v <= v1; v++) {
        put(rgb, w, h, u0, v, c);
        put(rgb, w, h, u1, v, c);
    }
}

static void draw_mask(const fl_hlv_t *hv, uint8_t *rgb, int w, int h)
{
    static const uint8_t c_mask[3] = {120, 200, 255}, c_skel[3] = {255, 0, 0};
    const int su = hv->step_u, sv = hv->step_v;
    int i, j, a, b;
    for (j = 0; j < hv->mask_h; j++)
        for (i = 0; i < hv->mask_w; i++) {
            const int sk = hv->params.crossings && fl_skel_pixel(&hv->skel, i, j);
            if (!hv->mask[j * hv->mask_w + i] && !sk)
                continue;
            /* the whole cell, so that the skeleton reads as a line */
            for (b = 0; b < sv; b++)
                for (a = 0; a < su; a++)
                    put(rgb, w, h, i * su + a, j * sv + b, sk ? c_skel : c_mask);
        }
}

static void draw_objects(const fl_hlv_t *hv, uint8_t *rgb, int w, int h)
{
    static const uint8_t c_post[3] = {0, 255, 0}, c_yby[3] = {255, 255, 0},
                         c_byb[3] = {0, 160, 255};
    int k;
    for (k = 0; k < hv->n_objects; k++) {
        const fl_hlv_object_t *o = &hv->objects[k];
        const int u0 = o->u0 - 2, u1 = o->u1 + 2;
        if (o->kind == FL_HLV_POST_YELLOW || o->kind == FL_HLV_POST_BLUE) {
            rect(rgb, w, h, u0, o->top_v, u1, o->foot_v, c_post);
            rect(rgb, w, h, u0 - 2, o->foot_v - 2, u1 + 2, o->foot_v + 2, c_post);
        } else {
            const uint8_t *c = o->kind == FL_HLV_POLE_YBY ? c_yby : c_byb;
            rect(rgb, w, h, u0, o->band_v[0], u1, o->foot_v, c);
            rect(rgb, w, h, u0, o->band_v[1], u1, o->band_v[0], c);
            rect(rgb, w, h, u0, o->top_v, u1, o->band_v[1], c);
        }
    }
}

static void draw_obs(const fl_obs_list_t *obs, uint8_t *rgb, int w, int h,
                     const fl_camera_t *cam)
{
    static const uint8_t c_t[3] = {255, 150, 0}, c_x[3] = {255, 0, 255}, c_pt[3] = {0, 0, 0};
    int i;
    for (i = 0; i < obs->n; i++) {
        const fl_obs_t *o = &obs->obs[i];
        const int u = (int)lround(o->u_q4 / 16.0), v = (int)lround(o->v_q4 / 16.0);
        if (o->kind == FL_LM_X || o->kind == FL_LM_T) {
            rect(rgb, w, h, u - 5, v - 5, u + 5, v + 5, o->kind == FL_LM_X ? c_x : c_t);
            rect(rgb, w, h, u - 4, v - 4, u + 4, v + 4, o->kind == FL_LM_X ? c_x : c_t);
        }
    }
    for (i = 0; i < obs->n_points && i < FL_OBS_MAX_POINTS; i++) {
#if FL_OBS_MAX_POINTS > 0
        fl_point_t g;
        int32_t uq, vq;
        g.x_mm = obs->points[i].x_mm;
        g.y_mm = obs->points[i].y_mm;
        if (cam && fl_camera_ground_to_pixel(cam, g, &uq, &vq)) {
            const int u = (int)lround(uq / 16.0), v = (int)lround(vq / 16.0);
            rect(rgb, w, h, u - 1, v - 1, u + 1, v + 1, c_pt);
        }
#endif
    }
}

void hld_draw(const fl_hlv_t *hv, const fl_obs_list_t *obs, uint8_t *rgb, int width, int height,
              const fl_camera_t *cam)
{
    if (!hv || !rgb)
        return;
    draw_mask(hv, rgb, width, height);
    draw_objects(hv, rgb, width, height);
    if (obs)
        draw_obs(obs, rgb, width, height, cam);
}

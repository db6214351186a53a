/*
 * src/vision/lines.c - line stage set-up and queries: parameters, init,
 * per-frame reset, points added by hand, the bucket grid of the points and
 * its neighbourhood query (lines_int.h for the algorithm; lines.h for the
 * method).  Cold code: the per-pixel and per-point loops stay in
 * lines_points.c and lines_segments.c.
 */
#include "lines_int.h"

#include <string.h>


/* ---- parameters, init, reset ----------------------------------------------- */

void fl_lines_params_default(fl_lines_params_t *p)
{
    if (!p)
        return;
    p->step_px = 0;
    p->gap_px = 0;
    p->min_points = 3;
    p->min_len_px = 0;
    p->err_base_q2 = 16;
    p->err_point_q2 = 4;
    p->white_pct = 70;
    p->merge_gap_px = 0;
    p->max_width_pct = 400;
    p->min_width_pct = 25;
    p->luma_contrast_pct = 12;
    p->luma_width_px = 3;
}

static bool ln_params_ok(const fl_lines_params_t *p)
{
    return p->step_px >= 0 && p->step_px <= 64 &&
           (p->gap_px == 0 || (p->gap_px >= 2 && p->gap_px <= 255)) &&
           p->min_points >= 2 && p->min_points <= 255 &&
           p->min_len_px >= 0 && p->min_len_px <= 4096 &&
           p->err_base_q2 >= 0 && p->err_base_q2 <= 65535 &&
           p->err_point_q2 >= 0 && p->err_point_q2 <= 65535 &&
           p->white_pct >= 0 && p->white_pct <= 100 &&
           p->merge_gap_px >= 0 && p->merge_gap_px <= 4096 &&
           p->max_width_pct >= 100 && p->max_width_pct <= 2000 &&
           p->min_width_pct >= 0 && p->min_width_pct <= 100 &&
           p->luma_contrast_pct >= 0 && p->luma_contrast_pct <= 100 &&
           p->luma_width_px >= 1 && p->luma_width_px <= 16;
}

fl_status_t fl_lines_init_cfg(fl_lines_t *l, const fl_lines_params_t *p, uint32_t caller_cfg)
{
    if (caller_cfg != FL_CONFIG_FINGERPRINT)
        return FL_ERR_CONFIG;   /* *l has another layout: no write is safe */
    if (!l || !p)
        return FL_ERR_NULL;
    memset(l, 0, sizeof *l);
    fl_lines_params_default(&l->params);
    if (!ln_params_ok(p))
        return FL_ERR_RANGE;
    l->params = *p;
    return FL_OK;
}

/* Effective step / gap for an image width. */
static void ln_effective(fl_lines_t *l, int32_t width)
{
    int32_t step = l->params.step_px;
    if (step <= 0) {
        step = width / 80;
        if (step < 2)
            step = 2;
    }
    l->step_px = step;
    l->gap_px = l->params.gap_px > 0 ? l->params.gap_px : 3 * step;
    if (l->gap_px > 255)
        l->gap_px = 255;
}

bool fl_lines_reset(fl_lines_t *l, int32_t width, int32_t height)
{
    if (!l)
        return false;
    l->n_points = 0;
    l->n_segments = 0;
    l->points_dropped = 0;
    l->runs_rejected = 0;
    l->segments_dropped = 0;
    l->merges = 0;
    l->white_checks = 0;
    l->checks_capped = 0;
    l->luma_points = 0;
    l->luma_capped = 0;
    l->ridge_checks = 0;
    l->robot_rejected = 0;
    l->robot_spans = 0;
    l->rob_step = 0;
    l->img.width = l->img.height = 0;
    l->lum_vend = l->lum_hend = -1;
    l->line_width_mm = 0;
    l->bcols = l->brows = 0;
    if (width < 1 || height < 1 || width > FL_IMAGE_MAX_DIM ||
        height > FL_IMAGE_MAX_DIM) {
        l->width = l->height = 0;
        return false;
    }
    l->width = width;
    l->height = height;
    ln_effective(l, width);
    return true;
}

bool fl_lines_add_point(fl_lines_t *l, int32_t u_q1, int32_t v_q1,
                        int32_t width_px, uint8_t flags)
{
    fl_line_point_t *pt;
    if (!l || l->width <= 0)
        return false;
    if (u_q1 < 0 || v_q1 < 0 || u_q1 > 2 * (l->width - 1) ||
        v_q1 > 2 * (l->height - 1))
        return false;
    if (l->n_points >= FL_LINES_MAX_POINTS) {
        l->points_dropped++;
        return false;
    }
    pt = &l->points[l->n_points++];
    pt->u_q1 = (int16_t)u_q1;
    pt->v_q1 = (int16_t)v_q1;
    pt->width_px = (uint8_t)(width_px < 0 ? 0 : width_px > 255 ? 255 : width_px);
    pt->flags = (uint8_t)(flags & (FL_LINE_POINT_VERTICAL | FL_LINE_POINT_LUMA));
    pt->seg = FL_LINES_NONE;
    return true;
}


/* ---- bucket grid ----------------------------------------------------------- */

void fl_lines_int_buckets(fl_lines_t *l)
{
    int32_t shift = 2, nb, k;
    while ((1 << shift) < l->gap_px)
        shift++;
    for (;;) {
        l->bcols = ((l->width - 1) >> shift) + 1;
        l->brows = ((l->height - 1) >> shift) + 1;
        if (l->bcols * l->brows <= FL_LINES_MAX_BUCKETS)
            break;
        shift++;
    }
    l->bshift = shift;
    nb = l->bcols * l->brows;
    memset(l->bstart, 0, (size_t)(nb + 1) * sizeof l->bstart[0]);
    for (k = 0; k < l->n_points; k++) {
        const fl_line_point_t *p = &l->points[k];
        int32_t b = ((p->v_q1 >> 1) >> shift) * l->bcols + ((p->u_q1 >> 1) >> shift);
        l->bstart[b + 1]++;
    }
    for (k = 0; k < nb; k++)
        l->bstart[k + 1] = (uint16_t)(l->bstart[k + 1] + l->bstart[k]);
    /* stable fill; bstart[b] is advanced and restored below */
    for (k = 0; k < l->n_points; k++) {
        const fl_line_point_t *p = &l->points[k];
        int32_t b = ((p->v_q1 >> 1) >> shift) * l->bcols + ((p->u_q1 >> 1) >> shift);
        l->border[l->bstart[b]++] = (uint16_t)k;
    }
    for (k = nb; k > 0; k--)
        l->bstart[k] = l->bstart[k - 1];
    l->bstart[0] = 0;
}

int32_t fl_lines_points_near(const fl_lines_t *l, int32_t u_q1, int32_t v_q1,
                             int32_t ru_px, int32_t rv_px, uint16_t *ids)
{
    int32_t b0u, b1u, b0v, b1v, x, y, n = 0, ru, rv;
    if (!l || l->width <= 0 || l->bcols <= 0 || ru_px < 0 || rv_px < 0)
        return 0;
    if (u_q1 < 0 || v_q1 < 0 || u_q1 > 2 * (l->width - 1) || v_q1 > 2 * (l->height - 1))
        return 0;
    if (ru_px > l->width)
        ru_px = l->width;
    if (rv_px > l->height)
        rv_px = l->height;
    ru = 2 * ru_px;
    rv = 2 * rv_px;
    b0u = ((u_q1 - ru) < 0 ? 0 : (u_q1 - ru) >> 1) >> l->bshift;
    b1u = ((u_q1 + ru) >> 1) >> l->bshift;
    b0v = ((v_q1 - rv) < 0 ? 0 : (v_q1 - rv) >> 1) >> l->bshift;
    b1v = ((v_q1 + rv) >> 1) >> l->bshift;
    if (b1u >= l->bcols)
        b1u = l->bcols - 1;
    if (b1v >= l->brows)
        b1v = l->brows - 1;
    for (y = b0v; y <= b1v; y++) {
        for (x = b0u; x <= b1u; x++) {
            int32_t b = y * l->bcols + x, k;
            for (k = l->bstart[b]; k < l->bstart[b + 1]; k++) {
                const fl_line_point_t *p = &l->points[l->border[k]];
                int32_t du = p->u_q1 - u_q1, dv = p->v_q1 - v_q1;
                if (du > ru || du < -ru || dv > rv || dv < -rv)
                    continue;
                if (ids && n < FL_LINES_NEAR_MAX)
                    ids[n] = l->border[k];
                n++;
            }
        }
    }
    return n;
}

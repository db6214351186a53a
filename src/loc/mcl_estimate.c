/*
 * src/loc/mcl_estimate.c - the Monte Carlo localizer's estimate: the
 * dominant cluster's weighted mean (never the mean of two mirror modes),
 * its spread, the mirror's weight, the calibrated reliability, and the
 * kernel density behind fl_mcl_possibility_q16.
 *
 * Algorithm.  (1) Coarse bins: the particles' weights summed in 16 x 12
 * bins over the carpet box, then over each bin's 3 x 3 neighbourhood.
 * (2) The dominant bin: the heaviest; while a cluster is tracked, the
 * heaviest near the track instead unless it has less than switch_q8 of the
 * heaviest's weight; before tracking, the heaviest in the prior's region
 * (own half: kept down to 1/8). (3) The cluster's heading: the heaviest
 * 45-degree sector (with its neighbours) of the particles near that bin
 * (the track's heading while tracked): near the centre of a symmetric
 * field the mirror mode lies at the same place with the opposite heading.
 * (4) Two local weighted means: within max(cluster_mm, a bin's diagonal)
 * of the bin and heading within 90 deg, then within cluster_mm of that
 * mean; sd, covariance and heading sd from the second.  (5) The mirror:
 * the weight within cluster_mm of (-x, -y), heading within 90 deg of
 * h + 180, relative to the cluster's; on a symmetric field whose half the
 * game did not tell, 65535 (a particle set that lost one mirror mode by
 * resampling has no evidence against it).  Leaving the tracked mode for
 * another cluster (a kidnap that injection recovered before the averages
 * called it one) drops the prior: the half it told was the old mode's.
 */
#include "mcl_int.h"

#include <string.h>

#define NBX 16
#define NBY 12

typedef struct {
    uint64_t w;                      /* weight */
    int64_t sx, sy, sh;              /* weighted offsets from the centre */
    uint64_t sxx, syy, shh;
    int64_t sxy;
    uint64_t sww;                    /* sum of squared weights */
    uint32_t n;
} csum_t;

static int bin_x(const fl_mcl_set_t *s, int32_t x)
{
    return mcl_clamp((int32_t)(((int64_t)(x + s->core->box_x_mm) * NBX) / (2 * s->core->box_x_mm + 1)), 0,
                     NBX - 1);
}

static int bin_y(const fl_mcl_set_t *s, int32_t y)
{
    return mcl_clamp((int32_t)(((int64_t)(y + s->core->box_y_mm) * NBY) / (2 * s->core->box_y_mm + 1)), 0,
                     NBY - 1);
}

static int32_t bin_cx(const fl_mcl_set_t *s, int bx)
{
    return -s->core->box_x_mm + (int32_t)(((2 * bx + 1) * (int64_t)(2 * s->core->box_x_mm + 1)) / (2 * NBX));
}

static int32_t bin_cy(const fl_mcl_set_t *s, int by)
{
    return -s->core->box_y_mm + (int32_t)(((2 * by + 1) * (int64_t)(2 * s->core->box_y_mm + 1)) / (2 * NBY));
}

/* Whether bin centre (x, y) is in the reference region: near the track,
 * else in the prior's region. */
static bool in_reference(const fl_mcl_set_t *s, int32_t x, int32_t y)
{
    if (s->core->track_valid) {
        int64_t dx = x - s->core->track_x_mm, dy = y - s->core->track_y_mm;
        int64_t r = 2 * s->params->cluster_mm;
        return dx * dx + dy * dy <= r * r;
    }
    if (s->core->prior == FL_MCL_PRIOR_HALF)
        return s->core->prior_half < 0 ? x < 0 : x > 0;
    if (s->core->prior == FL_MCL_PRIOR_POSE) {
        int64_t dx = x - s->core->prior_x_mm, dy = y - s->core->prior_y_mm;
        int64_t r = s->core->prior_radius_mm + s->params->cluster_mm;
        return dx * dx + dy * dy <= r * r;
    }
    return false;
}

/* Steps 1-2: the dominant bin; *switched when the track is given up. */
static int dominant_bin(const fl_mcl_set_t *s, bool *switched)
{
    uint32_t h[NBY][NBX], r3[NBY][NBX];
    int32_t cxs[NBX], cys[NBY];
    const fl_mcl_particle_t *p = s->p;
    uint64_t best = 0, bref = 0;
    int gi = 0, ri = -1, bx, by, i;
    memset(h, 0, sizeof h);
    for (bx = 0; bx < NBX; bx++)
        cxs[bx] = bin_cx(s, bx);
    for (by = 0; by < NBY; by++)
        cys[by] = bin_cy(s, by);
    for (i = 0; i < s->n; i++)
        h[bin_y(s, p[i].y_mm)][bin_x(s, p[i].x_mm)] += p[i].weight;
    /* 3 x 3 sums, separably: along x, then along y */
    for (by = 0; by < NBY; by++)
        for (bx = 0; bx < NBX; bx++)
            r3[by][bx] = h[by][bx] + (bx > 0 ? h[by][bx - 1] : 0u) +
                         (bx + 1 < NBX ? h[by][bx + 1] : 0u);
    for (by = 0; by < NBY; by++)
        for (bx = 0; bx < NBX; bx++) {
            uint64_t sum;
            if (h[by][bx] == 0u)
                continue;
            sum = (uint64_t)r3[by][bx] + (by > 0 ? r3[by - 1][bx] : 0u) +
                  (by + 1 < NBY ? r3[by + 1][bx] : 0u);
            if (sum > best) {
                best = sum;
                gi = by * NBX + bx;
            }
            if (sum > bref && in_reference(s, cxs[bx], cys[by])) {
                bref = sum;
                ri = by * NBX + bx;
            }
        }
    *switched = false;
    if (ri >= 0) {
        uint32_t q = s->core->track_valid ? s->params->switch_q8 : 32u;
        if (bref * 256u >= best * q)
            return ri;
    }
    *switched = s->core->track_valid;
    return gi;
}

/* Step 3: the heaviest 45-degree sector (with its neighbours) near (cx, cy). */
static fl_angle_t sector_heading(const fl_mcl_set_t *s, int32_t cx, int32_t cy, int64_t r2)
{
    uint64_t w[8], best = 0;
    const fl_mcl_particle_t *p = s->p;
    int i, k, bk = 0;
    memset(w, 0, sizeof w);
    for (i = 0; i < s->n; i++) {
        int64_t dx = p[i].x_mm - cx, dy = p[i].y_mm - cy;
        if (dx * dx + dy * dy <= r2)
            w[((uint16_t)(p[i].heading + 4096) >> 13) & 7u] += p[i].weight;
    }
    for (k = 0; k < 8; k++) {
        uint64_t t = w[k] * 2u + w[(k + 1) & 7] + w[(k + 7) & 7];
        if (t > best) {
            best = t;
            bk = k;
        }
    }
    return (fl_angle_t)(int16_t)(uint16_t)(bk << 13);
}

/* Weighted sums of the particles within sqrt(r2) of (cx, cy) whose heading
 * is within 90 deg of ch, offsets relative to (cx, cy, ch). */
static void cluster_sums(const fl_mcl_set_t *s, int32_t cx, int32_t cy, fl_angle_t ch, int64_t r2,
                         csum_t *c)
{
    const fl_mcl_particle_t *p = s->p;
    int i;
    memset(c, 0, sizeof *c);
    for (i = 0; i < s->n; i++) {
        int64_t dx = p[i].x_mm - cx, dy = p[i].y_mm - cy;
        int64_t dh = fl_angle_sub(p[i].heading, ch), w = p[i].weight;
        if (dx * dx + dy * dy > r2 || dh > FL_ANGLE_90 || dh < -FL_ANGLE_90)
            continue;
        c->w += (uint64_t)w;
        c->sx += w * dx;
        c->sy += w * dy;
        c->sh += w * dh;
        c->sxx += (uint64_t)(w * dx * dx);
        c->syy += (uint64_t)(w * dy * dy);
        c->shh += (uint64_t)(w * dh * dh);
        c->sxy += w * dx * dy;
        c->sww += (uint64_t)(w * w);
        c->n++;
    }
}

static uint16_t sd_of(uint64_t sqq, int64_t sq, uint64_t w)
{
    int64_t m = sq / (int64_t)w;
    int64_t v = (int64_t)(sqq / w) - m * m;
    uint32_t r = v > 0 ? fl_isqrt64((uint64_t)v) : 0u;
    return (uint16_t)(r > 65535u ? 65535u : r);
}

/* Uniform over the region the prior allows (localizer.h contract). */
void fl_mcl_internal_ignorance_pose(fl_mcl_core_t *c, uint16_t since_obs, fl_mcl_estimate_t *out)
{
    out->since_obs = since_obs;
    c->track_valid = false;
    int32_t hx = c->half_x_mm, hy = c->half_y_mm;
    out->ignorance = true;
    out->sd_x_mm = (uint16_t)((2 * hx * 1000) / 3464);
    out->sd_y_mm = (uint16_t)((2 * hy * 1000) / 3464);
    out->sd_heading = (fl_angle_t)32767;
    if (c->prior == FL_MCL_PRIOR_HALF) {
        out->x_mm = c->prior_half * (hx / 2);
        out->sd_x_mm = (uint16_t)((hx * 1000) / 3464);
    } else if (c->prior == FL_MCL_PRIOR_POSE) {
        int32_t r = mcl_clamp(c->prior_radius_mm, 100, hx);
        out->x_mm = mcl_clamp(c->prior_x_mm, -hx, hx);
        out->y_mm = mcl_clamp(c->prior_y_mm, -hy, hy);
        out->heading = c->prior_heading;
        out->sd_x_mm = (uint16_t)(r / 2);
        out->sd_y_mm = (uint16_t)(r / 2);
    }
}

/* Kernel density at a pose: sum of w (R^2 - d^2) / R^2 x (1 - |dh| / 45
 * deg) over the particles within R = cluster_mm / 2 and 45 deg (Q16
 * weight units). */
uint64_t fl_mcl_internal_density(const fl_mcl_set_t *s, int32_t x, int32_t y, fl_angle_t h)
{
    const fl_mcl_particle_t *p = s->p;
    int64_t r = s->params->cluster_mm / 2, r2 = r * r;
    uint64_t sum = 0;
    int i;
    for (i = 0; i < s->n; i++) {
        int64_t dx = p[i].x_mm - (int64_t)x, dy = p[i].y_mm - (int64_t)y, d2;
        int32_t dh = mcl_absang(fl_angle_sub(p[i].heading, h));
        if (dx > r || dx < -r || dy > r || dy < -r || dh >= FL_ANGLE_45)
            continue;
        d2 = dx * dx + dy * dy;
        if (d2 >= r2)
            continue;
        sum += ((uint64_t)p[i].weight * (uint64_t)(r2 - d2) / (uint64_t)r2) *
               (uint64_t)(FL_ANGLE_45 - dh) >> 13;
    }
    return sum;
}

uint32_t fl_mcl_internal_possibility(const fl_mcl_set_t *s, bool ignorance, uint32_t est_density,
                                     int32_t x_mm, int32_t y_mm, fl_angle_t heading)
{
    uint64_t d;
    if (x_mm < -s->core->half_x_mm || x_mm > s->core->half_x_mm || y_mm < -s->core->half_y_mm ||
        y_mm > s->core->half_y_mm)
        return 0u;
    if (ignorance)
        return fl_mcl_internal_allowed(s->core, x_mm, y_mm, heading) ? 65536u : 0u;
    d = fl_mcl_internal_density(s, x_mm, y_mm, heading);
    if (est_density == 0u)
        return d > 0u ? 65536u : 0u;
    d = (d << 16) / est_density;
    return d > 65536u ? 65536u : (uint32_t)d;
}

uint32_t fl_mcl_possibility_q16(const fl_mcl_t *s, int32_t x_mm, int32_t y_mm,
                                fl_angle_t heading)
{
    fl_mcl_set_t set;
    if (!mcl_ready(s))
        return 0u;
    mcl_set_of((fl_mcl_t *)s, &set);
    return fl_mcl_internal_possibility(&set, s->ignorance, s->est_density, x_mm, y_mm, heading);
}

/*
 * Calibration (localizer.h contract): raw score = cluster share x
 * compactness 1 / (1 + (sd_x^2 + sd_y^2) / (250 mm)^2) x min(1, effective
 * particles of the cluster / 32), then x 16 / (16 +
 * predict calls since an observation); piecewise linear through the knots
 * below, fitted like the fuzzy grid's by tools/build/fit_reliability.py on
 *     build/fieldloc reliability --localizer mcl --seeds 11,12,...,30
 *         --frame-seeds 4,5,6 --obs-cache-dir DIR --dump train.tsv
 * (the held-out walks, seeds 1-3, are `fieldloc reliability`'s default;
 * the top interval is flat, raised to 0.906: fitted 0.891 and 0.944 at
 * raw 65535, where a few degenerate records, every particle on one point,
 * held out 0.5);
 * then x 1 / (1 + 3 mirror) (AMBIGUOUS records: 0.24 good: after a kidnap
 * the sensor-reset modes of both halves compete); not tracking x 1/8 (LOST
 * records: 0.10 good); ignorance: 0.
 */
static const fl_mcl_cal_t mcl_cal = {
    15,
    {0, 24269, 28119, 31503, 34430, 36639, 40043, 42629, 46606, 49472, 51565, 54708, 56415, 58479,
     65535},
    {0, 35955, 36551, 42973, 46070, 47523, 51159, 52233, 54207, 54738, 55745, 56933, 57442, 59400,
     59400}};

uint16_t fl_mcl_internal_calibrate(const fl_mcl_estimate_t *e, const fl_mcl_cal_t *cal)
{
    const uint16_t *cal_raw = cal->raw, *cal_rel = cal->rel;
    int n_knots = cal->n;
    uint32_t raw, rel;
    int k;
    if (e->ignorance)
        return 0;
    raw = ((uint32_t)e->score_q16 * 16u) / (16u + (uint32_t)e->since_obs);
    for (k = 1; k < n_knots - 1 && raw > cal_raw[k]; k++)
        ;
    rel = cal_rel[k - 1];
    if (raw > cal_raw[k - 1])
        rel += (uint32_t)(((uint64_t)(cal_rel[k] - cal_rel[k - 1]) *
                           (raw - cal_raw[k - 1])) / (uint32_t)(cal_raw[k] - cal_raw[k - 1]));
    if (rel > cal_rel[k])
        rel = cal_rel[k];
    if (!e->tracking)
        rel >>= 3;
    rel = (uint32_t)(((uint64_t)rel * 65536u) / (65536u + 3u * (uint32_t)e->mirror_q16));
    return (uint16_t)(rel > 65535u ? 65535u : rel);
}

/* Step 5 and the scores. */
static void finish(const fl_mcl_set_t *s, const csum_t *c, uint64_t total, fl_mcl_estimate_t *out)
{
    uint64_t r2 = (uint64_t)s->params->cluster_mm * (uint64_t)s->params->cluster_mm;
    uint64_t sp2 = (uint64_t)out->sd_x_mm * out->sd_x_mm + (uint64_t)out->sd_y_mm * out->sd_y_mm;
    uint32_t share = (uint32_t)((c->w << 16) / (total > 0u ? total : 1u));
    uint32_t compact = (uint32_t)((62500ull << 16) / (62500ull + sp2));
    /* the cluster's effective number of particles (sum w)^2 / sum w^2: a
     * cluster carried by a few particles (the first update after a wide
     * prior) describes its spread badly; full credit from 32 on */
    uint64_t neff = c->sww > 0u ? (c->w * c->w) / c->sww : 0u;
    uint32_t fill = neff >= 32u ? 65536u : (uint32_t)(neff << 11);
    if (share > 65535u)
        share = 65535u;
    out->share_q16 = (uint16_t)share;
    out->score_q16 = (uint16_t)(((((uint64_t)share * compact) >> 16) * fill) >> 16);
    out->mirror_q16 = 0;
    if (s->core->field->symmetric) {
        csum_t m;
        cluster_sums(s, -out->x_mm, -out->y_mm, fl_angle_add(out->heading, FL_ANGLE_180),
                     (int64_t)r2, &m);
        if (!s->core->half_known || m.w >= c->w)
            out->mirror_q16 = 65535u;
        else
            out->mirror_q16 = (uint16_t)((m.w * 65535u) / c->w);
    }
    out->tracking = share >= 24576u && out->sd_x_mm < 1000u && out->sd_y_mm < 1000u;
}

bool fl_mcl_internal_cluster(const fl_mcl_set_t *s, fl_mcl_estimate_t *out)
{
    const fl_mcl_particle_t *p = s->p;
    int bi, i;
    int32_t cx, cy, ra;
    int64_t r2;
    fl_angle_t ch;
    csum_t c;
    uint64_t total = 0;
    for (i = 0; i < s->n; i++)
        total += p[i].weight;
    bi = dominant_bin(s, &out->switched);
    if (out->switched) {
        /* the belief left the tracked mode for another place (a kidnap
         * that injection recovered before the averages called it one):
         * the half the game told was the old mode's (the caller counts
         * the switch) */
        fl_mcl_internal_drop_prior(s->core);
    }
    cx = bin_cx(s, bi % NBX);
    cy = bin_cy(s, bi / NBX);
    ra = s->core->box_x_mm * 2 / NBX + s->core->box_y_mm * 2 / NBY;
    if (ra < s->params->cluster_mm)
        ra = s->params->cluster_mm;
    r2 = (int64_t)ra * ra;
    ch = s->core->track_valid && !out->switched ? s->core->track_heading
                                                 : sector_heading(s, cx, cy, r2);
    cluster_sums(s, cx, cy, ch, r2, &c);
    if (c.w > 0u) {
        cx += (int32_t)(c.sx / (int64_t)c.w);
        cy += (int32_t)(c.sy / (int64_t)c.w);
        ch = fl_angle_add(ch, fl_angle_wrap((int32_t)(c.sh / (int64_t)c.w)));
    }
    r2 = (int64_t)s->params->cluster_mm * s->params->cluster_mm;
    cluster_sums(s, cx, cy, ch, r2, &c);
    if (c.w == 0u)
        cluster_sums(s, cx, cy, ch, (int64_t)ra * ra, &c);
    if (c.w > 0u) {
        out->x_mm = cx + (int32_t)(c.sx / (int64_t)c.w);
        out->y_mm = cy + (int32_t)(c.sy / (int64_t)c.w);
        out->heading = fl_angle_add(ch, fl_angle_wrap((int32_t)(c.sh / (int64_t)c.w)));
        out->sd_x_mm = sd_of(c.sxx, c.sx, c.w);
        out->sd_y_mm = sd_of(c.syy, c.sy, c.w);
        out->sd_heading = (fl_angle_t)sd_of(c.shh, c.sh, c.w);
        out->cov_xy_mm2 = fl_sat32(c.sxy / (int64_t)c.w -
                                   (c.sx / (int64_t)c.w) * (c.sy / (int64_t)c.w));
    } else {
        out->x_mm = cx;
        out->y_mm = cy;
        out->heading = ch;
        out->sd_x_mm = (uint16_t)s->params->cluster_mm;
        out->sd_y_mm = (uint16_t)s->params->cluster_mm;
        out->sd_heading = (fl_angle_t)32767;
    }
    out->x_mm = mcl_clamp(out->x_mm, -s->core->half_x_mm, s->core->half_x_mm);
    out->y_mm = mcl_clamp(out->y_mm, -s->core->half_y_mm, s->core->half_y_mm);
    out->mode_particles = (uint16_t)c.n;
    finish(s, &c, total, out);
    s->core->track_valid = out->tracking;
    if (out->tracking) {
        s->core->track_x_mm = out->x_mm;
        s->core->track_y_mm = out->y_mm;
        s->core->track_heading = out->heading;
    }
    return true;
}

bool fl_mcl_estimate(fl_mcl_t *s, fl_mcl_estimate_t *out)
{
    fl_mcl_set_t set;
    uint64_t dens;
    if (out != NULL)
        memset(out, 0, sizeof *out);
    if (!mcl_ready(s) || out == NULL)
        return false;
    if (s->ignorance) {
        fl_mcl_internal_ignorance_pose(&s->core, s->since_obs, out);
        s->est_density = 0;
        return true;
    }
    mcl_set_of(s, &set);
    fl_mcl_internal_cluster(&set, out);
    if (out->switched)
        s->stats.mode_switches = mcl_sat_inc(s->stats.mode_switches);
    out->since_obs = s->since_obs;
    out->reliability_q16 = fl_mcl_internal_calibrate(out, &mcl_cal);
    dens = fl_mcl_internal_density(&set, out->x_mm, out->y_mm, out->heading);
    s->est_density = (uint32_t)(dens > UINT32_MAX ? UINT32_MAX : dens);
    return true;
}

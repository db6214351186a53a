/*
 * src/loc/mcl_update.c - the Monte Carlo localizer's sensor model (seed 000
 * section 4.2) and the likelihood averages of augmented MCL (section 4.4).
 *
 * Per observation, once: its robot-frame vector (r cos b, r sin b) and
 * direction, the scales 128 / sd^2 of its range and bearing terms, the
 * landmarks it may be (its kind, colour and side).  Per particle and
 * observation: the observation's field point from the particle's pose
 * (table sin/cos of the particle's heading, once per particle), the
 * nearest landmark of the kind, and the field-frame error split along and
 * across the particle's ray: along ~ the range difference, across / r ~
 * the bearing difference (first order; no atan2 or hypot per particle).
 * Negative log-likelihood (Q8 nats, 256 = 1 nat) of the Gaussian terms
 * q = (along / sd_r)^2 / 2 + (across / (r sd_b))^2 / 2 [+ (d1/d2 / sd_s)^2 / 2]
 * [+ (orientation difference / sd_o)^2 / 2], then the outlier floor:
 * -ln((1 - eps) e^-q + eps) from a per-frame table of quarter nats.
 * Summed over the observations; the weights are exp(min - nll) (heaviest
 * 65535): no underflow whatever the number of observations.
 *
 * sd_s, the association certainty (seed 000 leaves it undefined): the
 * certainty of having associated the right landmark is taken as 1 - d1/d2,
 * with d1 and d2 the distances from the observation's field point to the
 * nearest and second-nearest candidate landmark; the detector claims
 * certainty 1, so the difference is d1/d2 (0: unambiguous, 1: midway
 * between two candidates).  Off by default (assoc_q8 0): measured no
 * better (DESIGN.md).
 *
 * w_avg (Probabilistic Robotics Algorithm 3 line 10): the mean over the
 * particles of the geometric mean of their per-observation likelihoods,
 * exp(-nll / n_obs), absolute (before renormalisation): a frame's product
 * over all observations would shrink with their number and inject almost
 * constantly.  w_slow and w_fast are never reset by an injection.
 */
#include "mcl_int.h"

#include <string.h>

/* Observations applied per frame at most (bounds the work; the rest are
 * counted as ignored). */
#define MCL_OBS_PER_FRAME 16

/* e^-i in Q30 (i = 0..11 nats), e^(-f/256) in Q15 at f = 0, 8, ..., 256,
 * ln(1 + k/32) in Q12 (k = 0..32); generated with Python's math module. */
static const uint32_t exp_int_q30[12] = {
    1073741824u, 395007542u, 145315154u, 53458458u,
    19666268u, 7234816u, 2661540u, 979126u,
    360200u, 132510u, 48748u, 17933u,
};
static const uint16_t exp_frac_q15[33] = {
    32768u, 31760u, 30783u, 29836u, 28918u, 28028u, 27166u, 26330u, 25520u, 24735u, 23974u,
    23236u, 22521u, 21828u, 21157u, 20506u, 19875u, 19263u, 18671u, 18096u, 17539u, 17000u,
    16477u, 15970u, 15479u, 15002u, 14541u, 14093u, 13660u, 13239u, 12832u, 12437u, 12055u,
};
static const uint16_t ln1p_q12[33] = {
    0u, 126u, 248u, 367u, 482u, 595u, 704u, 810u, 914u, 1015u, 1114u,
    1210u, 1304u, 1396u, 1486u, 1575u, 1661u, 1745u, 1828u, 1909u, 1989u, 2067u,
    2143u, 2218u, 2292u, 2365u, 2436u, 2506u, 2575u, 2642u, 2709u, 2775u, 2839u,
};

/* e^(-nll) in Q16 (65536 = 1) for nll in Q8 nats; 0 beyond 12 nats. */
uint32_t fl_mcl_internal_exp_q16(uint32_t nll_q8)
{
    uint32_t i = nll_q8 >> 8, f = nll_q8 & 255u, k = f >> 3, t = f & 7u;
    uint32_t frac;
    if (i >= 12u)
        return 0u;
    frac = exp_frac_q15[k] - (((uint32_t)(exp_frac_q15[k] - exp_frac_q15[k + 1]) * t) >> 3);
    return (uint32_t)(((uint64_t)exp_int_q30[i] * frac + (1u << 28)) >> 29);
}

/* -ln(x / 65536) in Q8 nats for x in [1, 65536]. */
static uint32_t neg_ln_q8(uint32_t x)
{
    int k = 16;
    uint32_t t, j, r, ln;
    if (x == 0u)
        x = 1u;
    if (x >= 65536u)
        return 0u;
    while (!(x & (1u << k)))
        k--;
    /* x = 2^k (1 + t / 2^k) */
    t = x - (1u << k);
    t = k >= 10 ? t >> (k - 10) : t << (10 - k);        /* t in Q10 */
    j = t >> 5;
    r = t & 31u;
    ln = ln1p_q12[j] + (((uint32_t)(ln1p_q12[j + 1] - ln1p_q12[j]) * r) >> 5);
    /* (16 - k) ln 2 - ln(1 + t), Q12 -> Q8 */
    return ((uint32_t)(16 - k) * 2839u - ln + 8u) >> 4;
}

/* The floor table: F[j] = -ln((1 - eps) e^(-j/4) + eps) in Q8, j = 0..64. */
#define MIX_N FL_MCL_MIX_N
void fl_mcl_internal_mixture_table(uint16_t eps_q16, uint16_t *tab)
{
    uint32_t j;
    for (j = 0; j < MIX_N; j++) {
        uint32_t g = fl_mcl_internal_exp_q16(j * 64u);
        uint32_t l = (uint32_t)(((uint64_t)(65536u - eps_q16) * g) >> 16) + eps_q16;
        tab[j] = (uint16_t)neg_ln_q8(l);
    }
}

uint32_t fl_mcl_internal_mixture(const uint16_t *tab, uint32_t q)
{
    uint32_t j, f;
    if (q >= (MIX_N - 1) * 64u)
        return tab[MIX_N - 1];
    j = q >> 6;
    f = q & 63u;
    return (uint32_t)((int32_t)tab[j] + mcl_asr(((int32_t)tab[j + 1] - (int32_t)tab[j]) * (int32_t)f, 6));
}

/* ---- association -------------------------------------------------------- */

static bool lm_matches(const fl_landmark_t *lm, const fl_obs_t *o)
{
    if (o->side != FL_SIDE_UNKNOWN && lm->side != FL_SIDE_UNKNOWN && lm->side != o->side)
        return false;
    if (o->color != FL_COLOR_NONE && lm->color != FL_COLOR_NONE && lm->color != o->color)
        return false;
    if (o->color2 != FL_COLOR_NONE && lm->color2 != FL_COLOR_NONE && lm->color2 != o->color2)
        return false;
    return true;
}

int fl_mcl_associate(const fl_mcl_t *s, const fl_obs_t *o, int32_t fx, int32_t fy,
                     uint32_t *d1, uint32_t *d2)
{
    return fl_mcl_core_associate(s != NULL ? &s->core : NULL, o, fx, fy, d1, d2);
}

int fl_mcl_core_associate(const fl_mcl_core_t *c, const fl_obs_t *o, int32_t fx, int32_t fy,
                          uint32_t *d1, uint32_t *d2)
{
    uint32_t b1 = UINT32_MAX, b2 = UINT32_MAX;
    int best = -1, k, a, e;
    if (d1 != NULL)
        *d1 = UINT32_MAX;
    if (d2 != NULL)
        *d2 = UINT32_MAX;
    if (c == NULL || c->field == NULL || o == NULL || (int)o->kind < 0 || o->kind >= FL_LM_KIND_COUNT)
        return -1;
    k = (int)o->kind;
    fx = mcl_clamp(fx, -40000, 40000);
    fy = mcl_clamp(fy, -40000, 40000);
    for (a = c->kind_start[k], e = c->kind_start[k + 1]; a < e; a++) {
        const fl_landmark_t *lm = fl_field_all_at(c->field, c->lm_index[a]);
        int32_t dx = lm->x_mm - fx, dy = lm->y_mm - fy;
        uint32_t d;
        if (!lm_matches(lm, o))
            continue;
        dx = mcl_clamp(dx, -46000, 46000);
        dy = mcl_clamp(dy, -46000, 46000);
        d = (uint32_t)(dx * dx) + (uint32_t)(dy * dy);
        if (d < b1) {
            b2 = b1;
            b1 = d;
            best = c->lm_index[a];
        } else if (d < b2) {
            b2 = d;
        }
    }
    if (d1 != NULL)
        *d1 = b1;
    if (d2 != NULL)
        *d2 = b2;
    return best;
}

/* ---- the update ------------------------------------------------------------ */


/* Whether the observation is usable, and its constants. */
bool fl_mcl_internal_prepare(const fl_mcl_core_t *pc, const fl_mcl_params_t *p,
                             const fl_obs_t *o, fl_mcl_obs_c_t *c)
{
    int32_t r = o->range_mm;
    int64_t sa;
    int k, a;
    if (o->confidence == 0 || (int)o->kind < 0 || o->kind >= FL_LM_KIND_COUNT || r < 0 ||
        r > p->max_range_mm || r > FL_OBS_MAX_RANGE_MM)
        return false;
    /* crossings: L, T, X and seed 004's corner features (not its nets) */
    if (p->cross_max_mm > 0 && r > p->cross_max_mm &&
        (o->kind <= FL_LM_X || (fl_landmark_kind_is_feature(o->kind) && o->kind != FL_LM_NET)))
        return false;
    k = (int)o->kind;
    c->n_cand = 0;
    {
        /* params.corner_any: for seed 004's corner kinds every corner
         * feature is a candidate (the image stage types a pair by the lines
         * it sees leave it, and a faint stem or an unseen net changes the
         * type; aibo2004 frames, corners alone, seed 1: 436 mm position
         * RMSE with the observed kind only, 56 mm with any corner) */
        const bool corner = p->corner_any && (o->kind == FL_LM_CORNER_C ||
                                              o->kind == FL_LM_CORNER_TFIELD ||
                                              o->kind == FL_LM_CORNER_TNET);
        const int k0 = corner ? (int)FL_LM_CORNER_C : k, k1 = corner ? (int)FL_LM_CORNER_TNET : k;
        for (a = pc->kind_start[k0]; a < pc->kind_start[k1 + 1]; a++) {
            const fl_landmark_t *lm = fl_field_all_at(pc->field, pc->lm_index[a]);
            if (!corner && !lm_matches(lm, o))
                continue;
            c->cx[c->n_cand] = (int16_t)mcl_clamp(lm->x_mm, -20000, 20000);
            c->cy[c->n_cand] = (int16_t)mcl_clamp(lm->y_mm, -20000, 20000);
            c->cand[c->n_cand++] = pc->lm_index[a];
        }
    }
    if (c->n_cand == 0)
        return false;
    c->o = o;
    c->cb = fl_cos_q15(o->bearing);
    c->sb = fl_sin_q15(o->bearing);
    c->ox = mcl_asr((int64_t)r * c->cb, 15);
    c->oy = mcl_asr((int64_t)r * c->sb, 15);
    c->sd_r = p->range_base_mm + (int32_t)(((int64_t)r * p->range_pct) / 100);
    /* across: r x the bearing sd in radians (pi / 180000 per mdeg) */
    sa = ((int64_t)r * p->bearing_mdeg * 17453) / 1000000000;
    c->sd_a = (int32_t)sa + p->range_base_mm;
    c->k_r = (128ull << 32) / ((uint64_t)c->sd_r * (uint64_t)c->sd_r);
    c->k_a = (128ull << 32) / ((uint64_t)c->sd_a * (uint64_t)c->sd_a);
    return true;
}

/* (e / sd)^2 / 2 in Q8 nats, e clamped to 8 sd (8192 at most). */
static uint32_t gauss_nll(int32_t e, int32_t sd, uint64_t k)
{
    int32_t lim = 8 * sd;
    e = mcl_clamp(e, -lim, lim);
    return (uint32_t)(((uint64_t)((int64_t)e * e) * k) >> 32);
}

/* The Gaussian part q (Q8 nats) of one observation for one particle. */
uint32_t fl_mcl_internal_obs_nll(const fl_mcl_core_t *pc, const fl_mcl_params_t *p,
                                 const fl_mcl_obs_c_t *c, fl_mcl_at_t *at)
{
    int32_t px = at->x, py = at->y, ch = at->c, sh = at->s;
    fl_angle_t h = at->h;
    /* |fx|, |fy| <= 25000 and the landmarks within +-20000: differences
     * below 45000, squares below 2^31, their sum below 2^32 */
    int32_t fx = mcl_clamp(px + mcl_asr((int64_t)c->ox * ch - (int64_t)c->oy * sh, 15), -25000,
                           25000);
    int32_t fy = mcl_clamp(py + mcl_asr((int64_t)c->ox * sh + (int64_t)c->oy * ch, 15), -25000,
                           25000);
    int32_t ux = mcl_asr(c->cb * ch - c->sb * sh, 15), uy = mcl_asr(c->cb * sh + c->sb * ch, 15);
    uint32_t b1 = UINT32_MAX, b2 = UINT32_MAX, q;
    int best = c->cand[0], a;
    int32_t ex, ey, along, across;
    for (a = 0; a < c->n_cand; a++) {
        int32_t dx = c->cx[a] - fx, dy = c->cy[a] - fy;
        uint32_t d = (uint32_t)(dx * dx) + (uint32_t)(dy * dy);
        if (d < b1) {
            b2 = b1;
            b1 = d;
            best = c->cand[a];
        } else if (d < b2) {
            b2 = d;
        }
    }
    ex = mcl_clamp(fl_field_all_at(pc->field, (uint16_t)best)->x_mm - fx, -16000, 16000);
    ey = mcl_clamp(fl_field_all_at(pc->field, (uint16_t)best)->y_mm - fy, -16000, 16000);
    along = mcl_asr(ex * ux + ey * uy, 15);
    across = mcl_asr(ey * ux - ex * uy, 15);
    q = gauss_nll(along, c->sd_r, c->k_r) + gauss_nll(across, c->sd_a, c->k_a);
    if (p->assoc_q8 != 0 && b2 != UINT32_MAX && b2 > 0u)
        q += (uint32_t)(((uint64_t)b1 << 23) /
                        ((uint64_t)b2 * ((uint64_t)p->assoc_q8 * p->assoc_q8)));
    if (p->orient_mdeg != 0 && c->o->has_orientation && pc->lm_orient_mod[best] != 0) {
        /* field orientation of the observed crossing vs the landmark's,
         * modulo its symmetry (L, T 360, circle 180, X and marks 90 deg) */
        int32_t d = (int32_t)fl_angle_sub(fl_angle_add(c->o->orientation, h),
                                          pc->lm_orient[best]);
        int32_t m = pc->lm_orient_mod[best], sdo = (int32_t)(((int64_t)p->orient_mdeg * 65536) / 360000);
        d = (int32_t)fl_angle_wrap(d * m) / m;
        if (sdo < 1)
            sdo = 1;
        q += gauss_nll(d, sdo, (128ull << 32) / ((uint64_t)sdo * (uint64_t)sdo));
    }
    at->best = best;
    return q > MCL_NLL_MAX ? MCL_NLL_MAX : q;
}

/* Keep the frame's first applied observations for sensor resetting. */
void fl_mcl_internal_keep_reset_obs(fl_mcl_core_t *c, const fl_obs_t *o)
{
    fl_mcl_reset_obs_t *r;
    if (c->n_reset >= FL_MCL_RESET_OBS)
        return;
    r = &c->reset_obs[c->n_reset++];
    r->kind = (uint8_t)o->kind;
    r->color = (uint8_t)o->color;
    r->side = (uint8_t)o->side;
    r->pad = (uint8_t)o->color2;
    r->range_mm = o->range_mm;
    r->bearing = o->bearing;
}

/* w_avg, the averages and the injection probability. */
bool fl_mcl_internal_augment(fl_mcl_core_t *c, const fl_mcl_params_t *p, fl_mcl_aug_t *s,
                             const uint32_t *nll, uint16_t n, uint16_t used)
{
    bool kidnap = false;
    uint32_t recip = 65536u / used, i, pinj;
    uint64_t sum = 0;
    uint32_t w_avg;
    for (i = 0; i < n; i++)
        sum += fl_mcl_internal_exp_q16((uint32_t)(((uint64_t)nll[i] * recip) >> 16));
    w_avg = (uint32_t)((sum << 8) / n);           /* Q24 */
    if (s->w_slow_q24 == 0u) {
        s->w_slow_q24 = w_avg;
        s->w_fast_q24 = w_avg;
    } else {
        s->w_slow_q24 = (uint32_t)((int64_t)s->w_slow_q24 +
                                   mcl_asr(((int64_t)w_avg - s->w_slow_q24) * p->alpha_slow_q16, 16));
        s->w_fast_q24 = (uint32_t)((int64_t)s->w_fast_q24 +
                                   mcl_asr(((int64_t)w_avg - s->w_fast_q24) * p->alpha_fast_q16, 16));
    }
    pinj = 0;
    if (s->w_slow_q24 > 0u && s->w_fast_q24 < s->w_slow_q24)
        pinj = 65536u - (uint32_t)(((uint64_t)s->w_fast_q24 << 16) / s->w_slow_q24);
    if (pinj >= p->kidnap_q16 && (c->track_valid || c->prior != FL_MCL_PRIOR_NONE)) {
        kidnap = true;
        fl_mcl_internal_drop_prior(c);
    }
    if (pinj > p->inject_max_q16)
        pinj = p->inject_max_q16;
    if (pinj < p->inject_min_q16)
        pinj = p->inject_min_q16;
    s->inject_q16 = (uint16_t)pinj;
    return kidnap;
}

/* Adds one observation's floored negative log-likelihood to every
 * particle's sum (observation-major: one observation's constants on the
 * stack at a time). */
static void apply_obs(fl_mcl_t *s, const fl_mcl_obs_c_t *c, const uint16_t *tab)
{
    const fl_mcl_particle_t *p = mcl_live_c(s);
    fl_mcl_at_t at;
    uint16_t i;
    for (i = 0; i < s->n; i++) {
        at.x = p[i].x_mm;
        at.y = p[i].y_mm;
        at.c = s->trig[i][0];
        at.s = s->trig[i][1];
        at.h = p[i].heading;
        s->nll[i] += fl_mcl_internal_mixture(tab, fl_mcl_internal_obs_nll(&s->core, &s->params, c, &at));
    }
}

/* Under ignorance the first observations replace the uniform particles by
 * sensor-reset ones (poses that explain one observed feature): 256
 * particles spread uniformly over half a carpet and every heading are too
 * sparse for the first weighting to find the right place. */
static void seed_from_obs(fl_mcl_t *s)
{
    fl_mcl_particle_t *p = mcl_live(s);
    uint16_t i;
    for (i = 0; i < s->n; i++)
        fl_mcl_internal_inject(s, &p[i]);
}

uint16_t fl_mcl_update(fl_mcl_t *s, const fl_obs_list_t *obs)
{
    fl_mcl_obs_c_t c;
    uint16_t tab[MIX_N];
    uint16_t i, used = 0, nmax;
    uint32_t nmin = UINT32_MAX;
    fl_mcl_particle_t *p;
    if (!mcl_ready(s))
        return 0;
    s->stats.updates = mcl_sat_inc(s->stats.updates);
    if (obs == NULL)
        return 0;
    nmax = obs->n < FL_OBS_MAX ? obs->n : FL_OBS_MAX;
    /* pass 1: the usable observations (kept for sensor resetting) */
    for (i = 0; i < nmax && used < MCL_OBS_PER_FRAME; i++)
        if (fl_mcl_internal_prepare(&s->core, &s->params, &obs->obs[i], &c)) {
            if (used == 0)
                s->core.n_reset = 0;
            fl_mcl_internal_keep_reset_obs(&s->core, c.o);
            used++;
        }
    s->stats.obs_ignored += (uint32_t)(nmax - used);
    if (used == 0)
        return 0;
    if (s->weighted)
        fl_mcl_internal_resample(s);
    if (s->ignorance)
        seed_from_obs(s);
    fl_mcl_internal_mixture_table(s->params.outlier_q16, tab);
    memset(s->nll, 0, sizeof s->nll);
    p = mcl_live(s);
    for (i = 0; i < s->n; i++) {
        s->trig[i][0] = fl_cos_q15(p[i].heading);
        s->trig[i][1] = fl_sin_q15(p[i].heading);
    }
    /* pass 2: the likelihoods */
    for (i = 0, used = 0; i < nmax && used < MCL_OBS_PER_FRAME; i++)
        if (fl_mcl_internal_prepare(&s->core, &s->params, &obs->obs[i], &c)) {
            apply_obs(s, &c, tab);
            used++;
        }
    for (i = 0; i < s->n; i++)
        if (s->nll[i] < nmin)
            nmin = s->nll[i];
    for (i = 0; i < s->n; i++) {
        uint32_t w = fl_mcl_internal_exp_q16(s->nll[i] - nmin);
        p[i].weight = (uint16_t)(w > 65535u ? 65535u : w);
    }
    if (fl_mcl_internal_augment(&s->core, &s->params, &s->aug, s->nll, s->n, used))
        s->stats.kidnaps = mcl_sat_inc(s->stats.kidnaps);
    s->weighted = true;
    s->ignorance = false;
    s->since_obs = 0;
    s->stats.obs_used += used;
    return used;
}

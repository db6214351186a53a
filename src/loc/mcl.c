/*
 * src/loc/mcl.c - the Monte Carlo localizer (mcl.h): parameters, init,
 * the random generator and the Gaussian sampler, resets, priors, check.
 */
#include "mcl_int.h"

#include <string.h>

/* ---- random numbers ------------------------------------------------------- */

/* xorshift32, shifts 13, 17, 5 (Marsaglia, "Xorshift RNGs", J. Stat.
 * Softw. 8(14), 2003): period 2^32 - 1 over the non-zero states. */
uint32_t fl_mcl_rand(uint32_t *rng)
{
    uint32_t x = *rng != 0u ? *rng : 2463534242u;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *rng = x;
    return x;
}

/*
 * The half-normal quantile z(p) = Phi^-1((1 + p) / 2) in Q12, tabulated
 * (generated with Python's statistics.NormalDist().inv_cdf).  A deviate
 * takes 16 bits m for p = (m + 1/2) / 65536 and one bit for the sign.
 * gauss_main: knots at p = 256 k / 65536, k = 0..252 (p up to 0.984375);
 * the tail v = 65535 - m < 1024: gauss_tail knots at p = 1 - v / 65536 for
 * v = 32, 64, ..., 1024, and below v = 32 (where z bends fastest) each
 * gauss_tail0[v] is z((65535.5 - v) / 65536) exactly.  Between knots: linear
 * interpolation at the bin's centre.  Largest |z| 4.475; the variance and
 * the 4th moment of the table's distribution are 0.99997 and 3.0011
 * (exact over the 2^16 magnitudes; test mcl.gauss_moments samples them).
 */
static const int16_t gauss_main[253] = {
    0, 20, 40, 60, 80, 100, 120, 140, 160, 181, 201, 221,
    241, 261, 281, 301, 321, 341, 361, 382, 402, 422, 442, 462,
    482, 503, 523, 543, 563, 584, 604, 624, 644, 665, 685, 705,
    726, 746, 766, 787, 807, 828, 848, 869, 889, 910, 930, 951,
    972, 992, 1013, 1034, 1054, 1075, 1096, 1117, 1137, 1158, 1179, 1200,
    1221, 1242, 1263, 1284, 1305, 1326, 1347, 1369, 1390, 1411, 1432, 1454,
    1475, 1497, 1518, 1539, 1561, 1583, 1604, 1626, 1648, 1669, 1691, 1713,
    1735, 1757, 1779, 1801, 1823, 1845, 1868, 1890, 1912, 1935, 1957, 1979,
    2002, 2025, 2047, 2070, 2093, 2116, 2139, 2162, 2185, 2208, 2231, 2255,
    2278, 2301, 2325, 2348, 2372, 2396, 2420, 2444, 2468, 2492, 2516, 2540,
    2565, 2589, 2613, 2638, 2663, 2688, 2713, 2738, 2763, 2788, 2813, 2839,
    2864, 2890, 2916, 2942, 2968, 2994, 3020, 3046, 3073, 3100, 3126, 3153,
    3180, 3207, 3235, 3262, 3290, 3318, 3345, 3374, 3402, 3430, 3459, 3487,
    3516, 3545, 3575, 3604, 3634, 3664, 3694, 3724, 3754, 3785, 3816, 3847,
    3878, 3910, 3941, 3973, 4005, 4038, 4071, 4104, 4137, 4170, 4204, 4238,
    4273, 4307, 4342, 4378, 4414, 4450, 4486, 4523, 4560, 4597, 4635, 4673,
    4712, 4751, 4790, 4830, 4871, 4912, 4953, 4995, 5038, 5080, 5124, 5168,
    5213, 5258, 5304, 5351, 5399, 5447, 5496, 5545, 5596, 5647, 5700, 5753,
    5807, 5863, 5919, 5977, 6035, 6095, 6157, 6219, 6284, 6350, 6417, 6486,
    6558, 6631, 6706, 6784, 6865, 6948, 7034, 7123, 7216, 7312, 7413, 7519,
    7630, 7746, 7870, 8001, 8141, 8290, 8452, 8628, 8822, 9038, 9282, 9565,
    9902,
};
static const int16_t gauss_tail0[32] = {
    18331, 17345, 16869, 16549, 16306, 16109, 15944, 15801, 15676, 15563, 15461, 15368,
    15282, 15203, 15128, 15059, 14993, 14931, 14873, 14817, 14764, 14713, 14665, 14618,
    14573, 14530, 14488, 14448, 14410, 14372, 14336, 14300,
};
static const int16_t gauss_tail[32] = {
    14283, 13505, 13032, 12686, 12413, 12186, 11991, 11820, 11667, 11529, 11403, 11287,
    11179, 11079, 10984, 10896, 10812, 10732, 10656, 10584, 10515, 10449, 10385, 10324,
    10265, 10208, 10153, 10100, 10048, 9998, 9950, 9902,
};

int32_t fl_mcl_gauss_q12(uint32_t *rng)
{
    uint32_t r = fl_mcl_rand(rng);
    uint32_t m = r & 0xffffu;
    int32_t z;
    if (m < 252u * 256u) {
        uint32_t k = m >> 8, f = m & 255u;
        int32_t a = gauss_main[k], b = gauss_main[k + 1];
        z = a + (int32_t)(((b - a) * (int32_t)(2u * f + 1u)) >> 9);   /* b >= a */
    } else {
        uint32_t v = 65535u - m;
        if (v < 32u) {
            z = gauss_tail0[v];
        } else {
            uint32_t k = (v - 32u) >> 5, f = (v - 32u) & 31u;
            int32_t a = gauss_tail[k], b = gauss_tail[k + 1];
            z = a - (int32_t)(((a - b) * (int32_t)(2u * f + 1u)) >> 6);   /* a >= b */
        }
    }
    return (r & 0x80000000u) ? -z : z;
}

/* ---- parameters ------------------------------------------------------------ */

/*
 * Defaults (feature-level observations of the simulator, tools/world/sim.c
 * sim_scenario_defaults: NAO range noise 10 % of the range, bearing 2 deg,
 * odometry 12 % random per step plus 8-15 % systematic scale and 3-4 deg/m
 * drift, 5-8 % L/T confusions, false positives).
 *  - motion: 15 % of a 1 m step in x and y, 15 % of a 1 rad turn and 5 deg
 *    per metre walked (the simulator's random and systematic odometry
 *    errors together; Thrun et al., Probabilistic Robotics, table 5.6 has
 *    the same form with alphas set from the robot's odometry);
 *  - sensor: the simulator's range and bearing noise, 30 mm base; the
 *    floor 0.02 (a uniform term of a twentieth of a typical observation's
 *    peak likelihood: confusions and false positives are a few %);
 *  - augmentation: alpha_slow 0.001 and alpha_fast 0.1 per 10 Hz vision
 *    frame (Probabilistic Robotics section 8.3.5 and nav2 AMCL's
 *    recovery_alpha_slow / recovery_alpha_fast defaults), a third of that
 *    per update here (feature-level observations arrive at 30 Hz: the
 *    same time constants; 0.1 per update measured 17 flips in 18 spl2013
 *    feature walks, the injection bursting on noise); a kidnap called at
 *    an injection probability of 0.3; injection capped at 1/2, no minimum
 *    (a minimum seeds mirror modes that later win: measured more flips);
 *  - estimate: cluster radius 500 mm (the FL_LOC_GOOD_MM tolerance), a
 *    tracked cluster kept while it has 1/4 of the heaviest one's weight.
 */
void fl_mcl_params_default(fl_mcl_params_t *p)
{
    if (p == NULL)
        return;
    memset(p, 0, sizeof *p);
    p->seed = 1;
    p->n_particles = FL_MCL_MAX_PARTICLES < 256 ? FL_MCL_MAX_PARTICLES : 256;
    p->odo_trans_pct = 15;
    p->odo_rot_pct = 15;
    p->odo_rot_mdeg_per_m = 5000;
    p->odo_max_mm = 1000;
    p->jitter_mm = 10;
    p->jitter_mdeg = 500;
    p->margin_mm = 100;
    p->range_pct = 10;
    p->range_base_mm = 30;
    p->bearing_mdeg = 2000;
    p->orient_mdeg = 0;
    p->assoc_q8 = 0;
    p->outlier_q16 = 1311;
    p->corner_any = 1;
    p->max_range_mm = FL_OBS_MAX_RANGE_MM;
    p->cross_max_mm = 0;
    p->alpha_slow_q16 = 22;
    p->alpha_fast_q16 = 2185;
    p->inject_max_q16 = 32768;
    p->inject_min_q16 = 0;
    p->kidnap_q16 = 19661;
    p->cluster_mm = 500;
    p->switch_q8 = 64;
}

/* Vision (fl_vision_frame's observations): ranges from a NAO camera are
 * more precise than the simulator's 10 % (below 1 % mean error in the
 * vision diagnostics of `fieldloc simulate --frames`; 6 % leaves room for
 * the pose's own error), with L/T kind errors of 10-22 %: a floor of 0.05.
 * The crossings' orientation, sd 10 deg, measured on the frames walks of
 * seeds 1-6 x 5 generator seeds: spl2013 kidnap recovery worst 6.9 ->
 * 3.7 s, heading RMSE 0.78 -> 0.69 deg (20 deg: less; the association
 * certainty term, sd 0.5 or 1: no gain). */
void fl_mcl_params_vision(fl_mcl_params_t *p, bool lowres)
{
    if (p == NULL)
        return;
    fl_mcl_params_default(p);
    p->range_pct = 6;
    p->bearing_mdeg = 1500;
    p->outlier_q16 = 3277;
    p->orient_mdeg = 10000;
    p->alpha_slow_q16 = 66;
    p->alpha_fast_q16 = 6554;
    if (lowres)
        fl_mcl_params_lowres(p);
}

/* The AIBO's 208 x 160 camera: ranges several times less precise, far
 * crossings short and often of the wrong kind. */
void fl_mcl_params_lowres(fl_mcl_params_t *p)
{
    if (p == NULL)
        return;
    p->range_pct = 15;
    p->bearing_mdeg = 3000;
    if (p->cross_max_mm == 0)
        p->cross_max_mm = 2500;
}

fl_status_t fl_mcl_params_check(const fl_mcl_params_t *p)
{
    if (p == NULL)
        return FL_ERR_NULL;
    if (p->seed < 0 || p->n_particles < 1 || p->n_particles > FL_MCL_MAX_PARTICLES ||
        p->odo_trans_pct > 1000 || p->odo_rot_pct > 1000 || p->odo_rot_mdeg_per_m > 60000 ||
        p->odo_max_mm < 1 || p->odo_max_mm > 100000 || p->jitter_mm > 1000 ||
        p->jitter_mdeg > 30000 || p->margin_mm < 0 || p->margin_mm > 2000 ||
        p->range_pct > 100 || p->range_base_mm < 1 || p->range_base_mm > 5000 ||
        p->bearing_mdeg < 10 || p->bearing_mdeg > 45000 ||
        p->assoc_q8 > 4096 || p->outlier_q16 < 1 || p->corner_any > 1 || p->max_range_mm < 1 ||
        p->max_range_mm > FL_OBS_MAX_RANGE_MM || p->cross_max_mm < 0 ||
        p->alpha_slow_q16 > p->alpha_fast_q16 ||
        p->inject_min_q16 > p->inject_max_q16 || p->cluster_mm < 100 || p->cluster_mm > 5000)
        return FL_ERR_RANGE;
    return FL_OK;
}

/* ---- init ------------------------------------------------------------------ */

void fl_mcl_clear(fl_mcl_t *s)
{
    if (s != NULL)
        memset(s, 0, sizeof *s);
}

/* Landmark ids by kind, and the orientations of those that have one.  Ids
 * are fl_field_all_at's: the landmarks, then seed 004's features. */
static void index_landmarks(fl_mcl_core_t *c, const fl_field_t *f)
{
    uint16_t i, n = 0, na = fl_field_n_all(f);
    int k;
    for (k = 0; k < FL_LM_KIND_COUNT; k++) {
        c->kind_start[k] = (uint8_t)n;
        for (i = 0; i < na; i++)
            if ((int)fl_field_all_at(f, i)->kind == k)
                c->lm_index[n++] = (uint8_t)i;
    }
    c->kind_start[FL_LM_KIND_COUNT] = (uint8_t)n;
    for (i = 0; i < na; i++) {
        const fl_landmark_t *lm = fl_field_all_at(f, i);
        fl_angle_t o;
        int32_t period = fl_landmark_orientation_period(lm);
        if (period == 0 || !fl_landmark_orientation(lm, &o))
            continue;
        c->lm_orient[i] = o;
        c->lm_orient_mod[i] = (uint8_t)(65536 / period);
    }
}

fl_status_t fl_mcl_internal_core_init(fl_mcl_core_t *c, const fl_field_t *field,
                                      int32_t margin_mm, int32_t seed)
{
    memset(c, 0, sizeof *c);
    if (fl_field_n_all(field) > FL_MCL_MAX_LANDMARKS)
        return FL_ERR_SIZE;
    if (fl_field_carpet_half_x_mm(field) + margin_mm > 30000 ||
        fl_field_carpet_half_y_mm(field) + margin_mm > 30000 ||
        fl_field_carpet_half_x_mm(field) < 100 || fl_field_carpet_half_y_mm(field) < 100)
        return FL_ERR_RANGE;
    c->half_x_mm = fl_field_carpet_half_x_mm(field);
    c->half_y_mm = fl_field_carpet_half_y_mm(field);
    c->box_x_mm = c->half_x_mm + margin_mm;
    c->box_y_mm = c->half_y_mm + margin_mm;
    c->rng = (uint32_t)seed * 2654435761u ^ 0x9e3779b9u;
    if (c->rng == 0u)
        c->rng = 1u;
    index_landmarks(c, field);
    c->field = field;
    return FL_OK;
}

fl_status_t fl_mcl_init(fl_mcl_t *s, const fl_field_t *field, const fl_mcl_params_t *params)
{
    fl_mcl_params_t p;
    fl_status_t st;
    if (s == NULL)
        return FL_ERR_NULL;
    fl_mcl_clear(s);
    if (field == NULL || field->landmarks == NULL)
        return FL_ERR_NULL;
    if (params != NULL)
        p = *params;
    else
        fl_mcl_params_default(&p);
    st = fl_mcl_params_check(&p);
    if (st != FL_OK)
        return st;
    st = fl_mcl_internal_core_init(&s->core, field, p.margin_mm, p.seed);
    if (st != FL_OK)
        return st;
    s->params = p;
    s->n = p.n_particles;
    fl_mcl_reset_ignorance(s);
    s->stats.resets = 0;
    return FL_OK;
}

/* ---- regions ---------------------------------------------------------------- */

void fl_mcl_internal_clamp(const fl_mcl_core_t *c, int32_t *x, int32_t *y)
{
    *x = mcl_clamp(*x, -c->box_x_mm, c->box_x_mm);
    *y = mcl_clamp(*y, -c->box_y_mm, c->box_y_mm);
}

/* Whether a pose is on the carpet and inside the prior's region.  A half
 * prior decides between the mirror modes of a symmetric field (always) and
 * between modes of an asymmetric one until a mode is tracked (then the
 * map decides, and a kidnap into the other half recovers by injection). */
bool fl_mcl_internal_allowed(const fl_mcl_core_t *c, int32_t x, int32_t y, fl_angle_t h)
{
    if (x < -c->half_x_mm || x > c->half_x_mm || y < -c->half_y_mm || y > c->half_y_mm)
        return false;
    if (c->prior == FL_MCL_PRIOR_HALF && !c->field->symmetric && c->track_valid)
        return true;
    if (c->prior == FL_MCL_PRIOR_HALF)
        return c->prior_half < 0 ? x <= 0 : x >= 0;
    if (c->prior == FL_MCL_PRIOR_POSE) {
        int64_t dx = (int64_t)x - c->prior_x_mm, dy = (int64_t)y - c->prior_y_mm;
        return dx * dx + dy * dy <= (int64_t)c->prior_radius_mm * c->prior_radius_mm &&
               mcl_absang(fl_angle_sub(h, c->prior_heading)) <= FL_ANGLE_90;
    }
    return true;
}

/* A pose drawn uniformly from the prior's region (the carpet, the own
 * half, or a pose's disc and heading within 90 deg), any heading. */
void fl_mcl_internal_uniform(fl_mcl_core_t *c, fl_mcl_particle_t *p)
{
    int32_t x0 = -c->half_x_mm, x1 = c->half_x_mm, y0 = -c->half_y_mm, y1 = c->half_y_mm;
    int32_t x, y, tries;
    fl_angle_t h = (fl_angle_t)(int32_t)(fl_mcl_rand(&c->rng) >> 16) ;
    if (c->prior == FL_MCL_PRIOR_HALF && (c->field->symmetric || !c->track_valid)) {
        if (c->prior_half < 0)
            x1 = 0;
        else
            x0 = 0;
    } else if (c->prior == FL_MCL_PRIOR_POSE) {
        int32_t r = c->prior_radius_mm;
        x0 = mcl_clamp(c->prior_x_mm - r, x0, x1);
        x1 = mcl_clamp(c->prior_x_mm + r, x0, x1);
        y0 = mcl_clamp(c->prior_y_mm - r, y0, y1);
        y1 = mcl_clamp(c->prior_y_mm + r, y0, y1);
        h = fl_angle_add(c->prior_heading,
                         fl_angle_wrap((int32_t)mcl_below(&c->rng, 32769u) - 16384));
    }
    x = x0;
    y = y0;
    for (tries = 0; tries < 8; tries++) {
        x = x0 + (int32_t)mcl_below(&c->rng, (uint32_t)(x1 - x0 + 1));
        y = y0 + (int32_t)mcl_below(&c->rng, (uint32_t)(y1 - y0 + 1));
        if (fl_mcl_internal_allowed(c, x, y, h))
            break;
    }
    if (tries == 8 && c->prior == FL_MCL_PRIOR_POSE) {
        x = mcl_clamp(c->prior_x_mm, -c->half_x_mm, c->half_x_mm);
        y = mcl_clamp(c->prior_y_mm, -c->half_y_mm, c->half_y_mm);
    }
    p->x_mm = (int16_t)x;
    p->y_mm = (int16_t)y;
    p->heading = h;
    p->weight = 65535u;
}

/* A detected kidnap or an explicit reset: the game's half no longer
 * holds unless told again. */
void fl_mcl_internal_drop_prior(fl_mcl_core_t *c)
{
    c->prior = FL_MCL_PRIOR_NONE;
    c->half_known = false;
    c->track_valid = false;
}

/* ---- resets -------------------------------------------------------------------- */

/* Fresh particles: the averages start again from the next update. */
static void fresh(fl_mcl_t *s)
{
    s->n = s->params.n_particles;
    if (s->n < 1 || s->n > FL_MCL_MAX_PARTICLES)
        s->n = FL_MCL_MAX_PARTICLES < 256 ? FL_MCL_MAX_PARTICLES : 256;
    s->weighted = false;
    s->aug.w_slow_q24 = 0;
    s->aug.w_fast_q24 = 0;
    s->aug.inject_q16 = 0;
    s->core.n_reset = 0;
    s->est_density = 0;
}

/* ---- resets and priors on a particle core ---------------------------------------- */

void fl_mcl_internal_core_ignorance(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n)
{
    uint16_t i;
    for (i = 0; i < n; i++)
        fl_mcl_internal_uniform(c, &p[i]);
    c->track_valid = false;
    c->half_known = c->prior != FL_MCL_PRIOR_NONE;
}

/* Particles around one pose: Gaussian, sd pos_unc / 2 and heading_unc / 2
 * (most within the uncertainty; the fuzzy grid's cone falls to 1/2 there). */
static void paint_pose(fl_mcl_core_t *k, fl_mcl_particle_t *p, const fl_mcl_paint_t *c)
{
    int32_t sd = mcl_clamp(c->pos_unc, 1, 20000) / 2;
    int32_t sh = mcl_absang(c->heading_unc) / 2;
    int32_t px = mcl_clamp(c->x, -k->half_x_mm, k->half_x_mm) + mcl_noise(&k->rng, sd);
    int32_t py = mcl_clamp(c->y, -k->half_y_mm, k->half_y_mm) + mcl_noise(&k->rng, sd);
    fl_mcl_internal_clamp(k, &px, &py);
    p->x_mm = (int16_t)px;
    p->y_mm = (int16_t)py;
    p->heading = fl_angle_add(c->h, fl_angle_wrap(mcl_noise(&k->rng, sh)));
    p->weight = 65535u;
}

void fl_mcl_internal_core_pose(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                               const fl_mcl_paint_t *pose)
{
    uint16_t i;
    for (i = 0; i < n; i++)
        paint_pose(c, &p[i], pose);
    c->half_known = true;
    c->track_valid = true;
    c->track_x_mm = mcl_clamp(pose->x, -c->half_x_mm, c->half_x_mm);
    c->track_y_mm = mcl_clamp(pose->y, -c->half_y_mm, c->half_y_mm);
    c->track_heading = pose->h;
}

void fl_mcl_internal_core_penalty(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                  const fl_mcl_paint_t *pose)
{
    fl_mcl_paint_t q = *pose;
    int32_t hw = c->field->width_mm / 2;
    uint16_t i;
    for (i = 0; i < n; i++) {
        bool left = (i & 1u) == 0u;
        q.y = left ? hw : -hw;
        q.h = (fl_angle_t)(left ? -FL_ANGLE_90 : FL_ANGLE_90);
        paint_pose(c, &p[i], &q);
    }
    c->track_valid = false;
    /* the placement tells the half (unless the spots are on the halfway
     * line, where they are each other's mirror) */
    if (pose->x != 0)
        fl_mcl_internal_core_prior_half(c, p, n, false, pose->x < 0 ? -1 : 1);
    c->half_known = c->prior != FL_MCL_PRIOR_NONE;
}

/* The prior changed: under ignorance the particles are drawn again from
 * its region; otherwise, on a symmetric field, particles outside the own
 * half move to their mirror pose (which explains the same observations). */
static void apply_prior(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n, bool ignorance)
{
    uint16_t i;
    if (ignorance) {
        for (i = 0; i < n; i++)
            fl_mcl_internal_uniform(c, &p[i]);
        return;
    }
    if (c->prior != FL_MCL_PRIOR_HALF || !c->field->symmetric)
        return;
    for (i = 0; i < n; i++)
        if (c->prior_half < 0 ? p[i].x_mm > 0 : p[i].x_mm < 0) {
            p[i].x_mm = (int16_t)-p[i].x_mm;
            p[i].y_mm = (int16_t)-p[i].y_mm;
            p[i].heading = fl_angle_add(p[i].heading, FL_ANGLE_180);
        }
}

void fl_mcl_internal_core_prior_half(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                     bool ignorance, int half)
{
    c->prior = half == 0 ? FL_MCL_PRIOR_NONE : FL_MCL_PRIOR_HALF;
    c->prior_half = (int8_t)(half < 0 ? -1 : 1);
    /* no half: a tracked mode still carries the half it was told */
    c->half_known = half != 0 || (c->half_known && c->track_valid);
    apply_prior(c, p, n, ignorance);
}

void fl_mcl_internal_core_prior_pose(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                     bool ignorance, const fl_mcl_paint_t *pose)
{
    c->prior = FL_MCL_PRIOR_POSE;
    c->prior_x_mm = mcl_clamp(pose->x, -100000, 100000);
    c->prior_y_mm = mcl_clamp(pose->y, -100000, 100000);
    c->prior_heading = pose->h;
    c->prior_radius_mm = mcl_clamp(pose->pos_unc, 100, 20000);
    c->half_known = true;
    apply_prior(c, p, n, ignorance);
}

void fl_mcl_internal_core_clear_prior(fl_mcl_core_t *c)
{
    c->prior = FL_MCL_PRIOR_NONE;
    c->half_known = c->half_known && c->track_valid;
}

/* ---- re-seeding and spread on a particle core -------------------------------------- */

/* pi/8 (seed 003's heading sd) and 90 deg, binary angles. */
#define RESEED_SD_H 4096
#define RESEED_SD_H_MAX FL_ANGLE_90

bool fl_mcl_internal_reseed_paint(const fl_obs_report_t *r, const fl_mcl_estimate_t *e,
                                  fl_mcl_paint_t *pose)
{
    int32_t sh = mcl_absang(e->sd_heading);
    bool known = !e->ignorance && sh < RESEED_SD_H_MAX;
    if (sh < RESEED_SD_H)
        sh = RESEED_SD_H;
    if (!known)
        sh = RESEED_SD_H_MAX;
    /* twice the sds: core_pose draws with half of them */
    mcl_paint(pose, r->x_mm, r->y_mm, e->heading, 2 * r->sd_mm,
              (fl_angle_t)(sh >= RESEED_SD_H_MAX ? 32767 : 2 * sh));
    return known;
}

void fl_mcl_internal_core_reseed(fl_mcl_core_t *c, fl_mcl_particle_t *p, uint16_t n,
                                 const fl_mcl_paint_t *pose, bool heading_known)
{
    uint16_t i;
    uint32_t base;
    fl_mcl_internal_core_pose(c, p, n, pose);
    if (heading_known || n == 0)
        return;
    /* any heading, stratified: n evenly spaced headings from one random
     * start (a few particles, the UPF's 12, would leave gaps of random
     * width that observations cannot fill) */
    base = fl_mcl_rand(&c->rng) >> 16;
    for (i = 0; i < n; i++)
        p[i].heading = fl_angle_wrap((int32_t)((base + ((uint32_t)i << 16) / n) & 0xFFFFu));
    c->track_valid = false;
}

/* A particle's position, folded onto the track's side of the mirror when
 * fold (the nearer of itself and its mirror to the track). */
static void spread_point(const fl_mcl_core_t *c, bool fold, const fl_mcl_particle_t *p,
                         int64_t *x, int64_t *y)
{
    int64_t px = p->x_mm, py = p->y_mm;
    if (fold) {
        int64_t dx = px - c->track_x_mm, dy = py - c->track_y_mm;
        int64_t ex = -px - c->track_x_mm, ey = -py - c->track_y_mm;
        if (ex * ex + ey * ey < dx * dx + dy * dy) {
            px = -px;
            py = -py;
        }
    }
    *x = px;
    *y = py;
}

/* Scaling: |x| <= 2^15, weights < 2^16, n <= 2^8: sums of w x below 2^39,
 * of w dx^2 below 2^56. */
uint32_t fl_mcl_internal_spread(const fl_mcl_core_t *c, const fl_mcl_particle_t *p, uint16_t n,
                                const uint32_t *var)
{
    uint64_t w = 0, sq = 0;
    int64_t sx = 0, sy = 0, mx, my;
    bool fold = c->track_valid && c->field->symmetric, flat;
    uint16_t i;
    for (i = 0; i < n; i++)
        w += p[i].weight;
    flat = w == 0u;
    if (flat)
        w = n;
    if (w == 0u)
        return 0;
    for (i = 0; i < n; i++) {
        int64_t x, y;
        uint64_t pw = flat ? 1u : p[i].weight;
        spread_point(c, fold, &p[i], &x, &y);
        sx += (int64_t)pw * x;
        sy += (int64_t)pw * y;
    }
    mx = sx / (int64_t)w;
    my = sy / (int64_t)w;
    for (i = 0; i < n; i++) {
        int64_t x, y;
        uint64_t pw = flat ? 1u : p[i].weight;
        spread_point(c, fold, &p[i], &x, &y);
        x -= mx;
        y -= my;
        sq += pw * (uint64_t)(x * x + y * y);
        if (var != NULL)
            sq += pw * var[i];
    }
    return fl_isqrt64(sq / w);
}

bool fl_mcl_internal_core_check(const fl_mcl_core_t *c, const fl_mcl_particle_t *p, uint16_t n)
{
    uint16_t i;
    int k;
    if (c->field == NULL || c->rng == 0u || c->n_reset > FL_MCL_RESET_OBS ||
        c->box_x_mm > 32767 || c->box_y_mm > 32767 ||
        c->kind_start[FL_LM_KIND_COUNT] > FL_MCL_MAX_LANDMARKS)
        return false;
    for (k = 0; k < FL_LM_KIND_COUNT; k++)
        if (c->kind_start[k] > c->kind_start[k + 1])
            return false;
    for (i = 0; i < n; i++)
        if (p[i].x_mm < -c->box_x_mm || p[i].x_mm > c->box_x_mm || p[i].y_mm < -c->box_y_mm ||
            p[i].y_mm > c->box_y_mm)
            return false;
    return true;
}

/* ---- the Monte Carlo filter's resets, priors and check ---------------------------- */

void fl_mcl_reset_ignorance(fl_mcl_t *s)
{
    if (!mcl_ready(s))
        return;
    fresh(s);
    fl_mcl_internal_core_ignorance(&s->core, mcl_live(s), s->n);
    s->ignorance = true;
    s->stats.resets = mcl_sat_inc(s->stats.resets);
}

void fl_mcl_reset_pose(fl_mcl_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                       int32_t pos_unc_mm, fl_angle_t heading_unc)
{
    fl_mcl_paint_t c;
    if (!mcl_ready(s))
        return;
    fresh(s);
    mcl_paint(&c, x_mm, y_mm, heading, pos_unc_mm, heading_unc);
    fl_mcl_internal_core_pose(&s->core, mcl_live(s), s->n, &c);
    s->ignorance = false;
    s->stats.resets = mcl_sat_inc(s->stats.resets);
}

void fl_mcl_reset_penalty(fl_mcl_t *s, int32_t x_mm, int32_t pos_unc_mm,
                          fl_angle_t heading_unc)
{
    fl_mcl_paint_t c;
    if (!mcl_ready(s))
        return;
    fresh(s);
    mcl_paint(&c, x_mm, 0, 0, pos_unc_mm, heading_unc);
    s->ignorance = false;
    fl_mcl_internal_core_penalty(&s->core, mcl_live(s), s->n, &c);
    s->stats.resets = mcl_sat_inc(s->stats.resets);
}

void fl_mcl_set_prior_half(fl_mcl_t *s, int half)
{
    if (!mcl_ready(s))
        return;
    fl_mcl_internal_core_prior_half(&s->core, mcl_live(s), s->n, s->ignorance, half);
}

void fl_mcl_set_prior_pose(fl_mcl_t *s, int32_t x_mm, int32_t y_mm, fl_angle_t heading,
                           int32_t radius_mm)
{
    fl_mcl_paint_t c;
    if (!mcl_ready(s))
        return;
    mcl_paint(&c, x_mm, y_mm, heading, radius_mm, 0);
    fl_mcl_internal_core_prior_pose(&s->core, mcl_live(s), s->n, s->ignorance, &c);
}

void fl_mcl_clear_prior(fl_mcl_t *s)
{
    if (!mcl_ready(s))
        return;
    fl_mcl_internal_core_clear_prior(&s->core);
}

fl_status_t fl_mcl_reseed(fl_mcl_t *s, const fl_obs_report_t *r)
{
    fl_mcl_estimate_t e;
    fl_mcl_paint_t c;
    fl_status_t st;
    bool known;
    if (!mcl_ready(s))
        return FL_ERR_STATE;
    st = fl_obs_report_check(r, s->core.field);
    if (st != FL_OK) {
        s->stats.reseeds_refused = mcl_sat_inc(s->stats.reseeds_refused);
        return st;
    }
    (void)fl_mcl_estimate(s, &e);        /* the previous heading */
    known = fl_mcl_internal_reseed_paint(r, &e, &c);
    fresh(s);
    fl_mcl_internal_core_reseed(&s->core, mcl_live(s), s->n, &c, known);
    s->ignorance = false;
    s->stats.reseeds = mcl_sat_inc(s->stats.reseeds);
    return FL_OK;
}

uint32_t fl_mcl_spread_mm(const fl_mcl_t *s)
{
    if (!mcl_ready(s))
        return UINT32_MAX;
    return fl_mcl_internal_spread(&s->core, mcl_live_c(s), s->n, NULL);
}

bool fl_mcl_check(const fl_mcl_t *s)
{
    if (!mcl_ready(s) || s->n < 1 || s->n > FL_MCL_MAX_PARTICLES || s->cur > 1u)
        return false;
    return fl_mcl_internal_core_check(&s->core, mcl_live_c(s), s->n);
}

/*
 * fieldloc/localizer.h - one interface for every localizer (the fuzzy
 * position grid today; a Monte Carlo filter, an unscented particle filter
 * and a particle grid to follow).  A caller holds a `const fl_localizer_t *`
 * (fl_localizer_find("fuzzy")), a state of loc->state_size bytes and a
 * parameter block of loc->params_size bytes, both caller-owned (static
 * storage on a robot, malloc on a host; aligned for any type), and calls
 * through the function pointers or the fl_loc_* wrappers below, which
 * check their arguments:
 *
 *     const fl_localizer_t *loc = fl_localizer_find("fuzzy");
 *     void *st = <loc->state_size bytes, caller-owned>;
 *     fl_loc_init(loc, st, fl_field_find("spl2013"), NULL);
 *     every frame: fl_loc_predict(loc, st, dx_mm, dy_mm, dtheta);
 *                  fl_loc_update(loc, st, &obs, &view);
 *                  fl_loc_estimate(loc, st, &est);
 *
 * Nothing here needs the camera or vision: vision-path presets are chosen
 * by the caller as an fl_loc_preset_t, the frame's view comes as an
 * fl_obs_view_t (obs.h; vision.h fl_vision_view computes it).
 *
 * Randomness: a stochastic localizer keeps its random generator in the
 * state, seeded at init from its parameter "seed" (set it by name before
 * init; the same seed, inputs and build give the same results on every
 * target).  A deterministic localizer has no such parameter.
 *
 * Parameters by name: every localizer lists its tunable parameters as
 * fl_loc_param_t descriptors (offset into its params block, width and
 * signedness, range); fl_localizer_param_find / _set / _get work on any
 * of them (names compared by hand, no libc).
 */
#ifndef FIELDLOC_LOCALIZER_H
#define FIELDLOC_LOCALIZER_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/fixed.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Vision-path presets (the caller decides from its camera). */
typedef enum {
    FL_LOC_PRESET_DEFAULT = 0,      /* = params_default (feature-level obs) */
    FL_LOC_PRESET_VISION = 1,       /* observations from fl_vision_frame with
                                       a camera at least 320 px wide (NAO) */
    FL_LOC_PRESET_VISION_LOWRES = 2 /* ... narrower than 320 px (AIBO) */
} fl_loc_preset_t;

/* The preset for a camera image width in pixels (FL_LOC_PRESET_VISION for
 * >= 320 or <= 0 = unknown: a NAO camera, FL_LOC_PRESET_VISION_LOWRES
 * below). */
fl_loc_preset_t fl_loc_preset_for_width(int32_t width_px);

/* Whether the robot knows where it is. */
typedef enum {
    FL_LOC_LOST = 0,        /* no mode is tracked: the pose is a guess (under
                               total ignorance: the centre of the region the
                               prior allows, the field's centre without one,
                               with that region's spread) */
    FL_LOC_AMBIGUOUS = 1,   /* a mode is tracked but on a symmetric field the
                               pose rotated 180 deg about the centre is as
                               possible (mirror_q16 >= 1/2): nothing told the
                               half (no prior, or a kidnap since): the pose
                               or its mirror */
    FL_LOC_TRACKING = 2     /* a mode is tracked and its half is decided */
} fl_loc_state_t;

/* The reliability at which an estimate counts as localized. */
#define FL_LOC_LOCALIZED_Q16 32768u
/* The tolerance the reliability refers to. */
#define FL_LOC_GOOD_MM 500
#define FL_LOC_GOOD_DEG 20

/*
 * One estimate, common to every localizer.
 *
 * Contract (every localizer meets it; `fieldloc reliability` measures it
 * and a host test asserts it):
 *  - reliability_q16 is calibrated: over the simulated walks of every field
 *    (`fieldloc simulate`, feature-level observations and rendered frames
 *    through vision), of the estimates reported with reliability >= r, at
 *    least the share r is within FL_LOC_GOOD_MM and FL_LOC_GOOD_DEG of the
 *    true pose, for every r (the truth itself, not modulo the symmetry: a
 *    pose on the wrong half is wrong).  It is a function of the
 *    localizer's own measures only (peak, mode size, spread, mirror,
 *    time since an observation was applied, ...), fitted on training walks
 *    and checked on other seeds; not a probability of anything else.
 *  - Under total ignorance (after init or a reset to ignorance, after a
 *    detected kidnap, until an observation tells something) the estimate
 *    is the field's centre
 *    (the centre of the prior's region with a prior), sd_x_mm / sd_y_mm the
 *    spread of a uniform distribution over that region, sd_heading 32767,
 *    reliability 0, state FL_LOC_LOST, localized false: never a pose in a
 *    corner of the carpet.
 *  - localized = state == FL_LOC_TRACKING && reliability_q16 >=
 *    FL_LOC_LOCALIZED_Q16: the pose is right at least half the time.
 *    A behaviour gates on reliability_q16 (the share it can accept), or on
 *    localized.
 *  - sd_x_mm, sd_y_mm, cov_xy_mm2: the spread of the belief around the
 *    estimate (second moments about it; the mirror hypothesis excluded);
 *    sd_heading the heading's (binary angle; 32767: no heading
 *    information).  A description of the belief, not calibrated errors.
 *  - mirror_q16: on a symmetric field, the weight of the pose rotated
 *    180 deg about the centre (-x, -y, heading + 180 deg) relative to the
 *    estimate's, given the belief and what the game told (65535: as
 *    possible, 0: excluded or an asymmetric field).
 */
typedef struct {
    int32_t x_mm, y_mm;          /* field frame */
    fl_angle_t heading;
    uint16_t reliability_q16;    /* Q0.16 in [0, 65535] ~ [0, 1]: calibrated,
                                    see above */
    uint8_t peak_q8;             /* the chosen mode's peak (localizer's own
                                    measure of belief; 255 = 1) */
    uint16_t mode_cells;         /* size of the chosen mode (cells,
                                    particles, ...: the localizer's unit) */
    bool switched;               /* the estimate left the tracked mode */
    fl_loc_state_t state;        /* LOST, AMBIGUOUS, TRACKING */
    bool localized;              /* TRACKING and reliability >= 1/2 */
    uint16_t sd_x_mm, sd_y_mm;   /* spread of the belief around the pose */
    int32_t cov_xy_mm2;          /* its covariance (mm^2) */
    fl_angle_t sd_heading;       /* heading spread (32767: unknown) */
    uint16_t mirror_q16;         /* mirror pose's weight / the estimate's */
    uint16_t score_q16;          /* the localizer's own uncalibrated measure
                                    (fuzzy: consistency x compactness x
                                    (1 - bias) x uniqueness) */
    uint16_t since_obs;          /* predict calls since an observation was
                                    last applied (saturating) */
} fl_loc_estimate_t;

/* Counters every localizer keeps (0 when a localizer has no such event);
 * the tools print these (saturating, since init). */
typedef struct {
    uint32_t predicts, updates;
    uint32_t obs_used, obs_gated, obs_ignored;
    uint32_t odo_rejected;
    uint32_t empty_resets, kidnaps, mode_switches, resets;
    uint32_t reseeds, reseeds_refused;   /* fl_loc_reseed applied / refused */
} fl_loc_stats_t;

/* A tunable parameter: params block + offset, `size` bytes (1, 2 or 4),
 * signed or not, valid range [min, max]. */
typedef struct {
    const char *name;
    uint16_t offset;
    uint8_t size;
    bool is_signed;
    int32_t min, max;
} fl_loc_param_t;

/* A localizer whose belief lives on a grid shows it cell by cell (belief
 * pictures): nx x ny cells of cell_mm, cell (ix, iy) centred at
 * (x0 + ix * cell + cell / 2, y0 + iy * cell + cell / 2). */
typedef struct {
    uint16_t nx, ny;
    int32_t x0_mm, y0_mm;
    int32_t cell_mm;
} fl_loc_grid_t;

typedef struct {
    uint8_t height_q8;           /* most possible heading's possibility */
    fl_angle_t heading;          /* that heading */
    int32_t spread;              /* how far around it the heading is fully
                                    possible (binary angle, 0..32768) */
} fl_loc_cell_t;

/* A localizer whose belief is a set of weighted samples (particles) shows
 * them one by one (belief pictures, evaluation). */
typedef struct {
    int32_t x_mm, y_mm;          /* field frame */
    fl_angle_t heading;
    uint16_t weight_q16;         /* relative to the heaviest sample
                                    (65535 = as heavy; 0 = negligible) */
    bool in_mode;                /* belongs to the mode the estimate reports */
    /* the sample's own spread (a particle carrying a Gaussian, upf; 0 for
     * a point sample) */
    uint16_t sd_x_mm, sd_y_mm;
    int32_t cov_xy_mm2;
    fl_angle_t sd_heading;
} fl_loc_sample_t;

typedef struct fl_localizer {
    const char *name;            /* "fuzzy" */
    const char *summary;         /* one line */
    size_t state_size;           /* bytes of caller-owned state */
    size_t params_size;          /* bytes of caller-owned params */
    const fl_loc_param_t *param; /* parameter table, n_param entries */
    uint16_t n_param;

    void (*params_default)(void *params);
    void (*params_preset)(void *params, fl_loc_preset_t preset);
    /* Only the camera-dependent part of a vision preset, applied to
     * parameters the caller already holds (e.g. preset VISION, then its
     * own changes, then this with the actual camera's preset): a no-op
     * for FL_LOC_PRESET_DEFAULT and _VISION, and for parameters that are
     * not a vision preset's (fuzzy: fl_fuzzy_params_lowres). */
    void (*params_adapt)(void *params, fl_loc_preset_t preset);
    fl_status_t (*params_check)(const void *params);
    /* params NULL: defaults.  The state keeps a pointer to field.
     * caller_cfg: the caller's FL_CONFIG_FINGERPRINT (config.h); another
     * than the library's gives FL_ERR_CONFIG and an empty state (the
     * state has the library's state_size, but the observation lists the
     * caller would pass have the caller's layout).  fl_loc_init passes
     * it; a direct call passes FL_CONFIG_FINGERPRINT. */
    fl_status_t (*init)(void *state, const fl_field_t *field,
                        const void *params, uint32_t caller_cfg);
    /* The state's current parameters (read/write between calls, like
     * fl_fuzzy_t.params), NULL if uninitialized. */
    void *(*params_of)(void *state);

    void (*predict)(void *state, int32_t dx_mm, int32_t dy_mm,
                    fl_angle_t dtheta);
    /* view NULL or !valid: no negative information. */
    uint16_t (*update)(void *state, const fl_obs_list_t *obs,
                       const fl_obs_view_t *view);
    bool (*estimate)(void *state, fl_loc_estimate_t *out);

    void (*reset_ignorance)(void *state);
    void (*reset_pose)(void *state, int32_t x_mm, int32_t y_mm,
                       fl_angle_t heading, int32_t pos_unc_mm,
                       fl_angle_t heading_unc);
    void (*reset_penalty)(void *state, int32_t x_mm, int32_t pos_unc_mm,
                          fl_angle_t heading_unc);
    void (*set_prior_half)(void *state, int half);
    void (*set_prior_pose)(void *state, int32_t x_mm, int32_t y_mm,
                           fl_angle_t heading, int32_t radius_mm);
    void (*clear_prior)(void *state);

    bool (*check)(const void *state);
    /* Possibility (or density normalized to the peak) of a pose, Q16
     * (65536 = 1); 0 off the field. */
    uint32_t (*possibility_q16)(const void *state, int32_t x_mm,
                                int32_t y_mm, fl_angle_t heading);
    void (*stats)(const void *state, fl_loc_stats_t *out);
    /* Grid geometry (false: no grid, or uninitialized: the host's belief
     * pictures need it) and one cell (false outside the grid). */
    bool (*belief_grid)(const void *state, fl_loc_grid_t *out);
    bool (*belief_cell)(const void *state, int ix, int iy, fl_loc_cell_t *out);
    /* Samples (particles): how many there are (0: the belief is not a set
     * of samples, or uninitialized) and the i-th (false out of range). */
    uint16_t (*belief_samples)(const void *state);
    bool (*belief_sample)(const void *state, uint16_t i, fl_loc_sample_t *out);
    /* Re-seeding from an observer's report (obs.h fl_obs_report_t; seed
     * 003 section 3.4): the belief replaced by (particles: draws from) the
     * foot's Gaussian with the report's sd in position and the current
     * estimate's heading (sd pi/8 or the estimate's, if wider) in heading;
     * a possibility grid intersects its belief with a disc around the foot
     * instead (fuzzy.h fl_fuzzy_reseed).  The foot is tracked afterwards.
     * FL_OK; FL_ERR_STATE (uninitialized); FL_ERR_NULL, FL_ERR_RANGE,
     * FL_ERR_STALE (a bad report, fl_obs_report_check: counted in
     * reseeds_refused, the state unchanged). */
    fl_status_t (*reseed)(void *state, const fl_obs_report_t *r);
    /* How far the belief has spread, mm: the root of the variance of x
     * plus that of y over the whole belief (every mode, not only the
     * estimate's; a tracked mode's mirror on a symmetric field folded
     * onto it), UINT32_MAX when uninitialized.  A caller re-seeds when it
     * exceeds its threshold (FL_LOC_RESEED_SPREAD_MM). */
    uint32_t (*spread_mm)(const void *state);
    /* Whether update reads obs->points (white line points: relmap's tie
     * break).  A producer that pays to extract them (a simulator, a vision
     * path with a spare stage) may leave them out for a localizer that
     * does not; the others' results do not depend on them. */
    bool reads_points;
} fl_localizer_t;

/* The spread (spread_mm) beyond which a belief is taken to have spread
 * (seed 003 re-seeds "when particles spread"): FL_LOC_GOOD_MM, the
 * tolerance within which an estimate counts as right.  Under total
 * ignorance an SPL carpet's spread is about 3,000 mm; a converged belief's
 * a few hundred at most. */
#define FL_LOC_RESEED_SPREAD_MM FL_LOC_GOOD_MM

/* ---- catalogue ---------------------------------------------------------- */

/* The fuzzy position grid (fuzzy.h; adapter src/loc/loc_fuzzy.c), "fuzzy". */
extern const fl_localizer_t fl_localizer_fuzzy;
/* Augmented Monte Carlo localization (mcl.h; adapter src/loc/loc_mcl.c),
 * "mcl". */
extern const fl_localizer_t fl_localizer_mcl;
/* The unscented particle filter (upf.h; adapter src/loc/loc_upf.c), "upf". */
extern const fl_localizer_t fl_localizer_upf;
/* Seed 002's particle grid with the relative landmark map (relmap.h;
 * adapter src/loc/loc_relmap.c), "relmap". */
extern const fl_localizer_t fl_localizer_relmap;

/* NULL for NULL or an unknown name. */
const fl_localizer_t *fl_localizer_find(const char *name);
uint16_t fl_localizer_count(void);
const fl_localizer_t *fl_localizer_get(uint16_t i);   /* NULL out of range */

/* ---- parameters by name ------------------------------------------------- */

const fl_loc_param_t *fl_localizer_param_find(const fl_localizer_t *loc,
                                              const char *name);
/* FL_OK, FL_ERR_NULL, FL_ERR_NOT_FOUND, FL_ERR_RANGE (value outside
 * [min, max]: params unchanged). */
fl_status_t fl_localizer_param_set(const fl_localizer_t *loc, void *params,
                                   const char *name, int32_t value);
fl_status_t fl_localizer_param_get(const fl_localizer_t *loc,
                                   const void *params, const char *name,
                                   int32_t *value);

/* ---- checked wrappers (NULL loc or state: no-op / error / false / 0) ---- */

/* loc->init with the caller's FL_CONFIG_FINGERPRINT: FL_ERR_CONFIG when
 * the caller's config.h differs from the library's (the state is left
 * empty, as after any other init error). */
fl_status_t fl_loc_init_cfg(const fl_localizer_t *loc, void *state,
                            const fl_field_t *field, const void *params,
                            uint32_t caller_cfg);
static inline fl_status_t fl_loc_init(const fl_localizer_t *loc, void *state,
                                      const fl_field_t *field, const void *params)
{
    return fl_loc_init_cfg(loc, state, field, params, FL_CONFIG_FINGERPRINT);
}
void fl_loc_predict(const fl_localizer_t *loc, void *state, int32_t dx_mm,
                    int32_t dy_mm, fl_angle_t dtheta);
uint16_t fl_loc_update(const fl_localizer_t *loc, void *state,
                       const fl_obs_list_t *obs, const fl_obs_view_t *view);
bool fl_loc_estimate(const fl_localizer_t *loc, void *state,
                     fl_loc_estimate_t *out);
bool fl_loc_check(const fl_localizer_t *loc, const void *state);
/* loc->reseed; FL_ERR_NULL for a NULL loc, state or report. */
fl_status_t fl_loc_reseed(const fl_localizer_t *loc, void *state, const fl_obs_report_t *r);
/* loc->spread_mm; UINT32_MAX for NULL. */
uint32_t fl_loc_spread_mm(const fl_localizer_t *loc, const void *state);
/* Whether the belief has spread beyond threshold_mm (false for NULL: an
 * unusable state is no reason to re-seed; fl_loc_reseed refuses it). */
bool fl_loc_spread_beyond(const fl_localizer_t *loc, const void *state, uint32_t threshold_mm);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_LOCALIZER_H */

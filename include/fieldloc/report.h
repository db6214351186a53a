/*
 * fieldloc/report.h - what to do with an observer's reports of the players'
 * feet (obs.h fl_obs_report_t; seed 003's coach): which report is whose,
 * which to refuse, when to re-seed, and the message that carries them.
 *
 * Seed 003 leaves open which report belongs to which player.  Two answers,
 * both here:
 *
 *  - Coach side (fl_report_assign): the coach knows each report's team
 *    (jersey colour) and hears every player's own estimate (team
 *    communication: fl_report_claim_t).  It numbers its reports by a
 *    globally optimal assignment per team: minimum total cost over all
 *    one-to-one matchings of reports to claims, the cost of a pair the
 *    squared distance normalised by the variances of both (a chi-square
 *    with two degrees of freedom), a report beyond the gate to every claim
 *    left unnumbered.  Greedy nearest-first fails where two players'
 *    estimates are swapped or one is lost; the global one does not need
 *    every estimate to be right, only the sum.
 *  - Player side (fl_report_pick): a report carrying the player's number is
 *    its report; without numbers, the report of its own team nearest its
 *    own estimate, refused when a second one is about as near.
 *
 * Contradictions are refused with a status and counted, and the player's
 * filter is never touched by a refused report: two reports of one player
 * in one frame that disagree, a report that moved farther than a walking
 * robot can since the last accepted one, reports stale or off the carpet
 * (fl_obs_report_check).  fl_report_apply is the step a robot's runtime
 * calls each frame: it picks, checks, and re-seeds (localizer.h
 * fl_loc_reseed) only when the belief has spread beyond a threshold.
 *
 * The wire format (fl_report_encode / fl_report_decode) is fixed-size and
 * byte-order independent (every field written byte by byte, little-endian),
 * FL_REPORT_MSG_BYTES long:
 *
 *   offset  size  field
 *   0       2     magic 'F' 'R'
 *   2       1     version FL_REPORT_WIRE_VERSION
 *   3       1     count n, 0..FL_REPORT_MAX
 *   4       4     the coach's frame time, ms of the coach's clock (uint32)
 *   8       12 x FL_REPORT_MAX  report slots; slot k < n:
 *                   x_mm int16, y_mm int16, sd_mm uint16, confidence u8,
 *                   team u8, player u8, reserved u8 (0), age_ms uint16;
 *                 slots k >= n all zero
 *   8+12*FL_REPORT_MAX  4   CRC-32 (IEEE 802.3, reflected, as zlib's
 *                 crc32) of every byte before it
 *
 * Nothing here allocates or uses floating point; the work of every call is
 * bounded by the capacities of config.h (FL_REPORT_MAX reports per frame,
 * FL_REPORT_MAX_PLAYERS claims per team).
 */
#ifndef FIELDLOC_REPORT_H
#define FIELDLOC_REPORT_H

#include "fieldloc/common.h"
#include "fieldloc/config.h"
#include "fieldloc/field.h"
#include "fieldloc/obs.h"
#include "fieldloc/localizer.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Player numbers are 1..FL_REPORT_PLAYER_MAX; 0 is "unknown". */
#define FL_REPORT_PLAYER_MAX 31

/* The default gate of the coach's assignment: a report whose normalised
 * squared distance (chi-square, 2 degrees of freedom) to a claim exceeds
 * 16 (Q8: 4096; about 4 standard deviations, exceeded by a true pair with
 * probability 3e-4) is never matched to it. */
#define FL_REPORT_GATE_Q8 4096u
/* Largest gate accepted (chi-square 255). */
#define FL_REPORT_GATE_MAX_Q8 65535u

/* Player side: a report without a number is ambiguous when the second
 * nearest report of the player's team is less than
 * max(FL_REPORT_AMBIG_MM, d1 / 2) farther from the player's estimate than
 * the nearest (d1): the player's estimate cannot tell them apart. */
#define FL_REPORT_AMBIG_MM 500
/* Two reports of one team and player in one frame that are farther apart
 * than this contradict each other (an observer sees one foot per robot;
 * four of its standard deviations, 4 x FL_OBS_REPORT_SD_MM). */
#define FL_REPORT_CONFLICT_MM 500
/* A walking robot is slower than this (an SPL NAO walks 200-350 mm/s). */
#define FL_REPORT_MAX_SPEED_MM_S 500
/* A report farther than FL_REPORT_MAX_SPEED_MM_S x the time since the last
 * accepted report plus FL_REPORT_JUMP_SDS x (the sum of both reports' sd)
 * from that report has jumped. */
#define FL_REPORT_JUMP_SDS 2

/* ---- counters ----------------------------------------------------------- */

/* Every refusal and decision, counted (saturating).  Per report where the
 * name says so, per call otherwise. */
typedef struct {
    /* fl_report_apply, one per call: what happened */
    uint32_t frames;
    uint32_t reseeded, not_needed, none;
    uint32_t ambiguous, conflict, jump, gated;
    /* per report (apply, pick and assign) */
    uint32_t stale, off_carpet, other_team;
    /* fl_report_assign, per report of the caller's reports */
    uint32_t assigned, unassigned;
    uint32_t claims_refused;     /* bad or duplicate claims, extra claims */
    /* fl_report_decode, per message */
    uint32_t msgs, msg_truncated, msg_corrupt, msg_version, msg_range;
    /* calls refused for bad arguments (NULL, uninitialized state, ...) */
    uint32_t bad_calls;
} fl_report_stats_t;

/* ---- coach side: numbering the reports ----------------------------------- */

/* One player's own estimate, heard by the coach over team communication. */
typedef struct {
    int32_t x_mm, y_mm;      /* its estimate, field frame */
    uint32_t spread_mm;      /* its fl_loc_spread_mm (root of var x + var y) */
    uint8_t team;            /* fl_color_t jersey (FL_COLOR_RED, _BLUE) */
    uint8_t player;          /* 1..FL_REPORT_PLAYER_MAX */
} fl_report_claim_t;

/*
 * Number the reports of one coach frame: for every team that has claims,
 * the reports of that team that pass fl_obs_report_check (others get 0,
 * counted stale / off_carpet) are matched one-to-one to that team's claims
 * so that the sum of the pairs' costs plus gate x (reports left unmatched)
 * is least; reports[i].player is set to the matched claim's number, 0 when
 * unmatched or when no claim has its team.  A pair's cost, Q8:
 *     256 x d^2 / (spread^2 / 2 + sd^2)
 * d the distance from the report to the claim's estimate, spread the
 * claim's spread_mm (clamped to [FL_OBS_REPORT_SD_MIN_MM, 8000]) and sd the
 * report's sd_mm: the normalised squared distance of the difference of two
 * independent Gaussians, per axis variance spread^2 / 2 + sd^2.  A pair
 * whose cost exceeds gate_q8 is never matched (0: FL_REPORT_GATE_Q8).
 *
 * Exact: the integer Hungarian method (shortest augmenting paths with
 * potentials, 64-bit integer costs) on n_team reports x (claims + n_team
 * "unmatched" columns).  Ties: among matchings of equal total cost (cost in
 * Q8 units), the one that gives the first report (in the caller's order)
 * the lowest player number, then the second, ...  ("unmatched" after every
 * number) - a cost perturbation below one Q8 unit makes this exact.
 * Worst-case work per team: n^2 x m steps with n <= FL_REPORT_MAX reports
 * and m <= FL_REPORT_MAX_PLAYERS + FL_REPORT_MAX columns (10 x 10 x 16 =
 * 1,600 at the defaults), once per team that has claims.
 *
 * Claims: more than FL_REPORT_MAX_PLAYERS of a team, a second claim of the
 * same team and number, a number outside 1..FL_REPORT_PLAYER_MAX are
 * ignored and counted (claims_refused).
 * FL_OK; FL_ERR_NULL (reports or field NULL with n_reports > 0, claims NULL
 * with n_claims > 0); FL_ERR_SIZE (n_reports > FL_REPORT_MAX or n_claims >
 * 2 x FL_REPORT_MAX_PLAYERS: nothing written); FL_ERR_RANGE (gate_q8 >
 * FL_REPORT_GATE_MAX_Q8: nothing written).  st may be NULL.
 */
fl_status_t fl_report_assign(fl_obs_report_t *reports, size_t n_reports,
                             const fl_report_claim_t *claims, size_t n_claims,
                             const fl_field_t *field, uint32_t gate_q8,
                             fl_report_stats_t *st);

/* The cost fl_report_assign gives the pair (report, claim), Q8 (saturating
 * at UINT32_MAX; for tests and tools). */
uint32_t fl_report_pair_cost_q8(const fl_obs_report_t *r, const fl_report_claim_t *c);

/* ---- player side --------------------------------------------------------- */

/* What fl_report_pick / fl_report_apply decided. */
typedef enum {
    FL_REPORT_RESEEDED = 0,   /* a report is this player's and its belief had
                                 spread: re-seeded from it */
    FL_REPORT_NOT_NEEDED = 1, /* a report is this player's, accepted; the
                                 belief has not spread (pick: accepted) */
    FL_REPORT_NONE = 2,       /* no report of this player's team that could
                                 be its (none, or all numbered for others) */
    FL_REPORT_AMBIGUOUS = 3,  /* no numbers, and two reports of its team are
                                 about as near its estimate */
    FL_REPORT_CONFLICT = 4,   /* two reports of its team and number in the
                                 frame farther apart than FL_REPORT_CONFLICT_MM */
    FL_REPORT_JUMP = 5,       /* farther from the last accepted report than a
                                 walking robot can have moved */
    FL_REPORT_STALE = 6,      /* its only candidates were stale */
    FL_REPORT_OFF_CARPET = 7, /* its only candidates failed
                                 fl_obs_report_check's range test (off the
                                 carpet, bad sd, confidence 0) */
    FL_REPORT_GATED = 8,      /* no numbers, and the nearest report of its
                                 team is beyond the gate from its estimate
                                 (chi-square of distance vs its spread and
                                 the report's sd > FL_REPORT_GATE_Q8) */
    FL_REPORT_BAD_CALL = 9,   /* NULL arguments, uninitialized state or
                                 tracker, n > FL_REPORT_MAX */
    FL_REPORT_REFUSED = 10    /* the localizer refused the re-seed
                                 (fl_loc_reseed's status; not expected
                                 after the checks here) */
} fl_report_result_t;

/* Static name of a result ("reseeded", "ambiguous", ...; never NULL). */
const char *fl_report_result_str(fl_report_result_t r);

/* Who and when the player is. */
typedef struct {
    uint8_t team;                /* fl_color_t jersey */
    uint8_t player;              /* its number, 1..FL_REPORT_PLAYER_MAX; 0
                                    unknown (only unnumbered reports can be
                                    its then) */
    uint32_t now_ms;             /* the robot's clock when the reports arrive
                                    (a report was seen at now_ms - age_ms) */
    const fl_field_t *field;     /* for fl_obs_report_check */
    const fl_loc_estimate_t *est;/* this frame's fl_loc_estimate, for
                                    fl_report_apply (which must not call it:
                                    an estimate updates the localizer's mode
                                    bookkeeping); unused by fl_report_pick */
} fl_report_self_t;

/* The player's memory between frames: the last accepted report (for the
 * jump test) and the counters.  Caller-owned; fl_report_tracker_init
 * before the first frame, again after the robot is moved by hand (a
 * penalty, a manual placement: the jump test would refuse the truth). */
typedef struct {
    uint32_t magic;              /* set by init: an uninitialized tracker is
                                    refused (FL_REPORT_BAD_CALL) */
    bool have_last;
    int32_t last_x_mm, last_y_mm, last_sd_mm;
    uint32_t last_ms;            /* when it was seen (robot clock) */
    fl_report_stats_t stats;
} fl_report_tracker_t;

void fl_report_tracker_init(fl_report_tracker_t *t);

/*
 * Which of a frame's reports is this player's, without touching any
 * filter.  In order:
 *  1. reports of another team are ignored (other_team); the rest that fail
 *     fl_obs_report_check are dropped (stale, off_carpet);
 *  2. me->player != 0 and some report carries it: those are the
 *     candidates; two of them farther apart than FL_REPORT_CONFLICT_MM:
 *     FL_REPORT_CONFLICT; else the one with the least sd (first on ties);
 *  3. else among the unnumbered reports of the team: the nearest to
 *     (est_x_mm, est_y_mm); FL_REPORT_AMBIGUOUS when the second nearest is
 *     about as near (FL_REPORT_AMBIG_MM), FL_REPORT_GATED beyond the gate
 *     (est_spread_mm: the player's fl_loc_spread_mm); reports numbered for
 *     other players are never its;
 *  4. the chosen report jumped (FL_REPORT_JUMP_SDS, FL_REPORT_MAX_SPEED_MM_S
 *     since t's last accepted report): FL_REPORT_JUMP;
 *  5. accepted: *index set, t's last report updated, FL_REPORT_NOT_NEEDED.
 * Nothing candidate left after 1: FL_REPORT_STALE or _OFF_CARPET if a
 * dropped report could have been its, else FL_REPORT_NONE.  Refusals
 * (ambiguous, conflict, jump, gated) are counted in t->stats; frames,
 * reseeded, not_needed and none are fl_report_apply's.
 */
fl_report_result_t fl_report_pick(const fl_obs_report_t *reports, size_t n,
                                  const fl_report_self_t *me, int32_t est_x_mm,
                                  int32_t est_y_mm, uint32_t est_spread_mm,
                                  fl_report_tracker_t *t, size_t *index);

/*
 * The step a robot's runtime calls each frame that brings reports (n may
 * be 0): fl_report_pick against me->est (the caller's fl_loc_estimate of
 * this frame; NULL: FL_REPORT_BAD_CALL) and the localizer's spread; then, for an accepted report, fl_loc_reseed only when
 * fl_loc_spread_beyond(loc, state, spread_threshold_mm) (0:
 * FL_LOC_RESEED_SPREAD_MM).  The state is written only by that re-seed: a
 * refused report, or one that is not needed, leaves it untouched.  Counted
 * in t->stats (frames and the result).
 */
fl_report_result_t fl_report_apply(const fl_localizer_t *loc, void *state,
                                   const fl_obs_report_t *reports, size_t n,
                                   const fl_report_self_t *me,
                                   uint32_t spread_threshold_mm,
                                   fl_report_tracker_t *t);

/* ---- the message --------------------------------------------------------- */

#define FL_REPORT_WIRE_VERSION 1
#define FL_REPORT_MSG_HEADER_BYTES 8
#define FL_REPORT_MSG_SLOT_BYTES 12
#define FL_REPORT_MSG_BYTES \
    (FL_REPORT_MSG_HEADER_BYTES + FL_REPORT_MSG_SLOT_BYTES * FL_REPORT_MAX + 4)

typedef struct {
    uint32_t frame_ms;           /* the coach's clock at its frame */
    uint8_t n;                   /* reports, 0..FL_REPORT_MAX */
    fl_obs_report_t report[FL_REPORT_MAX];
} fl_report_msg_t;

/* Write msg into buf (exactly FL_REPORT_MSG_BYTES).  FL_OK; FL_ERR_NULL;
 * FL_ERR_SIZE (cap < FL_REPORT_MSG_BYTES); FL_ERR_RANGE (n >
 * FL_REPORT_MAX, a report's x or y outside int16, sd outside
 * [FL_OBS_REPORT_SD_MIN_MM, FL_OBS_REPORT_SD_MAX_MM], age outside
 * 0..65535, team above FL_COLOR_BLUE, player above FL_REPORT_PLAYER_MAX):
 * nothing written on error. */
fl_status_t fl_report_encode(const fl_report_msg_t *msg, uint8_t *buf, size_t cap);

/* Read a message of len bytes.  FL_OK; FL_ERR_NULL; FL_ERR_SIZE (len is
 * not FL_REPORT_MSG_BYTES: truncated or padded; counted msg_truncated);
 * FL_ERR_FORMAT (checksum or magic wrong: corrupt, msg_corrupt; or another
 * version, msg_version); FL_ERR_RANGE (count above FL_REPORT_MAX, a used
 * slot's sd, team, player or reserved byte out of range, an unused slot not
 * zero: msg_range).  On any error *msg is zeroed (n = 0).  st may be NULL;
 * a message read counts in msgs.  The reports' age_ms are as the coach
 * sent them: the caller adds the delay since (its own clock). */
fl_status_t fl_report_decode(const uint8_t *buf, size_t len, fl_report_msg_t *msg,
                             fl_report_stats_t *st);

/* CRC-32 (IEEE, zlib's crc32 of n bytes from 0). */
uint32_t fl_report_crc32(const uint8_t *p, size_t n);

#ifdef __cplusplus
}
#endif

#endif /* FIELDLOC_REPORT_H */

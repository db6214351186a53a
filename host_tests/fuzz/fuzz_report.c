/*
 * libFuzzer harness: the report reader (report.h).  Arbitrary bytes go to
 * fl_report_decode and what it accepts goes to the coach's assignment and
 * to the per-frame step on a real localizer state of the catalogue (mcl,
 * upf, fuzzy), frame after frame.
 *
 * Input: byte 0 = localizer (low 2 bits, modulo the catalogue), field
 * (bits 2-3), start (bit 4: a told pose from byte 1, else ignorance);
 * byte 1 = the player's team (bit 0), number (bits 1-3, 0 unknown), spread
 * threshold (bits 4-7, x 150 mm); then records of 8 control bytes and
 * FL_REPORT_MSG_BYTES message bytes:
 *   [0,1] ms since the last record, [2] [3] odometry (mm, signed),
 *   [4] bit 0: reseal (write the right magic, version and checksum over
 *       the fuzzed bytes, so the range checks and the step are reached),
 *       bit 1: number the reports by the coach's assignment first (claims
 *       from bytes [5..7]), bit 2: the frame's estimate from the state
 * A short tail is decoded as it is (truncated).
 * Must hold: decode never accepts what encode would not write, and an
 * accepted message encodes back to the same bytes; the localizer's check
 * after every step; the state byte for byte unchanged unless the step says
 * it re-seeded; estimates on the carpet.
 */
#include "fieldloc/fieldloc.h"
#include "fieldloc/report.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static union { int64_t align; uint8_t b[256 * 1024]; } state, copy;
static uint8_t msgbuf[FL_REPORT_MSG_BYTES], again[FL_REPORT_MSG_BYTES];

static void reseal(uint8_t *b)
{
    uint32_t c;
    b[0] = 'F';
    b[1] = 'R';
    b[2] = FL_REPORT_WIRE_VERSION;
    c = fl_report_crc32(b, FL_REPORT_MSG_BYTES - 4);
    b[FL_REPORT_MSG_BYTES - 4] = (uint8_t)c;
    b[FL_REPORT_MSG_BYTES - 3] = (uint8_t)(c >> 8);
    b[FL_REPORT_MSG_BYTES - 2] = (uint8_t)(c >> 16);
    b[FL_REPORT_MSG_BYTES - 1] = (uint8_t)(c >> 24);
}

static void check_estimate(const fl_localizer_t *loc, const fl_field_t *f, fl_loc_estimate_t *e)
{
    int32_t hx = fl_field_carpet_half_x_mm(f), hy = fl_field_carpet_half_y_mm(f);
    if (!fl_loc_estimate(loc, state.b, e))
        abort();
    if (e->x_mm < -hx || e->x_mm > hx || e->y_mm < -hy || e->y_mm > hy)
        abort();
}

/* The coach's numbering with up to 3 claims built from c[0..2]. */
static void assign(fl_report_msg_t *m, const uint8_t *c, const fl_field_t *f, fl_report_stats_t *st)
{
    fl_report_claim_t cl[3];
    size_t i, k;
    fl_obs_report_t before[FL_REPORT_MAX];
    memcpy(before, m->report, sizeof before);
    for (i = 0; i < 3; i++) {
        cl[i].x_mm = ((int32_t)c[i] - 128) * 40;
        cl[i].y_mm = ((int32_t)c[(i + 1) % 3] - 128) * 25;
        cl[i].spread_mm = (uint32_t)c[i] * 30u;
        cl[i].team = (uint8_t)(FL_COLOR_RED + (c[i] & 1));
        cl[i].player = (uint8_t)(c[i] >> 5);
    }
    if (fl_report_assign(m->report, m->n, cl, c[0] % 4, f, (uint32_t)c[1] * 64u, st) != FL_OK)
        abort();
    /* a number given is a claim's of the report's team, once per team */
    for (i = 0; i < m->n; i++) {
        bool found = m->report[i].player == 0;
        for (k = 0; k < (size_t)(c[0] % 4) && !found; k++)
            found = cl[k].player == m->report[i].player && cl[k].team == m->report[i].team;
        if (!found)
            abort();
        for (k = 0; k < i; k++)
            if (m->report[i].player != 0 && m->report[k].player == m->report[i].player &&
                m->report[k].team == m->report[i].team)
                abort();
        before[i].player = m->report[i].player;
        if (memcmp(&before[i], &m->report[i], sizeof before[i]) != 0)
            abort();   /* only the number changes */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const fl_localizer_t *loc;
    const fl_field_t *field;
    fl_report_tracker_t trk;
    fl_report_stats_t cst;
    fl_report_self_t me;
    fl_loc_estimate_t e;
    size_t k;
    const size_t rec = 8 + FL_REPORT_MSG_BYTES;
    if (size < 2)
        return 0;
    loc = fl_localizer_get((uint16_t)((data[0] & 3) % fl_localizer_count()));
    field = fl_field_at((size_t)((data[0] >> 2) & 3) % fl_field_count());
    if (loc == NULL || field == NULL || loc->state_size > sizeof state.b)
        abort();
    if (fl_loc_init(loc, state.b, field, NULL) != FL_OK)
        abort();
    if (data[0] & 0x10)
        loc->reset_pose(state.b, ((int32_t)data[1] - 128) * 30, ((int32_t)data[1] - 128) * 20,
                        (fl_angle_t)(data[1] << 8), 300, 2000);
    fl_report_tracker_init(&trk);
    memset(&cst, 0, sizeof cst);
    memset(&me, 0, sizeof me);
    me.team = (uint8_t)(FL_COLOR_RED + (data[1] & 1));
    me.player = (uint8_t)((data[1] >> 1) & 7);
    me.field = field;
    me.est = &e;
    check_estimate(loc, field, &e);
    for (k = 2; k < size; k += rec) {
        const uint8_t *c = data + k;
        fl_report_msg_t m;
        fl_report_result_t res;
        fl_status_t s;
        size_t len = size - k;
        if (len < rec) {   /* a short tail: truncated */
            s = fl_report_decode(c, len, &m, &cst);
            if (len != FL_REPORT_MSG_BYTES && (s != FL_ERR_SIZE || m.n != 0))
                abort();
            break;
        }
        memcpy(msgbuf, c + 8, FL_REPORT_MSG_BYTES);
        if (c[4] & 1)
            reseal(msgbuf);
        s = fl_report_decode(msgbuf, FL_REPORT_MSG_BYTES, &m, &cst);
        if (s != FL_OK) {
            if (m.n != 0 || (s != FL_ERR_FORMAT && s != FL_ERR_RANGE))
                abort();
            continue;
        }
        if (fl_report_encode(&m, again, sizeof again) != FL_OK ||
            memcmp(again, msgbuf, FL_REPORT_MSG_BYTES) != 0)
            abort();
        if (c[4] & 2)
            assign(&m, c + 5, field, &cst);
        me.now_ms += (uint32_t)(c[0] | (c[1] << 8));
        loc->predict(state.b, (int8_t)c[2], (int8_t)c[3], 0);
        if (c[4] & 4)
            check_estimate(loc, field, &e);
        memcpy(copy.b, state.b, loc->state_size);
        res = fl_report_apply(loc, state.b, m.report, m.n, &me, (uint32_t)(data[1] >> 4) * 150u,
                              &trk);
        if (res > FL_REPORT_REFUSED)
            abort();
        if (res != FL_REPORT_RESEEDED && memcmp(copy.b, state.b, loc->state_size) != 0)
            abort();
        if (!loc->check(state.b))
            abort();
        if (fl_loc_spread_mm(loc, state.b) > 100000u)
            abort();
        check_estimate(loc, field, &e);
    }
    if (trk.stats.reseeded + trk.stats.not_needed + trk.stats.none > trk.stats.frames)
        abort();
    return 0;
}

/*
 * src/loc/report_wire.c - the report message (report.h): fixed size, every
 * field written and read byte by byte (little-endian), so the bytes are the
 * same whatever the host's byte order or struct layout; a CRC-32 over the
 * rest.  The reader trusts nothing: length, checksum, magic, version,
 * count, every used slot's ranges and every unused slot's zeros.
 */
#include "fieldloc/report.h"

#include "report_int.h"

#include <string.h>

#define CRC_OFFSET (FL_REPORT_MSG_HEADER_BYTES + FL_REPORT_MSG_SLOT_BYTES * FL_REPORT_MAX)

uint32_t fl_report_crc32(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    size_t i;
    int k;
    if (p == NULL)
        return 0;
    for (i = 0; i < n; i++) {
        c ^= p[i];
        for (k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

static void put16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
}

static void put32(uint8_t *p, uint32_t v)
{
    put16(p, v & 0xFFFFu);
    put16(p + 2, v >> 16);
}

static uint32_t get16(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8);
}

static uint32_t get32(const uint8_t *p)
{
    return get16(p) | (get16(p + 2) << 16);
}

static int32_t s16(uint32_t v)
{
    return v >= 0x8000u ? (int32_t)v - 0x10000 : (int32_t)v;
}

/* The ranges both ends hold a report to (report.h fl_report_encode). */
static bool slot_ok(const fl_obs_report_t *r)
{
    return r->x_mm >= INT16_MIN && r->x_mm <= INT16_MAX && r->y_mm >= INT16_MIN &&
           r->y_mm <= INT16_MAX && r->sd_mm >= FL_OBS_REPORT_SD_MIN_MM &&
           r->sd_mm <= FL_OBS_REPORT_SD_MAX_MM && r->age_ms >= 0 && r->age_ms <= 0xFFFF &&
           r->team <= FL_COLOR_BLUE && r->player <= FL_REPORT_PLAYER_MAX;
}

fl_status_t fl_report_encode(const fl_report_msg_t *msg, uint8_t *buf, size_t cap)
{
    size_t k;
    if (msg == NULL || buf == NULL)
        return FL_ERR_NULL;
    if (cap < FL_REPORT_MSG_BYTES)
        return FL_ERR_SIZE;
    if (msg->n > FL_REPORT_MAX)
        return FL_ERR_RANGE;
    for (k = 0; k < msg->n; k++)
        if (!slot_ok(&msg->report[k]))
            return FL_ERR_RANGE;
    memset(buf, 0, FL_REPORT_MSG_BYTES);
    buf[0] = 'F';
    buf[1] = 'R';
    buf[2] = FL_REPORT_WIRE_VERSION;
    buf[3] = msg->n;
    put32(buf + 4, msg->frame_ms);
    for (k = 0; k < msg->n; k++) {
        const fl_obs_report_t *r = &msg->report[k];
        uint8_t *p = buf + FL_REPORT_MSG_HEADER_BYTES + FL_REPORT_MSG_SLOT_BYTES * k;
        put16(p, (uint32_t)r->x_mm & 0xFFFFu);
        put16(p + 2, (uint32_t)r->y_mm & 0xFFFFu);
        put16(p + 4, (uint32_t)r->sd_mm);
        p[6] = r->confidence;
        p[7] = r->team;
        p[8] = r->player;
        p[9] = 0;
        put16(p + 10, (uint32_t)r->age_ms);
    }
    put32(buf + CRC_OFFSET, fl_report_crc32(buf, CRC_OFFSET));
    return FL_OK;
}

/* One slot's bytes into *r; false when out of range. */
static bool read_slot(const uint8_t *p, fl_obs_report_t *r)
{
    memset(r, 0, sizeof *r);
    r->x_mm = s16(get16(p));
    r->y_mm = s16(get16(p + 2));
    r->sd_mm = (int32_t)get16(p + 4);
    r->confidence = p[6];
    r->team = p[7];
    r->player = p[8];
    r->age_ms = (int32_t)get16(p + 10);
    return p[9] == 0 && slot_ok(r);
}

static bool all_zero(const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (p[i] != 0)
            return false;
    return true;
}

fl_status_t fl_report_decode(const uint8_t *buf, size_t len, fl_report_msg_t *msg,
                             fl_report_stats_t *st)
{
    size_t k, n;
    if (msg == NULL || buf == NULL) {
        REPORT_COUNT(st, bad_calls);
        if (msg != NULL)
            memset(msg, 0, sizeof *msg);
        return FL_ERR_NULL;
    }
    memset(msg, 0, sizeof *msg);
    REPORT_COUNT(st, msgs);
    if (len != FL_REPORT_MSG_BYTES) {
        REPORT_COUNT(st, msg_truncated);
        return FL_ERR_SIZE;
    }
    if (get32(buf + CRC_OFFSET) != fl_report_crc32(buf, CRC_OFFSET) || buf[0] != 'F' ||
        buf[1] != 'R') {
        REPORT_COUNT(st, msg_corrupt);
        return FL_ERR_FORMAT;
    }
    if (buf[2] != FL_REPORT_WIRE_VERSION) {
        REPORT_COUNT(st, msg_version);
        return FL_ERR_FORMAT;
    }
    n = buf[3];
    if (n > FL_REPORT_MAX) {
        REPORT_COUNT(st, msg_range);
        return FL_ERR_RANGE;
    }
    for (k = 0; k < FL_REPORT_MAX; k++) {
        const uint8_t *p = buf + FL_REPORT_MSG_HEADER_BYTES + FL_REPORT_MSG_SLOT_BYTES * k;
        bool good = k < n ? read_slot(p, &msg->report[k]) : all_zero(p, FL_REPORT_MSG_SLOT_BYTES);
        if (!good) {
            memset(msg, 0, sizeof *msg);
            REPORT_COUNT(st, msg_range);
            return FL_ERR_RANGE;
        }
    }
    msg->frame_ms = get32(buf + 4);
    msg->n = (uint8_t)n;
    return FL_OK;
}

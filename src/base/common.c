/* src/base/common.c - status strings. */
#include "fieldloc/common.h"

const char *fl_status_str(fl_status_t s)
{
    switch (s) {
    case FL_OK: return "ok";
    case FL_ERR_NULL: return "null pointer";
    case FL_ERR_SIZE: return "bad size";
    case FL_ERR_STRIDE: return "stride smaller than a row";
    case FL_ERR_FORMAT: return "bad pixel format";
    case FL_ERR_RANGE: return "parameter out of range";
    case FL_ERR_NOT_FOUND: return "not found";
    }
    return "unknown status";
}

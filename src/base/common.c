/* src/base/common.c - status strings, the library's version and
 * configuration fingerprint. */
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
    case FL_ERR_CONFIG:
        return "caller compiled with different config.h capacities than the library; "
               "rebuild with the installed config.h";
    case FL_ERR_MISMATCH: return "frame size differs from the camera model";
    case FL_ERR_CAMERA: return "camera not initialized (fl_camera_init failed or never ran)";
    case FL_ERR_STALE: return "report too old";
    case FL_ERR_STATE: return "localizer state not initialized (its init failed or never ran)";
    }
    return "unknown status";
}

uint32_t fl_config_fingerprint(void)
{
    return FL_CONFIG_FINGERPRINT;
}

const char *fl_version(void)
{
    return FL_VERSION_STRING;
}

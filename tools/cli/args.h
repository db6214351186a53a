/*
 * tools/cli/args.h - checked numeric options for every CLI command.
 *
 * Each parser reads the whole text (strtol / strtod end pointer, errno for
 * overflow; no leading blank, no "nan"/"inf"), checks the value against
 * [lo, hi] and, on failure, prints ONE line on stderr:
 *     fieldloc detect: --repeat: "abc" is not a number
 *     fieldloc detect: --repeat: "1.5" is not an integer
 *     fieldloc detect: --neck: 20 is out of range 50..2000 mm
 * and returns -1 (the command then exits with status 2); 0 on success.
 * unit (may be NULL) follows the range in the message.
 *
 * Ranges used by the commands (the lead's list in the CLI's --help texts):
 * head angles within the robot's joints (NAO HeadPitch -38.5..29.5 deg,
 * HeadYaw -119.5..119.5 deg, from the Aldebaran NAO joint documentation)
 * or, for a non-NAO camera, the camera model's limit (optical axis within
 * 90 deg of the horizontal, include/fieldloc/camera.h); neck heights within
 * FL_CAMERA_NECK_MIN_MM..MAX_MM; positions within the field's carpet plus
 * ARG_FIELD_MARGIN_MM.
 */
#ifndef FL_TOOLS_ARGS_H
#define FL_TOOLS_ARGS_H

#include "fieldloc/fieldloc.h"

#include <stdint.h>

/* Positions may lie this far beyond the carpet (a robot carried off the
 * field, a ball kicked out). */
#define ARG_FIELD_MARGIN_MM 1000

/* NAO head joints, radians (Aldebaran "NAO - Joints": HeadYaw -119.5..119.5
 * deg = -2.0857..2.0857 rad, HeadPitch -38.5..29.5 deg = -0.6720..0.5149
 * rad; NAOqi convention, pitch > 0 looks down). */
#define ARG_NAO_PITCH_MIN_RAD (-0.6720)
#define ARG_NAO_PITCH_MAX_RAD 0.5149
#define ARG_NAO_YAW_MAX_RAD 2.0857

int arg_long(const char *cmd, const char *opt, const char *text, long lo, long hi,
             const char *unit, long *out);
int arg_int(const char *cmd, const char *opt, const char *text, int lo, int hi,
            const char *unit, int *out);
int arg_int32(const char *cmd, const char *opt, const char *text, int32_t lo, int32_t hi,
              const char *unit, int32_t *out);
/* Seeds: any 0..4294967295. */
int arg_u32(const char *cmd, const char *opt, const char *text, uint32_t *out);
int arg_double(const char *cmd, const char *opt, const char *text, double lo, double hi,
               const char *unit, double *out);

/* Head angles in radians (NAOqi convention) for camera model m: NAO
 * joint ranges for the NAO cameras (names nao*, uva2013), else the camera
 * limit on the pitch (mount tilt + pitch + the model's pitch offset within
 * +-90 deg) and a half turn either way on the yaw.  opt names the option
 * in messages ("--head"). */
int arg_head(const char *cmd, const char *opt, const fl_camera_model_t *m,
             const char *pitch_text, const char *yaw_text, double *pitch_rad,
             double *yaw_rad);
/* Range of head pitch / yaw for m, radians, and a name for messages. */
void arg_head_range(const fl_camera_model_t *m, double *pitch_lo, double *pitch_hi,
                    double *yaw_lo, double *yaw_hi, const char **what);

/* A field position (mm): |x| <= carpet half length + margin (axis 'x') or
 * |y| <= carpet half width + margin (axis 'y'). */
int arg_field_mm(const char *cmd, const char *opt, const char *text, const fl_field_t *f,
                 char axis, double *out);

/* An argument no branch took: "unknown option --foo", or, when arg is one
 * of the options listed in valued ("--field=1 --head=2 ..."), "--head needs
 * 2 values"; a non-option: "unexpected argument X".  Returns 2. */
int arg_unknown(const char *cmd, const char *arg, const char *valued);

#endif

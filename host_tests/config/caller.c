/*
 * host_tests/config/caller.c - a user program calling every public init,
 * compiled and run at test time by host_tests/test_config.c: once with the
 * library's configuration (every init FL_OK) and once with another
 * config.h value (every init FL_ERR_CONFIG, nothing written).  Prints one
 * line per init, "NAME STATUS UNTOUCHED": UNTOUCHED 1 when the object
 * still holds the byte pattern it was filled with before the call (for
 * the localizer, whose state the library sizes, EMPTY instead: 1 when the
 * state is left uninitialized).  Not part of the runner (its own main).
 */
#include <fieldloc/fieldloc.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static fl_camera_t cam;
static fl_color_table_t colors;
static fl_scan_t scan;
static fl_lines_t lines;
static fl_crossings_t crossings;
static fl_beacon_t beacon;
static fl_vision_t vision;
static fl_fuzzy_t fuzzy;

#define PATTERN 0xA5

static int untouched(const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n; i++)
        if (b[i] != PATTERN)
            return 0;
    return 1;
}

#define RUN(name, obj, call)                                             \
    do {                                                                 \
        fl_status_t st_;                                                 \
        memset(&(obj), PATTERN, sizeof(obj));                            \
        st_ = (call);                                                    \
        printf("%s %d %d\n", name, (int)st_, untouched(&(obj), sizeof(obj))); \
    } while (0)

int main(void)
{
    const fl_field_t *field = fl_field_find("spl2013");
    const fl_camera_model_t *model = fl_camera_model_find("nao4-bottom-320");
    const fl_localizer_t *loc = fl_localizer_find("fuzzy");
    fl_camera_pose_t pose;
    fl_color_params_t cp;
    fl_scan_params_t sp;
    fl_lines_params_t lp;
    fl_crossings_params_t xp;
    fl_beacon_params_t bp;
    fl_vision_params_t vp;
    fl_status_t st;
    void *state;
    if (!field || !model || !loc)
        return 2;
    memset(&pose, 0, sizeof pose); /* roll and torso angles 0: level */
    pose.neck_height_mm = model->default_neck_height_mm;
    pose.head_pitch = 0;
    pose.head_yaw = 0;
    pose.pitch_offset = model->default_pitch_offset;
    fl_color_params_default(&cp);
    fl_scan_params_default(&sp);
    fl_lines_params_default(&lp);
    fl_crossings_params_default(&xp);
    fl_beacon_params_default(&bp);
    fl_vision_params_default(&vp);

    printf("fingerprint 0x%08lx 0x%08lx\n", (unsigned long)FL_CONFIG_FINGERPRINT,
           (unsigned long)fl_config_fingerprint());
    printf("version %s %s\n", FL_VERSION_STRING, fl_version());
    printf("fl_obs_max %d\n", (int)FL_OBS_MAX);
    RUN("camera", cam, fl_camera_init(&cam, model, &pose));
    RUN("color", colors, fl_color_init(&colors, &cp));
    RUN("scan", scan, fl_scan_init(&scan, &sp));
    RUN("lines", lines, fl_lines_init(&lines, &lp));
    RUN("crossings", crossings, fl_crossings_init(&crossings, &xp));
    RUN("beacon", beacon, fl_beacon_init(&beacon, &bp));
    RUN("vision", vision, fl_vision_init(&vision, &vp));
    RUN("fuzzy", fuzzy, fl_fuzzy_init(&fuzzy, field, NULL));

    /* the localizer interface: the state is the library's size */
    state = malloc(loc->state_size);
    if (!state)
        return 2;
    memset(state, PATTERN, loc->state_size);
    st = fl_loc_init(loc, state, field, NULL);
    printf("loc_init %d %d\n", (int)st, loc->params_of(state) == NULL);
    memset(state, PATTERN, loc->state_size);
    st = loc->init(state, field, NULL, FL_CONFIG_FINGERPRINT);
    printf("loc_table_init %d %d\n", (int)st, loc->params_of(state) == NULL);
    printf("status_str %s\n", fl_status_str(st));
    free(state);
    return 0;
}

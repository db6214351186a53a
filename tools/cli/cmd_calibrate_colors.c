/*
 * tools/cli/cmd_calibrate_colors.c - `fieldloc calibrate-colors IMAGE...
 * [--field F] [--camera C --head PITCH_RAD YAW_RAD] --out FILE`: the
 * colour classes of a team's own carpet and light.
 *
 * Each image goes through the firmware's start-up estimate
 * (fl_color_estimate: the carpet's hue mode and spread, S and V
 * percentiles below the horizon, or in the lower half without --camera);
 * one line per image says what it found.  The images are combined
 * robustly: the median carpet hue; images more than 8 hue units from it
 * are left out (a frame full of something else); of the rest the median
 * of every number (hue spread, S and V percentiles): one odd frame (a
 * robot's feet, a ball filling the view) moves nothing.  fl_color_auto_params turns that into the
 * boxes (yellow kept clear of the carpet on a yellow-goal --field, none on
 * a white-goal one; default field spl2020), and the result is written as a
 * commented `fieldloc-colors 1` file with field_auto 1: `--colors FILE`
 * and fl_color_params_parse load it, and the boxes follow the carpet per
 * frame from there.  The team may edit the boxes.
 * Exit status: 0 written; 1 no image gave a carpet or FILE cannot be
 * written; 2 bad usage (unknown field or camera, an image of another size
 * than the camera, an unreadable image).
 */
#include "cli/args.h"
#include "cli/registry.h"
#include "eval/detect.h"
#include "world/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CC_MAX_IMAGES 256

static int cc_usage(void)
{
    fprintf(stderr,
            "usage: fieldloc calibrate-colors IMAGE... [--field NAME]\n"
            "                 [--camera NAME --head PITCH_RAD YAW_RAD] --out FILE\n"
            "  the carpet of each image (below the horizon with --camera, else the lower\n"
            "  half), combined (median; outlying images left out) into a colour file with\n"
            "  field_auto 1 for `--colors FILE`; --field decides the goal colour (spl2020:\n"
            "  white goals, no yellow class; default spl2020)\n");
    return 2;
}

static int cc_cmp(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

static int cc_median(int *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cc_cmp);
    return v[n / 2];
}

/* Circular hue difference a - b, -90..89. */
static int cc_hdiff(int a, int b)
{
    int d = ((a - b) % 180 + 180) % 180;
    return d >= 90 ? d - 180 : d;
}

/* The combined estimate of the n found ones (n >= 1) into *out. */
static void cc_combine(const fl_color_estimate_t *e, int n, fl_color_estimate_t *out, int *used)
{
    int *tmp = malloc(sizeof(int) * (size_t)n * 2), i, k = 0, ref, lo, hi;
    int *s = tmp, *v = tmp + n;
    memset(out, 0, sizeof *out);
    if (!tmp)
        return;
    for (i = 0; i < n; i++)
        s[i] = cc_hdiff(e[i].hue, e[0].hue);
    ref = (e[0].hue + cc_median(s, n) + 180) % 180;
    for (i = 0; i < n; i++) {
        int d = cc_hdiff(e[i].hue, ref);
        if (d > 8 || d < -8)
            continue;
        s[k] = cc_hdiff(e[i].hue_lo, ref);
        v[k] = cc_hdiff(e[i].hue_hi, ref);
        out->n += e[i].n;
        out->n_sat += e[i].n_sat;
        k++;
    }
    lo = cc_median(s, k);
    hi = cc_median(v, k);
    out->hue = (uint8_t)ref;
    out->hue_lo = (uint8_t)((ref + lo + 180) % 180);
    out->hue_hi = (uint8_t)((ref + hi + 180) % 180);
#define CC_MED(field)                                                                          \
    do {                                                                                       \
        int m = 0;                                                                             \
        for (i = 0; i < n; i++)                                                                \
            if (cc_hdiff(e[i].hue, ref) <= 8 && cc_hdiff(e[i].hue, ref) >= -8)                 \
                v[m++] = e[i].field;                                                           \
        out->field = (uint8_t)cc_median(v, m);                                                 \
    } while (0)
    CC_MED(s_p5);
    CC_MED(v_p2);
    CC_MED(s_med);
    CC_MED(v_med);
    CC_MED(v_p98);
#undef CC_MED
    *used = k;
    free(tmp);
}

/* One image: read, check its size against the camera, estimate; prints
 * its line.  0 found, 1 no carpet, 2 usage error. */
static int cc_image(const char *path, const fl_camera_model_t *m, double pitch, double yaw,
                    fl_color_estimate_t *e)
{
    render_frame_t fr;
    fl_camera_t cam;
    char err[256];
    fl_status_t st;
    if (render_read_frame(path, &fr, err, sizeof err) != 0) {
        fprintf(stderr, "fieldloc calibrate-colors: %s: %s\n", path, err);
        return 2;
    }
    if (m && (fr.width != m->width_px || fr.height != m->height_px)) {
        fprintf(stderr, "fieldloc calibrate-colors: %s: %dx%d does not match camera %s (%dx%d)\n",
                path, fr.width, fr.height, m->name, (int)m->width_px, (int)m->height_px);
        render_frame_free(&fr);
        return 2;
    }
    if (m && det_camera(&cam, m, pitch, yaw) != FL_OK) {
        fprintf(stderr, "fieldloc calibrate-colors: invalid head pose\n");
        render_frame_free(&fr);
        return 2;
    }
    st = fl_color_estimate(&fr.view, m ? &cam : NULL, e);
    render_frame_free(&fr);
    if (st != FL_OK) {
        printf("%s: no carpet (%d saturated samples)\n", path, (int)e->n_sat);
        return 1;
    }
    printf("%s: carpet hue %d (%d..%d) S p5 %d median %d V p2 %d median %d p98 %d, %d samples\n",
           path, e->hue, e->hue_lo, e->hue_hi, e->s_p5, e->s_med, e->v_p2, e->v_med, e->v_p98,
           (int)e->n);
    return 0;
}

/* Combine, derive the boxes, write the file.  Exit status. */
static int cc_write(const fl_color_estimate_t *e, int n, const fl_field_t *field, const char *out)
{
    static fl_color_estimate_t all;
    fl_color_params_t p;
    char text[FL_COLOR_TEXT_MAX];
    size_t len;
    int used = 0, k;
    FILE *f;
    cc_combine(e, n, &all, &used);
    fl_color_params_default(&p);
    p.auto_yellow = 0;
    for (k = 0; k < 2; k++)
        if (field->goal_color[k] == FL_COLOR_YELLOW)
            p.auto_yellow = 1;
    if (used == 0 || fl_color_auto_params(&all, &p) != FL_OK) {
        fprintf(stderr, "fieldloc calibrate-colors: no usable carpet estimate\n");
        return 1;
    }
    printf("combined %d of %d images: carpet hue %d (%d..%d) S median %d V p2 %d median %d\n",
           used, n, all.hue, all.hue_lo, all.hue_hi, all.s_med, all.v_p2, all.v_med);
    printf("green %d..%d S %d..%d V %d..%d, white S %d..%d V %d..%d, yellow %s\n", p.green.h_lo,
           p.green.h_hi, p.green.s_lo, p.green.s_hi, p.green.v_lo, p.green.v_hi, p.white.s_lo,
           p.white.s_hi, p.white.v_lo, p.white.v_hi, p.auto_yellow ? "kept clear" : "none");
    len = det_colors_text(&p, text, sizeof text);
    f = fopen(out, "w");
    if (len == 0 || !f || fwrite(text, 1, len, f) != len || fclose(f) != 0) {
        fprintf(stderr, "fieldloc calibrate-colors: %s: cannot write\n", out);
        return 1;
    }
    printf("wrote %s\n", out);
    return 0;
}

int cmd_calibrate_colors(int argc, char **argv)
{
    const char *out = NULL, *field_name = "spl2020", *cam_name = NULL, *img[CC_MAX_IMAGES];
    const char *head_text[2] = {"0", "0"};
    const fl_field_t *field;
    const fl_camera_model_t *m = NULL;
    fl_color_estimate_t *e;
    double pitch = 0, yaw = 0;
    int i, n_img = 0, n = 0, rc = 0;
    for (i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--field") && i + 1 < argc)
            field_name = argv[++i];
        else if (!strcmp(argv[i], "--camera") && i + 1 < argc)
            cam_name = argv[++i];
        else if (!strcmp(argv[i], "--head") && i + 2 < argc) {
            head_text[0] = argv[++i];
            head_text[1] = argv[++i];
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            cc_usage();
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0')
            return arg_unknown("calibrate-colors", argv[i], "--out=1 --field=1 --camera=1 --head=2");
        else if (n_img < CC_MAX_IMAGES)
            img[n_img++] = argv[i];
        else {
            fprintf(stderr, "fieldloc calibrate-colors: at most %d images\n", CC_MAX_IMAGES);
            return 2;
        }
    }
    if (n_img == 0 || out == NULL)
        return cc_usage();
    field = fl_field_find(field_name);
    if (!field) {
        fprintf(stderr, "fieldloc calibrate-colors: unknown field %s (see: fieldloc fields)\n",
                field_name);
        return 2;
    }
    if (cam_name) {
        m = fl_camera_model_find(cam_name);
        if (!m) {
            fprintf(stderr, "fieldloc calibrate-colors: unknown camera %s (see: fieldloc cameras)\n",
                    cam_name);
            return 2;
        }
        if (arg_head("calibrate-colors", "--head", m, head_text[0], head_text[1], &pitch, &yaw))
            return 2;
    }
    e = malloc(sizeof *e * (size_t)n_img);
    if (!e)
        return 1;
    for (i = 0; i < n_img && rc == 0; i++) {
        int r = cc_image(img[i], m, pitch, yaw, &e[n]);
        if (r == 0)
            n++;
        else if (r == 2)
            rc = 2;
    }
    if (rc == 0 && n == 0) {
        fprintf(stderr, "fieldloc calibrate-colors: no carpet found in any image\n");
        rc = 1;
    }
    if (rc == 0)
        rc = cc_write(e, n, field, out);
    free(e);
    return rc;
}

/*
 * host_tests/test_picture.c - suite `picture`: the belief picture of a
 * localizer whose belief is a set of samples (tools/eval/picture.h), with a
 * fake localizer that has nothing but fixed samples (so the picture is
 * tested without any real particle filter), and its legend set.
 */
#include "eval/picture.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    uint16_t n;
    fl_loc_sample_t s[8];
} fake_state_t;

static uint16_t fake_samples(const void *state)
{
    return ((const fake_state_t *)state)->n;
}

static bool fake_sample(const void *state, uint16_t i, fl_loc_sample_t *out)
{
    const fake_state_t *st = state;
    if (i >= st->n)
        return false;
    *out = st->s[i];
    return true;
}

/* Only what a picture may call: no grid, samples. */
static const fl_localizer_t fake_loc = {
    "fake", "fixed samples", sizeof(fake_state_t), 0, NULL, 0,
    NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
    NULL, NULL, NULL, NULL, NULL, NULL,
    NULL, NULL, NULL, NULL, NULL, fake_samples, fake_sample, NULL, NULL, false};

static fl_loc_sample_t mk(int32_t x, int32_t y, int32_t mdeg, uint16_t w, bool in_mode)
{
    fl_loc_sample_t s;
    s.x_mm = x;
    s.y_mm = y;
    s.heading = fl_angle_from_mdeg(mdeg);
    s.weight_q16 = w;
    s.in_mode = in_mode;
    return s;
}

/* Pixel of field point (x, y) on an SPL 2013 picture at 8 px per 100 mm
 * (the fuzzy grid's 104 x 74 cells: corner at (-5200, -3700)). */
static const uint8_t *at(const host_image_t *im, double x, double y)
{
    int u = (int)lround((x + 5200) * 0.08 - 0.5), v = (int)lround(im->height - (y + 3700) * 0.08 - 0.5);
    if (u < 0 || v < 0 || u >= im->width || v >= im->height)
        return NULL;
    return im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u);
}

static int is(const uint8_t *p, int r, int g, int b)
{
    return p != NULL && p[0] == r && p[1] == g && p[2] == b;
}

static void t_samples(void)
{
    static fake_state_t st;
    const fl_field_t *f = fl_field_find("spl2013");
    fl_loc_estimate_t est;
    pic_pose_t truth = {-3500, 2000, 90};
    host_image_t img;
    uint8_t heavy[3], light[3], other[3];
    const uint8_t *p;
    int w = 0, h = 0, u, v, lime = 0, lime_far = 0;
    memset(&st, 0, sizeof st);
    st.n = 4;
    st.s[0] = mk(1000, -500, 30000, 65535, true);     /* the heaviest, in the cluster */
    st.s[1] = mk(1000, -900, 0, 8000, true);          /* light, in the cluster */
    st.s[2] = mk(-2000, 1500, 180000, 65535, false);  /* heavy, elsewhere, heading -x */
    st.s[3] = mk(3000, 2500, 90000, 0, false);        /* negligible */
    memset(&est, 0, sizeof est);
    est.x_mm = 1000;
    est.y_mm = -600;
    est.heading = fl_angle_from_mdeg(25000);
    est.state = FL_LOC_TRACKING;
    est.sd_x_mm = 300;
    est.sd_y_mm = 200;
    est.reliability_q16 = 40000;
    /* the size is the fuzzy grid's on that field; the no-field call refuses */
    CHECK_EQ(pic_belief_size_on(&fake_loc, &st, f, 8, &w, &h), 0);
    CHECK_EQ(w, 104 * 8);
    CHECK_EQ(h, 74 * 8);
    CHECK_EQ(pic_belief_size(&fake_loc, &st, 8, &w, &h), -1);
    CHECK_EQ(pic_belief_legend(&fake_loc, &st), PIC_LEGEND_PARTICLES);
    CHECK_EQ(pic_belief_legend(&fl_localizer_fuzzy, &st), PIC_LEGEND_BELIEF);
    CHECK_EQ(pic_belief(&fake_loc, &st, f, 8, &truth, &est, NULL, &img), 0);
    if (img.rgb == NULL)
        return;
    CHECK_EQ(img.width, 104 * 8);
    CHECK_EQ(img.height, 74 * 8);
    pic_particle_color(1.0, 1, heavy);
    pic_particle_color(8000 / 65535.0, 1, light);
    pic_particle_color(1.0, 0, other);
    /* the colors: cluster warm (red > blue), others blue, heavy brighter */
    CHECK(heavy[0] > heavy[2] && light[0] > light[2] && other[2] > other[0]);
    CHECK(heavy[0] + heavy[1] + heavy[2] > light[0] + light[1] + light[2]);
    /* every sample's dot at its place (the estimate's ring and the ellipse
     * pass elsewhere) */
    p = at(&img, 1000, -500);
    CHECK(is(p, heavy[0], heavy[1], heavy[2]));
    p = at(&img, 1000, -900);
    CHECK(is(p, light[0], light[1], light[2]));
    p = at(&img, -2000, 1500);
    CHECK(is(p, other[0], other[1], other[2]));
    /* its heading tick points to -x: 50 mm left of it, not 50 mm right */
    CHECK(is(at(&img, -2050, 1500), other[0], other[1], other[2]));
    CHECK(is(at(&img, -1950 + 12, 1500), 18, 62, 28));
    /* the negligible one is drawn too, darkest blue */
    {
        uint8_t c0[3];
        pic_particle_color(0, 0, c0);
        CHECK(is(at(&img, 3000, 2500), c0[0], c0[1], c0[2]));
    }
    /* away from everything: carpet */
    CHECK(is(at(&img, -4000, -2500), 18, 62, 28));
    /* the cluster's 2-sd ellipse: lime pixels, all about 2 sd from the
     * estimate (600 x 400 mm half-axes, axis aligned) */
    for (v = 0; v < img.height; v++)
        for (u = 0; u < img.width; u++) {
            const uint8_t *q = img.rgb + 3 * ((size_t)v * (size_t)img.width + (size_t)u);
            double x = (u + 0.5) / 0.08 - 5200, y = (img.height - v - 0.5) / 0.08 - 3700, e;
            if (!is(q, 150, 255, 60))
                continue;
            lime++;
            e = hypot((x - 1000) / 600.0, (y + 600) / 400.0);
            lime_far += e < 0.85 || e > 1.15;
        }
    CHECK(lime > 100);
    CHECK_EQ(lime_far, 0);
    /* truth (cyan) and estimate (magenta) marked */
    CHECK(is(at(&img, -3500, 2000 + 200), 0, 230, 255) || is(at(&img, -3500, 2000 + 212), 0, 230, 255));
    host_image_free(&img);
    /* magnified: 4 x around the estimate, the samples there at 32 px per
     * 100 mm, a grey frame; a grid localizer has no such view */
    CHECK_EQ(pic_belief_zoom(&fake_loc, &st, f, 1000, -600, 0, 200, &truth, &est, NULL, &img), 0);
    if (img.rgb != NULL) {
        CHECK_EQ(img.width, 200);
        CHECK_EQ(img.height, 200);
        /* (1000, -500): 100 mm above the centre = 32 px; (1000, -900): 96 px below */
        CHECK(is(img.rgb + 3 * ((size_t)(100 - 32) * 200 + 100), heavy[0], heavy[1], heavy[2]) ||
              is(img.rgb + 3 * ((size_t)(99 - 32) * 200 + 99), heavy[0], heavy[1], heavy[2]));
        CHECK(is(img.rgb + 3 * ((size_t)(100 + 96) * 200 + 100), light[0], light[1], light[2]) ||
              is(img.rgb + 3 * ((size_t)(99 + 96) * 200 + 99), light[0], light[1], light[2]));
        CHECK(is(img.rgb + 3 * 199, 150, 150, 150));
        host_image_free(&img);
    }
    CHECK_EQ(pic_belief_zoom(&fl_localizer_fuzzy, &st, f, 0, 0, 0, 200, NULL, NULL, NULL, &img),
             -1);
    /* no ellipse without a tracked mode */
    est.state = FL_LOC_LOST;
    CHECK_EQ(pic_belief(&fake_loc, &st, f, 8, NULL, &est, NULL, &img), 0);
    lime = 0;
    for (u = 0; img.rgb != NULL && u < img.width * img.height; u++)
        lime += is(img.rgb + 3 * (size_t)u, 150, 255, 60);
    CHECK_EQ(lime, 0);
    host_image_free(&img);
    /* no samples, or no field: refused */
    st.n = 0;
    CHECK_EQ(pic_belief(&fake_loc, &st, f, 8, NULL, &est, NULL, &img), -1);
    CHECK(img.rgb == NULL);
    CHECK_EQ(pic_belief_legend(&fake_loc, &st), PIC_LEGEND_BELIEF);
    st.n = 4;
    CHECK_EQ(pic_belief(&fake_loc, &st, NULL, 8, NULL, &est, NULL, &img), -1);
}

/* The legend of a particle picture shows its marks in their colors. */
static void t_legend_particles(void)
{
    host_image_t img = host_image_new(400, 30, 0, 0, 0);
    uint8_t heavy[3];
    int hp = pic_legend_height(400, PIC_LEGEND_PARTICLES, NULL), found = 0, lime = 0;
    size_t i, n;
    CHECK(hp > pic_legend_height(400, PIC_LEGEND_TRUTH, NULL));
    /* beside a grid's legend, the shared items (lines, estimate,
     * observations, posts) are shown once: the estimate's ring as often as
     * in the grid's legend alone */
    {
        host_image_t a = host_image_new(400, 1, 0, 0, 0), b = host_image_new(400, 1, 0, 0, 0);
        int na = 0, nb = 0;
        CHECK_EQ(pic_legend_inplace(&a, PIC_LEGEND_BELIEF, NULL), 0);
        CHECK_EQ(pic_legend_inplace(&b, PIC_LEGEND_BELIEF | PIC_LEGEND_PARTICLES, NULL), 0);
        for (i = 0; a.rgb != NULL && i < (size_t)a.width * (size_t)a.height; i++)
            na += is(a.rgb + 3 * i, 255, 40, 255);
        for (i = 0; b.rgb != NULL && i < (size_t)b.width * (size_t)b.height; i++)
            nb += is(b.rgb + 3 * i, 255, 40, 255);
        CHECK(na > 0);
        CHECK_EQ(nb, na);
        CHECK(b.height > a.height);
        host_image_free(&a);
        host_image_free(&b);
    }
    CHECK_EQ(pic_legend_inplace(&img, PIC_LEGEND_PARTICLES | PIC_LEGEND_TRUTH, NULL), 0);
    if (img.rgb == NULL)
        return;
    pic_particle_color(1.0, 1, heavy);
    n = (size_t)img.width * (size_t)img.height;
    for (i = 30 * 400; i < n; i++) {
        found += is(img.rgb + 3 * i, heavy[0], heavy[1], heavy[2]);
        lime += is(img.rgb + 3 * i, 150, 255, 60);
    }
    CHECK(found > 0);
    CHECK(lime > 0);
    host_image_free(&img);
}

void suite_picture(void)
{
    t_run("picture.samples", t_samples);
    t_run("picture.legend_particles", t_legend_particles);
}

/*
 * host_tests/test_localizer.c - the localizer interface (localizer.h):
 * catalogue lookup, parameters by name, and the fuzzy grid through the
 * interface giving exactly what the direct fl_fuzzy_* calls give.
 */
#include "test.h"
#include "fieldloc/fuzzy.h"
#include "fieldloc/localizer.h"

#include <stdlib.h>
#include <string.h>

static void test_catalogue(void)
{
    const fl_localizer_t *loc = fl_localizer_find("fuzzy");
    uint16_t i;
    CHECK(loc != NULL);
    CHECK(loc == &fl_localizer_fuzzy);
    CHECK(fl_localizer_find(NULL) == NULL);
    CHECK(fl_localizer_find("") == NULL);
    CHECK(fl_localizer_find("fuzz") == NULL);
    CHECK(fl_localizer_find("fuzzyx") == NULL);
    CHECK(fl_localizer_find("mcl") == &fl_localizer_mcl);
    CHECK(fl_localizer_find("mc") == NULL);
    CHECK(fl_localizer_count() >= 1);
    CHECK(fl_localizer_get(fl_localizer_count()) == NULL);
    for (i = 0; i < fl_localizer_count(); i++) {
        const fl_localizer_t *l = fl_localizer_get(i);
        CHECK(l != NULL && l->name != NULL && l->summary != NULL);
        CHECK(fl_localizer_find(l->name) == l);
        CHECK(l->state_size > 0 && l->params_size > 0);
        CHECK(l->init && l->predict && l->update && l->estimate && l->check &&
              l->params_default && l->params_preset && l->params_adapt && l->params_check &&
              l->params_of && l->reset_ignorance && l->reset_pose && l->reset_penalty &&
              l->set_prior_half && l->set_prior_pose && l->clear_prior &&
              l->possibility_q16 && l->stats && l->belief_grid && l->belief_cell &&
              l->belief_samples && l->belief_sample);
    }
    if (loc == NULL)
        return;
    CHECK_EQ(loc->state_size, sizeof(fl_fuzzy_t));
    CHECK_EQ(loc->params_size, sizeof(fl_fuzzy_params_t));
    CHECK_EQ(fl_loc_preset_for_width(320), FL_LOC_PRESET_VISION);
    CHECK_EQ(fl_loc_preset_for_width(640), FL_LOC_PRESET_VISION);
    CHECK_EQ(fl_loc_preset_for_width(0), FL_LOC_PRESET_VISION);
    CHECK_EQ(fl_loc_preset_for_width(208), FL_LOC_PRESET_VISION_LOWRES);
    /* NULL everywhere: no crash */
    CHECK_EQ(fl_loc_init(NULL, NULL, NULL, NULL), FL_ERR_NULL);
    CHECK_EQ(fl_loc_init(loc, NULL, NULL, NULL), FL_ERR_NULL);
    fl_loc_predict(NULL, NULL, 0, 0, 0);
    CHECK_EQ(fl_loc_update(loc, NULL, NULL, NULL), 0);
    CHECK(!fl_loc_estimate(NULL, NULL, NULL));
    CHECK(!fl_loc_check(loc, NULL));
}

/* Every parameter of the table equal (struct padding is not compared). */
static int same_params(const void *a, const void *b)
{
    const fl_localizer_t *loc = &fl_localizer_fuzzy;
    uint16_t i;
    for (i = 0; i < loc->n_param; i++) {
        int32_t x = 0, y = 1;
        if (fl_localizer_param_get(loc, a, loc->param[i].name, &x) != FL_OK ||
            fl_localizer_param_get(loc, b, loc->param[i].name, &y) != FL_OK || x != y)
            return 0;
    }
    return 1;
}

static void test_params_by_name(void)
{
    const fl_localizer_t *loc = &fl_localizer_fuzzy;
    fl_fuzzy_params_t p, d, v;
    int32_t x = 0;
    uint16_t i;
    loc->params_default(&p);
    fl_fuzzy_params_default(&d);
    CHECK(same_params(&p, &d));
    CHECK_EQ(loc->params_check(&p), FL_OK);
    /* every descriptor reads back the field's value */
    CHECK_EQ(fl_localizer_param_get(loc, &p, "odo_max_mm", &x), FL_OK);
    CHECK_EQ(x, d.odo_max_mm);
    CHECK_EQ(fl_localizer_param_get(loc, &p, "bearing_core", &x), FL_OK);
    CHECK_EQ(x, d.bearing_core);
    CHECK_EQ(fl_localizer_param_get(loc, &p, "ring_track_q8", &x), FL_OK);
    CHECK_EQ(x, d.ring_track_q8);
    for (i = 0; i < loc->n_param; i++) {
        CHECK(fl_localizer_param_find(loc, loc->param[i].name) == &loc->param[i]);
        CHECK_LE((size_t)loc->param[i].offset + loc->param[i].size, loc->params_size);
        /* set the value it has: nothing changes */
        CHECK_EQ(fl_localizer_param_get(loc, &p, loc->param[i].name, &x), FL_OK);
        CHECK_EQ(fl_localizer_param_set(loc, &p, loc->param[i].name, x), FL_OK);
    }
    CHECK(same_params(&p, &d));
    CHECK_EQ(fl_localizer_param_set(loc, &p, "odo_max_mm", 1500), FL_OK);
    CHECK_EQ(p.odo_max_mm, 1500);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "bearing_core", -5), FL_OK);
    CHECK_EQ(p.bearing_core, -5);
    CHECK_EQ(fl_localizer_param_get(loc, &p, "bearing_core", &x), FL_OK);
    CHECK_EQ(x, -5);
    CHECK_EQ(loc->params_check(&p), FL_ERR_RANGE);   /* in the type, not in use */
    CHECK_EQ(fl_localizer_param_set(loc, &p, "gate_q8", 256), FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "gate_q8", -1), FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "ring_core_q8", 65536), FL_ERR_RANGE);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "bearing_core", 40000), FL_ERR_RANGE);
    CHECK_EQ(p.gate_q8, d.gate_q8);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "no_such_param", 1), FL_ERR_NOT_FOUND);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "odo_max", 1), FL_ERR_NOT_FOUND);
    CHECK_EQ(fl_localizer_param_set(loc, &p, "odo_max_mmx", 1), FL_ERR_NOT_FOUND);
    CHECK_EQ(fl_localizer_param_get(loc, &p, "no_such_param", &x), FL_ERR_NOT_FOUND);
    CHECK_EQ(fl_localizer_param_set(NULL, &p, "gate_q8", 1), FL_ERR_NULL);
    CHECK_EQ(fl_localizer_param_set(loc, NULL, "gate_q8", 1), FL_ERR_NULL);
    CHECK_EQ(fl_localizer_param_set(loc, &p, NULL, 1), FL_ERR_NULL);
    CHECK_EQ(fl_localizer_param_get(loc, &p, "gate_q8", NULL), FL_ERR_NULL);
    CHECK(fl_localizer_param_find(loc, NULL) == NULL);
    /* presets = the fuzzy.h vision presets */
    loc->params_preset(&p, FL_LOC_PRESET_VISION);
    fl_fuzzy_params_vision(&v, false);
    CHECK(same_params(&p, &v));
    CHECK_EQ(fl_loc_preset_for_width(208), FL_LOC_PRESET_VISION_LOWRES);
    CHECK_EQ(fl_loc_preset_for_width(320), FL_LOC_PRESET_VISION);
    CHECK_EQ(fl_loc_preset_for_width(0), FL_LOC_PRESET_VISION);
    loc->params_preset(&p, FL_LOC_PRESET_VISION_LOWRES);
    fl_fuzzy_params_vision(&v, true);
    CHECK(same_params(&p, &v));
    loc->params_preset(&p, FL_LOC_PRESET_VISION);
    loc->params_adapt(&p, FL_LOC_PRESET_VISION_LOWRES);
    CHECK(same_params(&p, &v));
    loc->params_preset(&p, FL_LOC_PRESET_DEFAULT);
    CHECK(same_params(&p, &d));
}

static void make_obs(fl_obs_list_t *l, int k)
{
    fl_obs_t o;
    fl_obs_list_clear(l);
    memset(&o, 0, sizeof o);
    o.kind = FL_LM_L;
    o.range_mm = 1500 + 37 * k;
    o.bearing = (fl_angle_t)(4000 - 300 * k);
    o.orientation = (fl_angle_t)(-8000 + 100 * k);
    o.has_orientation = true;
    o.confidence = 220;
    o.u_q4 = o.v_q4 = -1;
    fl_obs_list_push(l, &o);
    o.kind = FL_LM_CENTRE_CIRCLE;
    o.range_mm = 2100 - 20 * k;
    o.bearing = (fl_angle_t)(-3000 + 150 * k);
    o.orientation = 16384;
    fl_obs_list_push(l, &o);
    o.kind = FL_LM_POST;
    o.has_orientation = false;
    o.orientation = 0;
    o.range_mm = 4200;
    o.bearing = (fl_angle_t)(9000 + 50 * k);
    fl_obs_list_push(l, &o);
}

/* The same belief: cells (8 bytes, no padding), counters and track (not
 * the whole struct: padding and the dead scratch may differ). */
static int same_state(const fl_fuzzy_t *a, const fl_fuzzy_t *b)
{
    return a->nx == b->nx && a->ny == b->ny && a->x0_mm == b->x0_mm && a->y0_mm == b->y0_mm &&
           memcmp(a->cell, b->cell, sizeof(fl_fuzzy_cell_t) * a->nx * a->ny) == 0 &&
           memcmp(&a->stats, &b->stats, sizeof a->stats) == 0 &&
           a->track_valid == b->track_valid && a->track_x_mm == b->track_x_mm &&
           a->track_y_mm == b->track_y_mm && a->track_heading == b->track_heading &&
           a->consistency_q16 == b->consistency_q16 && a->prior.kind == b->prior.kind &&
           a->prior.half == b->prior.half && a->prior.x_mm == b->prior.x_mm &&
           a->prior.radius_mm == b->prior.radius_mm;
}

static void test_same_as_direct(void)
{
    const fl_localizer_t *loc = fl_localizer_find("fuzzy");
    const fl_field_t *field = fl_field_find("spl2013");
    fl_fuzzy_t *g = malloc(sizeof *g);
    void *st = loc ? malloc(loc->state_size) : NULL;
    void *pp = loc ? malloc(loc->params_size) : NULL;
    fl_fuzzy_params_t fp;
    fl_fuzzy_estimate_t e;
    fl_loc_estimate_t le;
    fl_loc_stats_t ls;
    fl_obs_list_t obs;
    fl_obs_view_t view = {true, (fl_angle_t)-5000, (fl_angle_t)5000, 300, 3500};
    int k;
    CHECK(g && st && pp && field);
    if (!g || !st || !pp || !field) {
        free(g), free(st), free(pp);
        return;
    }
    fl_fuzzy_params_vision(&fp, false);
    loc->params_preset(pp, FL_LOC_PRESET_VISION);
    CHECK_EQ(fl_fuzzy_init(g, field, &fp), FL_OK);
    CHECK_EQ(fl_loc_init(loc, st, field, pp), FL_OK);
    CHECK(loc->params_of(st) != NULL);
    CHECK(same_params(loc->params_of(st), &fp));
    fl_fuzzy_set_prior_half(g, -1);
    loc->set_prior_half(st, -1);
    for (k = 0; k < 12; k++) {
        make_obs(&obs, k);
        fl_fuzzy_predict(g, 60, 5, 300);
        fl_loc_predict(loc, st, 60, 5, 300);
        CHECK_EQ(fl_loc_update(loc, st, &obs, k & 1 ? &view : NULL),
                 fl_fuzzy_update_view(g, &obs, k & 1 ? &view : NULL));
        CHECK(fl_fuzzy_estimate(g, &e));
        CHECK(fl_loc_estimate(loc, st, &le));
        CHECK_EQ(le.x_mm, e.x_mm);
        CHECK_EQ(le.y_mm, e.y_mm);
        CHECK_EQ(le.heading, e.heading);
        /* the interface's reliability is the calibrated one; the grid's
         * own measure is its score */
        CHECK_EQ(le.reliability_q16, e.calibrated_q16);
        CHECK_EQ(le.score_q16, e.reliability_q16);
        CHECK_EQ(le.sd_x_mm, e.sd_x_mm);
        CHECK_EQ(le.sd_y_mm, e.sd_y_mm);
        CHECK_EQ(le.cov_xy_mm2, e.cov_xy_mm2);
        CHECK_EQ(le.sd_heading, e.sd_heading);
        CHECK_EQ(le.mirror_q16, e.mirror_q16);
        CHECK_EQ(le.since_obs, e.since_obs);
        CHECK_EQ(le.state == FL_LOC_LOST, !e.tracking || e.ignorance);
        CHECK_EQ(le.peak_q8, e.peak_q8);
        CHECK_EQ(le.mode_cells, e.mode_cells);
        CHECK_EQ(le.switched, e.switched);
        CHECK_EQ(loc->possibility_q16(st, e.x_mm, e.y_mm, e.heading),
                 fl_fuzzy_possibility_q16(g, e.x_mm, e.y_mm, e.heading));
    }
    CHECK(same_state(st, g));   /* the very same belief */
    loc->stats(st, &ls);
    CHECK_EQ(ls.predicts, g->stats.predicts);
    CHECK_EQ(ls.obs_used, g->stats.obs_used);
    CHECK(fl_loc_check(loc, st));
    {
        /* the belief cell by cell = the grid's cells */
        fl_loc_grid_t gr;
        fl_loc_cell_t c;
        int ix, iy, bad = 0;
        CHECK(loc->belief_grid(st, &gr));
        CHECK_EQ(gr.nx, g->nx);
        CHECK_EQ(gr.ny, g->ny);
        CHECK_EQ(gr.x0_mm, g->x0_mm);
        CHECK_EQ(gr.cell_mm, FL_FUZZY_CELL_MM);
        for (iy = 0; iy < gr.ny; iy++)
            for (ix = 0; ix < gr.nx; ix++) {
                const fl_fuzzy_cell_t *fc = &g->cell[iy * g->nx + ix];
                if (!loc->belief_cell(st, ix, iy, &c) || c.height_q8 != fc->height ||
                    c.heading != fc->centre || c.spread < 0 || c.spread > 32768)
                    bad++;
            }
        CHECK_EQ(bad, 0);
        CHECK(!loc->belief_cell(st, -1, 0, &c));
        CHECK(!loc->belief_cell(st, gr.nx, 0, &c));
        CHECK(!loc->belief_cell(st, 0, gr.ny, &c));
        CHECK(!loc->belief_grid(NULL, &gr));
    }
    {
        /* a grid has no samples */
        fl_loc_sample_t sm;
        CHECK_EQ(loc->belief_samples(st), 0);
        CHECK(!loc->belief_sample(st, 0, &sm));
    }
    /* resets and priors through the interface */
    loc->reset_pose(st, 1000, -500, 8192, 300, 2048);
    fl_fuzzy_reset_pose(g, 1000, -500, 8192, 300, 2048);
    loc->set_prior_pose(st, 1000, -500, 8192, 800);
    fl_fuzzy_set_prior_pose(g, 1000, -500, 8192, 800);
    loc->reset_penalty(st, -1500, 200, 1024);
    fl_fuzzy_reset_penalty(g, -1500, 200, 1024);
    loc->clear_prior(st);
    fl_fuzzy_clear_prior(g);
    loc->reset_ignorance(st);
    fl_fuzzy_reset_ignorance(g);
    CHECK(same_state(st, g));
    CHECK(fl_loc_check(loc, st));
    /* a corrupted state */
    ((fl_fuzzy_t *)st)->cell[5].bias = 255;
    ((fl_fuzzy_t *)st)->cell[5].height = 10;
    CHECK(!fl_loc_check(loc, st));
    /* bad init */
    CHECK(fl_loc_init(loc, st, NULL, NULL) != FL_OK);
    CHECK(!fl_loc_check(loc, st));
    CHECK(loc->params_of(st) == NULL);
    CHECK(!fl_loc_estimate(loc, st, &le));
    fl_fuzzy_params_default(&fp);
    fp.odo_max_mm = 0;
    CHECK_EQ(fl_loc_init(loc, st, field, &fp), FL_ERR_RANGE);
    CHECK_EQ(fl_loc_init(loc, st, field, NULL), FL_OK);
    CHECK(fl_loc_check(loc, st));
    free(g);
    free(st);
    free(pp);
}

void suite_localizer(void)
{
    t_run("localizer.catalogue", test_catalogue);
    t_run("localizer.params_by_name", test_params_by_name);
    t_run("localizer.same_as_direct", test_same_as_direct);
}

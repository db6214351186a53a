/* host_tests/test_obs.c - observation lists and landmark orientation. */
#include "test.h"
#include "fieldloc/obs.h"

static void test_list(void)
{
    static fl_obs_list_t list;
    fl_obs_t o = {FL_LM_T, FL_SIDE_UNKNOWN, FL_COLOUR_NONE, 1500, 1000, 0, false, 200, -1, -1, FL_COLOUR_NONE};
    int i;
    fl_obs_list_clear(&list);
    CHECK_EQ(list.n, 0);
    for (i = 0; i < FL_OBS_MAX; i++) {
        o.range_mm = 100 + i;
        CHECK(fl_obs_list_push(&list, &o));
    }
    CHECK_EQ(list.n, FL_OBS_MAX);
    CHECK(!fl_obs_list_push(&list, &o));
    CHECK(!fl_obs_list_push(&list, &o));
    CHECK_EQ(list.n, FL_OBS_MAX);
    CHECK_EQ(list.dropped, 2);
    CHECK_EQ(list.obs[FL_OBS_MAX - 1].range_mm, 100 + FL_OBS_MAX - 1);
    CHECK(!fl_obs_list_push(NULL, &o));
    CHECK(!fl_obs_list_push(&list, NULL));
    fl_obs_list_clear(NULL);
    fl_obs_list_clear(&list);
    CHECK_EQ(list.dropped, 0);
}

/* Orientation of every crossing of every field: L -> bisector lies strictly
 * between its arms (90 deg arms: 45 deg from each); T -> the stem has no
 * opposite arm; X and marks -> one of the arms. */
static void test_orientation(void)
{
    size_t fi;
    uint32_t h = t_hash_init();
    for (fi = 0; fi < fl_field_count(); fi++) {
        const fl_field_t *f = fl_field_at(fi);
        uint16_t i;
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            fl_angle_t o = 0;
            bool has = fl_landmark_orientation(lm, &o);
            h = t_hash_i32(h, has ? o : 99999);
            switch (lm->kind) {
            case FL_LM_L: {
                int32_t d0 = fl_angle_sub(lm->arm[0], o), d1 = fl_angle_sub(lm->arm[1], o);
                CHECK(has);
                CHECK(d0 * d1 < 0);                       /* arms on both sides */
                CHECK(d0 + d1 >= -1 && d0 + d1 <= 1);    /* symmetric about it */
                break;
            }
            case FL_LM_T: {
                int k, same = 0;
                CHECK(has);
                for (k = 0; k < 3; k++)
                    if (lm->arm[k] == o)
                        same++;
                CHECK_EQ(same, 1);
                for (k = 0; k < 3; k++) {
                    int32_t d = fl_angle_sub(lm->arm[k], o);
                    CHECK(d > -30000 && d < 30000);    /* no arm opposite the stem */
                }
                break;
            }
            case FL_LM_X: case FL_LM_PENALTY_MARK: case FL_LM_CENTRE_MARK:
                CHECK(has);
                CHECK(o == lm->arm[0]);
                break;
            case FL_LM_CENTRE_CIRCLE:
                CHECK(has);
                break;
            default:
                CHECK(!has);
            }
        }
    }
    /* the SPL corner at (+4500, +3000) opens toward -x and -y: bisector -135 deg */
    {
        const fl_field_t *f = fl_field_find("spl2013");
        uint16_t i;
        int found = 0;
        for (i = 0; i < fl_field_count_kind(f, FL_LM_L); i++) {
            const fl_landmark_t *lm = fl_field_nth_kind(f, FL_LM_L, i);
            fl_angle_t o;
            if (lm->x_mm == 4500 && lm->y_mm == 3000) {
                CHECK(fl_landmark_orientation(lm, &o));
                CHECK_EQ(o, fl_angle_from_mdeg(-135000));
                found = 1;
            }
        }
        CHECK(found);
    }
    CHECK(!fl_landmark_orientation(NULL, NULL));
    t_digest("obs.orientation", h);
}

void suite_obs(void)
{
    t_run("obs.list_capacity", test_list);
    t_run("obs.landmark_orientation", test_orientation);
}

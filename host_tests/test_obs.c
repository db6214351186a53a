/* host_tests/test_obs.c - observation lists and landmark orientation. */
#include "test.h"
#include "fieldloc/fuzzy.h"
#include "fieldloc/obs.h"
#include "fieldloc/vision.h"

#include <string.h>

static void test_list(void)
{
    static fl_obs_list_t list;
    fl_obs_t o = {FL_LM_T, FL_SIDE_UNKNOWN, FL_COLOR_NONE, 1500, 1000, 0, false, 200, -1, -1, FL_COLOR_NONE};
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

/* Line points: their own capacity and counter, cleared with the list,
 * absurd positions refused without being counted. */
static void test_points(void)
{
    static fl_obs_list_t list;
    int i;
    memset(&list, 0x5a, sizeof list);
    fl_obs_list_clear(&list);
    CHECK_EQ(list.n_points, 0);
    CHECK_EQ(list.points_dropped, 0);
    for (i = 0; i < FL_OBS_MAX_POINTS; i++)
        CHECK(fl_obs_list_push_point(&list, 100 * i, -50 * i));
    CHECK_EQ(list.n_points, FL_OBS_MAX_POINTS);
    CHECK(!fl_obs_list_push_point(&list, 1, 2));
    CHECK_EQ(list.points_dropped, 1);
#if FL_OBS_MAX_POINTS > 0
    CHECK_EQ(list.points[FL_OBS_MAX_POINTS - 1].x_mm, 100 * (FL_OBS_MAX_POINTS - 1));
    CHECK_EQ(list.points[FL_OBS_MAX_POINTS - 1].y_mm, -50 * (FL_OBS_MAX_POINTS - 1));
#endif
    CHECK_EQ(list.n, 0);
    fl_obs_list_clear(&list);
    CHECK(!fl_obs_list_push_point(&list, FL_OBS_MAX_RANGE_MM + 1, 0));
    CHECK(!fl_obs_list_push_point(&list, 0, -FL_OBS_MAX_RANGE_MM - 1));
    CHECK(!fl_obs_list_push_point(NULL, 0, 0));
    CHECK_EQ(list.points_dropped, 0);
    CHECK(fl_obs_list_push_point(&list, FL_OBS_MAX_RANGE_MM, -FL_OBS_MAX_RANGE_MM));
    CHECK_EQ(list.n_points, 1);
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

/* fl_vision_view_from_camera: the sector lies inside the shrunk image (its
 * corners and centre project at least the margin inside), follows the
 * head yaw, and is invalid for a camera that sees no ground or bad
 * arguments. */
static bool view_point_inside(const fl_camera_t *cam, int32_t r, fl_angle_t b, int32_t m_px)
{
    int32_t u, v;
    fl_point_t p = fl_point_from_polar(r, b);
    if (!fl_camera_ground_to_pixel(cam, p, &u, &v))
        return false;
    /* a pixel of slack for the sampled (slightly curved) side edges */
    return u >= (m_px - 1) * 16 && u <= (cam->model.width_px - m_px) * 16 &&
           v >= (m_px - 1) * 16 && v <= (cam->model.height_px - m_px) * 16;
}

static void test_view(void)
{
    const char *models[] = {"nao4-top-320", "aibo-ers7"};
    const double yaws[] = {0.0, 0.7, -1.2};
    size_t mi, yi;
    uint32_t h = t_hash_init();
    for (mi = 0; mi < 2; mi++) {
        const fl_camera_model_t *model = fl_camera_model_find(models[mi]);
        int32_t m_px = model->width_px / 16;
        for (yi = 0; yi < 3; yi++) {
            fl_camera_pose_t pose;
            fl_camera_t cam;
            fl_obs_view_t v;
            fl_angle_t yaw = fl_angle_from_urad((int32_t)(yaws[yi] * 1e6));
            int32_t width, k, dc;
            memset(&pose, 0, sizeof pose);
            pose.neck_height_mm = model->default_neck_height_mm;
            pose.head_pitch = fl_angle_from_urad(300000);
            pose.head_yaw = yaw;
            CHECK_EQ(fl_camera_init(&cam, model, &pose), FL_OK);
            fl_vision_view_from_camera(&cam, m_px, 4000, &v);
            CHECK(v.valid);
            width = fl_angle_sub(v.bearing_left, v.bearing_right);
            CHECK(width > fl_angle_from_mdeg(20000) && width < fl_angle_from_mdeg(65000));
            /* centred on the yaw (no roll: the image is symmetric) */
            dc = fl_angle_sub(fl_angle_add(v.bearing_right, (fl_angle_t)(width / 2)), yaw);
            CHECK_LE(dc < 0 ? -dc : dc, fl_angle_from_mdeg(500));
            CHECK(v.near_mm > 0 && v.near_mm < v.far_mm && v.far_mm <= 4000);
            /* corners, edge midpoints and centre of the sector: in the image */
            for (k = 0; k < 9; k++) {
                int32_t r = v.near_mm + (v.far_mm - v.near_mm) * (k / 3) / 2;
                fl_angle_t b = fl_angle_add(v.bearing_right, (fl_angle_t)(width * (k % 3) / 2));
                CHECK(view_point_inside(&cam, r, b, m_px));
            }
            h = t_hash_i32(h, v.bearing_right);
            h = t_hash_i32(h, v.bearing_left);
            h = t_hash_i32(h, v.near_mm);
            h = t_hash_i32(h, v.far_mm);
        }
        {
            /* looking up: no ground in the shrunk image */
            fl_camera_pose_t pose;
            fl_camera_t cam;
            fl_obs_view_t v;
            memset(&pose, 0, sizeof pose);
            pose.neck_height_mm = model->default_neck_height_mm;
            pose.head_pitch = fl_angle_from_urad(-1200000);
            CHECK_EQ(fl_camera_init(&cam, model, &pose), FL_OK);
            fl_vision_view_from_camera(&cam, m_px, 4000, &v);
            CHECK(!v.valid);
            /* bad arguments */
            pose.head_pitch = fl_angle_from_urad(300000);
            CHECK_EQ(fl_camera_init(&cam, model, &pose), FL_OK);
            fl_vision_view_from_camera(&cam, -1, 4000, &v);
            CHECK(!v.valid);
            fl_vision_view_from_camera(&cam, model->width_px, 4000, &v);
            CHECK(!v.valid);
            fl_vision_view_from_camera(&cam, m_px, 0, &v);
            CHECK(!v.valid);
            fl_vision_view_from_camera(NULL, m_px, 4000, &v);
            CHECK(!v.valid);
            fl_vision_view_from_camera(&cam, m_px, 4000, NULL);
        }
    }
    t_digest("obs.view", h);
}

/* fl_vision_view and fl_fuzzy_params_vision / _lowres: the view
 * is the 1/16-margin view up to 4 m (2.5 m under 320 px wide); the
 * parameters pass fl_fuzzy_params_check for every catalogue camera, keep
 * the precise tracking rings and all crossings for the NAO cameras, and
 * give the narrow AIBO camera wide rings and a 2.5 m crossing cut-off,
 * unless the caller chose another ring_track_q8. */
static void test_vision_defaults(void)
{
    size_t i;
    int narrow = 0, wide = 0;
    fl_fuzzy_params_t p, d;
    fl_obs_view_t v;
    for (i = 0; i < fl_camera_model_count(); i++) {
        const fl_camera_model_t *model = fl_camera_model_at(i);
        fl_camera_pose_t pose;
        fl_camera_t cam;
        fl_obs_view_t a, b;
        int32_t w = model->width_px;
        memset(&pose, 0, sizeof pose);
        pose.neck_height_mm = model->default_neck_height_mm;
        pose.pitch_offset = model->default_pitch_offset;
        pose.head_pitch = fl_angle_from_urad(300000);
        CHECK_EQ(fl_camera_init(&cam, model, &pose), FL_OK);
        fl_vision_view(&cam, &a);
        fl_vision_view_from_camera(&cam, w / 16, w >= 320 ? 4000 : 2500, &b);
        CHECK(a.valid && b.valid);
        CHECK_EQ(memcmp(&a, &b, sizeof a), 0);
        CHECK_LE(a.far_mm, w >= 320 ? 4000 : 2500);
        fl_fuzzy_params_vision(&p, w < 320);
        CHECK_EQ(fl_fuzzy_params_check(&p), FL_OK);
        CHECK(p.neg_q8 > 0 && p.confuse_q8 > 0 && p.head_bias_outlier == 1);
        if (w < 320) {
            narrow++;
            CHECK_EQ(p.ring_track_q8, 256);
            CHECK_EQ(p.cross_max_mm, 2500);
        } else {
            wide++;
            CHECK_EQ(p.ring_track_q8, FL_FUZZY_RING_TRACK_VISION);
            CHECK_EQ(p.cross_max_mm, 0);
        }
    }
    CHECK(narrow >= 1 && wide >= 1);
    /* NULL model: a NAO camera; the camera part leaves chosen values and
     * other parameter sets alone */
    fl_fuzzy_params_vision(&p, false);
    CHECK_EQ(p.ring_track_q8, FL_FUZZY_RING_TRACK_VISION);
    p.ring_track_q8 = 128;
    fl_fuzzy_params_lowres(&p);
    CHECK_EQ(p.ring_track_q8, 128);
    CHECK_EQ(p.cross_max_mm, 0);
    fl_fuzzy_params_default(&d);
    p = d;
    fl_fuzzy_params_lowres(&p);
    CHECK_EQ(memcmp(&p, &d, sizeof p), 0);
    fl_fuzzy_params_vision(NULL, true);   /* no crash */
    fl_fuzzy_params_lowres(NULL);
    fl_vision_view(NULL, &v);
    CHECK(!v.valid);
}

void suite_obs(void)
{
    t_run("obs.view_from_camera", test_view);
    t_run("obs.vision_defaults", test_vision_defaults);
    t_run("obs.list_capacity", test_list);
    t_run("obs.list_points", test_points);
    t_run("obs.landmark_orientation", test_orientation);
}

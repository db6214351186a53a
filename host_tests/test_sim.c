/*
 * host_tests/test_sim.c - suite `sim`: the walk simulator (tools/world/sim.h).
 *
 * Checks: integrating the true motion reproduces the true path; odometry
 * error statistics match the configured noise over a long walk; noiseless
 * observations re-project onto map landmarks (1 mm, 0.01 deg) and are
 * complete; nothing outside the field of view (checked with an independent
 * double pinhole model written here from camera.h's description) is seen;
 * observation noise, misses, false positives and confusion match their
 * parameters; kidnap and penalty move the pose as specified; the head sweep;
 * the scenario text round-trips; determinism (digests); the committed walk
 * fixtures equal the generator's output; the sequence writer (mode b).
 */
#include "test.h"
#include "world/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846

/* The renderer may not be linked in every build (mode b is skipped then). */
#pragma weak render_frame
#pragma weak render_read_frame
#pragma weak render_frame_free
#pragma weak render_project_field
#pragma weak render_occluded

static double ang_rad(fl_angle_t a) { return (double)a * (2 * PI / 65536.0); }

static double wrap_pi(double a)
{
    while (a >= PI)
        a -= 2 * PI;
    while (a < -PI)
        a += 2 * PI;
    return a;
}

/* A built-in walk without feature mode's white points (sim.h
 * white_points): the tests here look at the landmarks, the walk and the
 * events; sim.white_points turns them on and checks that nothing else
 * changes. */
static int load_builtin(sim_scenario_t *sc, int i)
{
    int r = sim_scenario_builtin(sc, sim_builtin_names[i]);
    CHECK_EQ(r, 0);
    sc->white_points = 0;
    return r;
}

/* ---- independent camera model (double), after camera.h ------------------ */

typedef struct {
    double R[3][3];   /* camera (x optical, y left, z up) -> robot */
    double p[3];      /* camera centre, robot frame */
    double f, cx, cy;
    int w, h;
} dcam_t;

static void dcam_init(dcam_t *c, const fl_camera_model_t *m, const fl_camera_pose_t *ps)
{
    double yaw = ang_rad(ps->head_yaw);
    double theta = ang_rad(ps->head_pitch) + ang_rad(ps->pitch_offset);
    double alpha = ang_rad(m->mount_tilt) + theta;
    double cyw = cos(yaw), syw = sin(yaw), ca = cos(alpha), sa = sin(alpha);
    /* mount offset turned down by the head pitch, then yawed */
    double hx = m->mount_x_mm * cos(theta) + m->mount_z_mm * sin(theta);
    double hz = -m->mount_x_mm * sin(theta) + m->mount_z_mm * cos(theta);
    c->R[0][0] = cyw * ca; c->R[0][1] = -syw; c->R[0][2] = cyw * sa;
    c->R[1][0] = syw * ca; c->R[1][1] = cyw;  c->R[1][2] = syw * sa;
    c->R[2][0] = -sa;      c->R[2][1] = 0;    c->R[2][2] = ca;
    c->p[0] = cyw * hx;
    c->p[1] = syw * hx;
    c->p[2] = ps->neck_height_mm + hz;
    c->f = m->focal_q4 / 16.0;
    c->cx = m->cx_q4 / 16.0;
    c->cy = m->cy_q4 / 16.0;
    c->w = m->width_px;
    c->h = m->height_px;
}

/* Robot-frame ground point -> pixel; 0 when behind the camera. */
static int dcam_project(const dcam_t *c, double gx, double gy, double *u, double *v)
{
    double d[3] = {gx - c->p[0], gy - c->p[1], -c->p[2]}, q[3];
    int i;
    for (i = 0; i < 3; i++)
        q[i] = c->R[0][i] * d[0] + c->R[1][i] * d[1] + c->R[2][i] * d[2];
    if (q[0] <= 1e-9)
        return 0;
    *u = c->cx - c->f * q[1] / q[0];
    *v = c->cy - c->f * q[2] / q[0];
    return 1;
}

static void field_to_robot(const sim_step_t *st, double fx, double fy, double *rx, double *ry)
{
    double h = ang_rad(st->heading), dx = fx - st->x_mm, dy = fy - st->y_mm;
    *rx = dx * cos(h) + dy * sin(h);
    *ry = -dx * sin(h) + dy * cos(h);
}

/* ---- consistency: integrating the true motion gives the true path ------- */

static void test_consistency(void)
{
    int i;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        sim_scenario_t sc;
        sim_t sim;
        sim_step_t st;
        double xd = 0, yd = 0, hd = 0;   /* integrated doubles */
        double xi = 0, yi = 0;           /* integrated integer deltas */
        int32_t hi = 0;                  /* integer heading, binary units */
        double err_d = 0, err_i = 0, err_h = 0;
        if (load_builtin(&sc, i) != 0)
            continue;
        CHECK_EQ(sim_init(&sim, &sc), 0);
        while (sim_step(&sim, &st)) {
            double c, s;
            if (st.index == 0 || (st.events & (SIM_EV_KIDNAP | SIM_EV_PENALIZED))) {
                /* start, or a teleport: the motion of this step happened
                 * before it; restart the integration at the new pose */
                xd = st.true_x_mm;
                yd = st.true_y_mm;
                hd = st.true_heading_rad;
                xi = st.x_mm;
                yi = st.y_mm;
                hi = st.heading;
                continue;
            }
            c = cos(hd);
            s = sin(hd);
            xd += st.true_dx * c - st.true_dy * s;
            yd += st.true_dx * s + st.true_dy * c;
            hd += st.true_dtheta_rad;
            c = cos(ang_rad(fl_angle_wrap(hi)));
            s = sin(ang_rad(fl_angle_wrap(hi)));
            xi += st.true_dx_mm * c - st.true_dy_mm * s;
            yi += st.true_dx_mm * s + st.true_dy_mm * c;
            hi = fl_angle_add(fl_angle_wrap(hi), st.true_dtheta);
            err_d = fmax(err_d, hypot(xd - st.true_x_mm, yd - st.true_y_mm));
            err_d = fmax(err_d, fabs(wrap_pi(hd - st.true_heading_rad)) * 1000);
            err_i = fmax(err_i, hypot(xi - st.x_mm, yi - st.y_mm));
            err_h = fmax(err_h, abs(fl_angle_sub(fl_angle_wrap(hi), st.heading)));
        }
        t_info("sim.consistency %s: double path error %.2g mm (heading %.2g mrad), "
               "integer path error %.2f mm, heading %g units",
               sim_builtin_names[i], err_d, err_d, err_i, err_h);
        CHECK_LE(err_d, 1e-6);
        /* integer deltas: rounding to 1 mm per step with error diffusion;
         * the remainders are carried in turning frames, and the rounded
         * true pose itself is off by up to 0.7 mm */
        CHECK_LE(err_i, 3.0);
        CHECK_LE(err_h, 1);
    }
}

/* ---- odometry statistics -------------------------------------------------- */

static void odometry_stats(sim_robot_t robot, const char *field, const char *camera)
{
    sim_scenario_t sc;
    sim_t sim;
    sim_step_t st;
    char text[512];
    double sxx = 0, sxo = 0, syy = 0, syo = 0, sth = 0, sto = 0;
    double n = 0, ex2 = 0, ey2 = 0, sum_l = 0, sum_rth = 0, eth2 = 0;
    double sum_odx = 0, sum_odx_i = 0, sum_oth = 0, sum_oth_i = 0;
    double est_sx, est_sy, est_st, est_drift, sd_x, sd_y, sd_th;
    snprintf(text, sizeof text,
             "robot %s\nfield %s\ncamera %s\nseed 99\nduration_s %d\n"
             "slip_rate_hz 0\nmax_range_mm 1\n"
             "waypoint -2000 -1000\nwaypoint 1500 1200\nwaypoint 2000 -1200\n"
             "waypoint -500 800\n",
             robot == SIM_ROBOT_AIBO ? "aibo" : "nao", field, camera,
             t_quick ? 300 : 600);   /* quick (qemu): half the walk */
    CHECK_EQ(sim_scenario_parse(&sc, text, NULL, 0), 0);
    CHECK_EQ(sim_init(&sim, &sc), 0);
    while (sim_step(&sim, &st)) {
        double L = hypot(st.true_dx, st.true_dy), rx, ry, rth, sig;
        sum_odx += st.odo_dx;
        sum_odx_i += st.odo_dx_mm;
        sum_oth += st.odo_dtheta_rad;
        sum_oth_i += ang_rad(st.odo_dtheta);
        if (L < 1e-9 && st.true_dtheta_rad == 0)
            continue;
        /* regressions through the origin: odo = (1 + s) * true */
        sxx += st.true_dx * st.true_dx;
        sxo += st.true_dx * st.odo_dx;
        syy += st.true_dy * st.true_dy;
        syo += st.true_dy * st.odo_dy;
        sth += st.true_dtheta_rad * st.true_dtheta_rad;
        sto += st.true_dtheta_rad * st.odo_dtheta_rad;
        /* residuals with the configured systematic part removed */
        rx = st.odo_dx - (1 + sc.odo_scale_x) * st.true_dx;
        ry = st.odo_dy - (1 + sc.odo_scale_y) * st.true_dy;
        rth = st.odo_dtheta_rad - (1 + sc.odo_scale_theta) * st.true_dtheta_rad;
        sum_l += L;
        sum_rth += rth;
        if (L > 1e-9) {
            ex2 += (rx / L) * (rx / L);
            ey2 += (ry / L) * (ry / L);
        }
        sig = sc.odo_sigma_rot * fabs(st.true_dtheta_rad) +
              sc.odo_sigma_rot_deg_per_m * (PI / 180) * L / 1000;
        rth -= sc.odo_drift_deg_per_m * (PI / 180) * L / 1000;
        if (sig > 0)
            eth2 += (rth / sig) * (rth / sig);
        n++;
    }
    est_sx = sxo / sxx - 1;
    est_sy = syo / syy - 1;
    est_st = sto / sth - 1;
    est_drift = sum_rth / (sum_l / 1000) * 180 / PI;
    sd_x = sqrt(ex2 / n);
    sd_y = sqrt(ey2 / n);
    sd_th = sqrt(eth2 / n);
    t_info("sim.odometry %s (%.0f moving steps, %.0f m): scale x %.4f (set %.2f) "
           "y %.4f (%.2f) theta %.4f (%.2f); drift %.3f deg/m (%.1f); "
           "random: x %.4f y %.4f of the step (%.2f), rotation %.3f sigma",
           field, n, sum_l / 1000, est_sx, sc.odo_scale_x, est_sy, sc.odo_scale_y,
           est_st, sc.odo_scale_theta, est_drift, sc.odo_drift_deg_per_m, sd_x,
           sd_y, sc.odo_sigma_trans, sd_th);
    CHECK(n > 5000);
    CHECK_LE(fabs(est_sx - sc.odo_scale_x), 0.01);
    CHECK_LE(fabs(est_sy - sc.odo_scale_y), 0.03);   /* little sideways walking */
    CHECK_LE(fabs(est_st - sc.odo_scale_theta), 0.02);
    CHECK_LE(fabs(est_drift - sc.odo_drift_deg_per_m), 0.1 * sc.odo_drift_deg_per_m);
    CHECK_LE(fabs(sd_x / sc.odo_sigma_trans - 1), 0.05);
    CHECK_LE(fabs(sd_y / sc.odo_sigma_trans - 1), 0.05);
    CHECK_LE(fabs(sd_th - 1), 0.05);
    /* integer odometry with error diffusion sums to the exact odometry */
    CHECK_LE(fabs(sum_odx_i - sum_odx), 0.5 + 1e-6);
    CHECK_LE(fabs(sum_oth_i - sum_oth), 0.5 * 2 * PI / 65536 + 1e-9);
}

static void test_odometry(void)
{
    odometry_stats(SIM_ROBOT_NAO, "spl2013", "nao4-top-320");
    odometry_stats(SIM_ROBOT_AIBO, "aibo2004", "aibo-ers7");
}

/* ---- observations: geometry, completeness, field of view ------------------ */

static void test_geometry_noiseless(void)
{
    int i;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        sim_scenario_t sc;
        sim_t sim;
        sim_step_t st;
        double max_pos = 0, max_brg = 0, max_ori = 0;
        long n_obs = 0, n_expect = 0, n_bad_kind = 0, n_fp = 0;
        if (load_builtin(&sc, i) != 0)
            continue;
        sim_scenario_noise_off(&sc);
        sc.n_others = 0;   /* completeness without occlusion (sim.occlusion) */
        CHECK_EQ(sim_init(&sim, &sc), 0);
        while (sim_step(&sim, &st)) {
            dcam_t dc;
            int j, k;
            dcam_init(&dc, sc.camera, &st.head);
            for (j = 0; j < st.obs.n; j++) {
                const fl_obs_t *o = &st.obs.obs[j];
                const fl_landmark_t *lm;
                double h = ang_rad(st.heading), b = ang_rad(o->bearing);
                double fx, fy, want_b;
                if (st.obs_landmark[j] < 0) {
                    n_fp++;
                    continue;
                }
                lm = &sc.field->landmarks[st.obs_landmark[j]];
                n_bad_kind += o->kind != lm->kind || st.obs_confused[j];
                fx = st.x_mm + o->range_mm * cos(h + b);
                fy = st.y_mm + o->range_mm * sin(h + b);
                max_pos = fmax(max_pos, hypot(fx - lm->x_mm, fy - lm->y_mm));
                want_b = atan2(lm->y_mm - st.y_mm, lm->x_mm - st.x_mm) - h;
                max_brg = fmax(max_brg, fabs(wrap_pi(b - want_b)) * 180 / PI);
                if (o->has_orientation) {
                    fl_angle_t mo;
                    CHECK(fl_landmark_orientation(lm, &mo));
                    max_ori = fmax(max_ori, fabs(wrap_pi(ang_rad(o->orientation) -
                                                         (ang_rad(mo) - h))) * 180 / PI);
                }
            }
            n_obs += st.obs.n;
            /* completeness: every landmark well inside the image and within
             * range (independent model) is observed */
            for (k = 0; k < sc.field->n_landmarks; k++) {
                const fl_landmark_t *lm = &sc.field->landmarks[k];
                double rx, ry, u, v, m = sc.fov_margin_px + 0.5;
                int seen = 0;
                field_to_robot(&st, lm->x_mm, lm->y_mm, &rx, &ry);
                if (!dcam_project(&dc, rx, ry, &u, &v) || u < m || v < m ||
                    u > dc.w - 1 - m || v > dc.h - 1 - m ||
                    hypot(lm->x_mm - st.x_mm, lm->y_mm - st.y_mm) > sc.max_range_mm - 1)
                    continue;
                n_expect++;
                for (j = 0; j < st.obs.n; j++)
                    seen |= st.obs_landmark[j] == k;
                CHECK(seen);
                if (!seen)
                    t_fail_msg(__FILE__, __LINE__, "%s step %u: landmark %d at (%.1f, %.1f) px not observed",
                               sim_builtin_names[i], (unsigned)st.index, k, u, v);
            }
        }
        t_info("sim.geometry %s noise off: %ld observations (%ld expected well inside), "
               "max re-projection error %.3f mm, bearing %.4f deg, orientation %.4f deg",
               sim_builtin_names[i], n_obs, n_expect, max_pos, max_brg, max_ori);
        CHECK(n_obs > 1000);
        CHECK_EQ(n_fp, 0);
        CHECK_EQ(n_bad_kind, 0);
        CHECK_LE(max_pos, 1.0);
        CHECK_LE(max_brg, 0.01);
        CHECK_LE(max_ori, 0.01);
    }
}

static void test_field_of_view(void)
{
    int i;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        sim_scenario_t sc;
        sim_t sim;
        sim_step_t st;
        double worst_out = -1e9, max_range_seen = 0, max_uv_err = 0, max_uv_fp = 0;
        long n = 0;
        if (load_builtin(&sc, i) != 0)
            continue;
        CHECK_EQ(sim_init(&sim, &sc), 0);
        while (sim_step(&sim, &st)) {
            dcam_t dc;
            int j;
            dcam_init(&dc, sc.camera, &st.head);
            for (j = 0; j < st.obs.n; j++) {
                const fl_obs_t *o = &st.obs.obs[j];
                double rx, ry, u, v, out;
                if (st.obs_landmark[j] >= 0) {
                    const fl_landmark_t *lm = &sc.field->landmarks[st.obs_landmark[j]];
                    field_to_robot(&st, lm->x_mm, lm->y_mm, &rx, &ry);
                } else {
                    double b = ang_rad(o->bearing);
                    rx = o->range_mm * cos(b);
                    ry = o->range_mm * sin(b);
                }
                max_range_seen = fmax(max_range_seen, hypot(rx, ry) / sc.max_range_mm);
                if (!dcam_project(&dc, rx, ry, &u, &v)) {
                    CHECK(0);   /* behind the camera */
                    continue;
                }
                /* how far outside the image (negative: inside) */
                out = fmax(fmax(-u, u - (dc.w - 1)), fmax(-v, v - (dc.h - 1)));
                worst_out = fmax(worst_out, out);
                if (st.obs_landmark[j] >= 0)
                    max_uv_err = fmax(max_uv_err, fmax(fabs(u - o->u_q4 / 16.0),
                                                       fabs(v - o->v_q4 / 16.0)));
                else
                    max_uv_fp = fmax(max_uv_fp, fmax(fabs(u - o->u_q4 / 16.0),
                                                     fabs(v - o->v_q4 / 16.0)));
                n++;
            }
        }
        t_info("sim.fov %s: %ld observations (incl. false positives), farthest inside "
               "the image edge %.2f px (negative = inside), max range / limit %.4f, "
               "image position vs independent model %.3f px (false positives: "
               "%.3f px from their rounded range and bearing)",
               sim_builtin_names[i], n, worst_out, max_range_seen, max_uv_err, max_uv_fp);
        CHECK(n > 1000);
        /* the simulator's margin is fov_margin_px; rounding of the robot-
         * frame point (0.5 mm) and of false-positive ranges moves less than
         * 1 px at these distances */
        CHECK_LE(worst_out, 1.0 - sc.fov_margin_px);
        CHECK_LE(max_range_seen, 1.0 + 1e-3);
        CHECK_LE(max_uv_err, 1.0);
    }
}

/* ---- observation noise statistics ---------------------------------------- */

static void test_observation_noise(void)
{
    sim_scenario_t sc;
    sim_t sim;
    sim_step_t st;
    sim_scenario_t clean;
    double er2 = 0, eb2 = 0, eo2 = 0, er_mean = 0;
    double n = 0, n_o = 0, n_fp = 0, n_lt = 0, n_conf = 0, n_vis = 0, frames = 0;
    double n_post = 0, n_post_sided = 0, n_side_wrong = 0;
    double miss_rate, fp_rate, conf_rate;
    CHECK_EQ(sim_scenario_builtin(&sc, "spl2013"), 0);
    sc.white_points = 0;
    sc.duration_s = t_quick ? 200 : 400;   /* quick (qemu): half */
    clean = sc;
    sim_scenario_noise_off(&clean);
    sc.slip_rate_hz = 0;
    CHECK_EQ(sim_init(&sim, &sc), 0);
    while (sim_step(&sim, &st)) {
        int j, goal_seen[2] = {0, 0};
        fl_camera_t cam;
        sim_step_t ref;
        uint64_t rng = 1;
        /* what a perfect detector would see from the same pose */
        CHECK_EQ(fl_camera_init(&cam, sc.camera, &st.head), FL_OK);
        memset(&ref, 0, sizeof ref);
        sim_observe(&clean, &cam, st.x_mm, st.y_mm, st.heading, &rng, &ref);
        n_vis += ref.obs.n;
        frames++;
        for (j = 0; j < st.obs.n; j++) {
            int k = st.obs_landmark[j];
            if (k >= 0 && sc.field->landmarks[k].kind == FL_LM_POST)
                goal_seen[sc.field->landmarks[k].goal > 0]++;
        }
        for (j = 0; j < st.obs.n; j++) {
            const fl_obs_t *o = &st.obs.obs[j];
            const fl_landmark_t *lm;
            double h = ang_rad(st.heading), r, b;
            int k = st.obs_landmark[j];
            if (k < 0) {
                n_fp++;
                continue;
            }
            lm = &sc.field->landmarks[k];
            r = hypot(lm->x_mm - st.x_mm, lm->y_mm - st.y_mm);
            b = atan2(lm->y_mm - st.y_mm, lm->x_mm - st.x_mm) - h;
            er_mean += (o->range_mm - r) / r;
            er2 += ((o->range_mm - r) / r) * ((o->range_mm - r) / r);
            eb2 += pow(wrap_pi(ang_rad(o->bearing) - b) * 180 / PI, 2);
            if (o->has_orientation) {
                fl_angle_t mo;
                fl_landmark_orientation(lm, &mo);
                eo2 += pow(wrap_pi(ang_rad(o->orientation) - (ang_rad(mo) - h)) * 180 / PI, 2);
                n_o++;
            }
            if (lm->kind == FL_LM_L || lm->kind == FL_LM_T) {
                n_lt++;
                n_conf += st.obs_confused[j];
                CHECK_EQ(st.obs_confused[j], o->kind != lm->kind);
            }
            if (lm->kind == FL_LM_POST) {
                int both = goal_seen[lm->goal > 0] >= 2;
                n_post++;
                n_post_sided += o->side != FL_SIDE_UNKNOWN;
                n_side_wrong += both ? o->side != lm->side : o->side != FL_SIDE_UNKNOWN;
            }
            n++;
        }
    }
    er_mean /= n;
    miss_rate = 1.0 - n / n_vis;
    fp_rate = n_fp / frames;
    conf_rate = n_conf / n_lt;
    t_info("sim.noise spl2013 %.0f s: %.0f observations of %.0f visible: range error "
           "mean %.4f sd %.4f (set %.2f), bearing sd %.3f deg (%.2f), orientation sd "
           "%.3f deg (%.1f), miss rate %.4f (%.2f), false positives %.4f/frame (%.2f), "
           "L<->T confusion %.4f (%.2f), posts %.0f (%.0f with side)",
           sc.duration_s, n, n_vis, er_mean, sqrt(er2 / n - er_mean * er_mean), sc.range_sigma_pct / 100,
           sqrt(eb2 / n), sc.bearing_sigma_deg, sqrt(eo2 / n_o), sc.orientation_sigma_deg,
           miss_rate, sc.p_miss, fp_rate, sc.fp_per_frame, conf_rate, sc.p_confuse,
           n_post, n_post_sided);
    CHECK(n > 10000);
    CHECK_LE(fabs(er_mean), 0.005);
    CHECK_LE(fabs(sqrt(er2 / n - er_mean * er_mean) / (sc.range_sigma_pct / 100) - 1), 0.05);
    CHECK_LE(fabs(sqrt(eb2 / n) / sc.bearing_sigma_deg - 1), 0.05);
    CHECK_LE(fabs(sqrt(eo2 / n_o) / sc.orientation_sigma_deg - 1), 0.05);
    CHECK_LE(fabs(miss_rate - sc.p_miss), 0.02);
    CHECK_LE(fabs(fp_rate - sc.fp_per_frame), 0.02);
    CHECK_LE(fabs(conf_rate - sc.p_confuse), 0.015);
    CHECK(n_post > 100);
    CHECK(n_post_sided > 0 && n_post_sided < n_post);
    CHECK_EQ(n_side_wrong, 0);
}

/* ---- events ---------------------------------------------------------------- */

static void test_events(void)
{
    int i, sides[2] = {0, 0};
    unsigned seed;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        sim_scenario_t sc;
        sim_t sim;
        sim_step_t st, prev;
        int n_kidnap = 0, n_pen = 0, n_unpen = 0, penalized = 0;
        int32_t px = 0, py = 0;
        fl_angle_t ph = 0;
        double pen_t = 0, pen_dur = 0;
        int j;
        if (load_builtin(&sc, i) != 0)
            continue;
        for (j = 0; j < sc.n_events; j++)
            if (sc.event[j].kind == SIM_EVENT_PENALTY) {
                pen_t = sc.event[j].t_s;
                pen_dur = sc.event[j].duration_s;
            }
        CHECK_EQ(sim_init(&sim, &sc), 0);
        memset(&prev, 0, sizeof prev);
        while (sim_step(&sim, &st)) {
            double step_max = (sc.v_forward_mm_s + sc.v_side_mm_s) / sc.frame_hz *
                              (1 + sc.odo_scale_x + sc.odo_scale_y) * 2 + 1;
            if (st.events & SIM_EV_KIDNAP) {
                const sim_event_t *e = NULL;
                for (j = 0; j < sc.n_events; j++)
                    if (sc.event[j].kind == SIM_EVENT_KIDNAP)
                        e = &sc.event[j];
                n_kidnap++;
                CHECK(e != NULL);
                if (e) {
                    CHECK_EQ(st.x_mm, (int32_t)lround(e->x_mm));
                    CHECK_EQ(st.y_mm, (int32_t)lround(e->y_mm));
                    CHECK_LE(abs(fl_angle_sub(st.heading,
                                              fl_angle_from_mdeg((int32_t)(e->heading_deg * 1000)))), 1);
                    CHECK_LE(fabs(st.t_ms - e->t_s * 1000), 1000 / sc.frame_hz);
                    /* far from where the robot was: a real teleport */
                    CHECK(hypot(st.x_mm - prev.x_mm, st.y_mm - prev.y_mm) > 500);
                }
                /* odometry says nothing about it: one ordinary step */
                CHECK_LE(hypot(st.odo_dx_mm, st.odo_dy_mm), step_max);
            }
            if (st.events & SIM_EV_PENALIZED) {
                n_pen++;
                penalized = 1;
                CHECK_LE(fabs(st.t_ms - pen_t * 1000), 1000 / sc.frame_hz);
                CHECK_EQ(st.x_mm, (int32_t)lround(sc.penalty_x_mm));
                CHECK_EQ(abs(st.y_mm), sc.field->width_mm / 2);   /* touchline */
                /* facing into the field: +90 deg on the -y line, -90 on +y */
                CHECK_EQ(st.heading, st.y_mm > 0 ? -FL_ANGLE_90 : FL_ANGLE_90);
                CHECK_LE(hypot(st.odo_dx_mm, st.odo_dy_mm), step_max);
                CHECK(st.penalized);
                px = st.x_mm;
                py = st.y_mm;
                ph = st.heading;
                sides[st.y_mm > 0]++;
            } else if (penalized && !(st.events & SIM_EV_UNPENALIZED)) {
                /* standing still at the spot, head still scanning */
                CHECK(st.penalized);
                CHECK_EQ(st.x_mm, px);
                CHECK_EQ(st.y_mm, py);
                CHECK_EQ(st.heading, ph);
                CHECK_EQ(st.odo_dx_mm, 0);
                CHECK_EQ(st.odo_dy_mm, 0);
                CHECK_EQ(st.odo_dtheta, 0);
            }
            if (st.events & SIM_EV_UNPENALIZED) {
                n_unpen++;
                CHECK(penalized);
                CHECK(!st.penalized);
                CHECK_LE(fabs(st.t_ms - (pen_t + pen_dur) * 1000), 1000 / sc.frame_hz + 1);
                penalized = 0;
            }
            prev = st;
        }
        CHECK_EQ(n_kidnap, 1);
        CHECK_EQ(n_pen, 1);
        CHECK_EQ(n_unpen, 1);
    }
    /* both touchlines get used over seeds */
    for (seed = 1; seed <= 16; seed++) {
        sim_scenario_t sc;
        sim_t sim;
        sim_step_t st;
        char text[256];
        snprintf(text, sizeof text, "field uva2013\ncamera nao4-top-320\nseed %u\n"
                 "duration_s 2\nwaypoint 0 0\npenalty 1 0.5\n", seed);
        CHECK_EQ(sim_scenario_parse(&sc, text, NULL, 0), 0);
        CHECK_EQ(sim_init(&sim, &sc), 0);
        while (sim_step(&sim, &st))
            if (st.events & SIM_EV_PENALIZED)
                sides[st.y_mm > 0]++;
    }
    CHECK(sides[0] >= 3 && sides[1] >= 3);
}

/* ---- head ------------------------------------------------------------------ */

static void test_head(void)
{
    int i;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        sim_scenario_t sc;
        sim_t sim;
        sim_step_t st;
        double ymin = 1e9, ymax = -1e9, max_rate = 0, prev_yaw = 0;
        int pitch_values[2] = {0, 0};
        if (load_builtin(&sc, i) != 0)
            continue;
        CHECK_EQ(sim_init(&sim, &sc), 0);
        while (sim_step(&sim, &st)) {
            ymin = fmin(ymin, st.head_yaw_rad);
            ymax = fmax(ymax, st.head_yaw_rad);
            if (st.index > 0)
                max_rate = fmax(max_rate, fabs(st.head_yaw_rad - prev_yaw) * sc.frame_hz);
            prev_yaw = st.head_yaw_rad;
            if (fabs(st.head_pitch_rad - sc.head_pitch_rad[0]) < 1e-4)
                pitch_values[0]++;
            else if (fabs(st.head_pitch_rad - sc.head_pitch_rad[1]) < 1e-4)
                pitch_values[1]++;
            else
                CHECK(0);
        }
        t_info("sim.head %s: yaw %.3f..%.3f rad, max yaw rate %.3f rad/s",
               sim_builtin_names[i], ymin, ymax, max_rate);
        /* the sweep is sampled: the extremes are reached within one
         * frame's worth of yaw motion */
        CHECK_LE(sc.yaw_amplitude_rad - ymax, 4 * sc.yaw_amplitude_rad / sc.yaw_period_s / sc.frame_hz + 1e-4);
        CHECK_LE(sc.yaw_amplitude_rad + ymin, 4 * sc.yaw_amplitude_rad / sc.yaw_period_s / sc.frame_hz + 1e-4);
        CHECK_LE(ymax, sc.yaw_amplitude_rad + 1e-4);
        CHECK_LE(-ymin, sc.yaw_amplitude_rad + 1e-4);
        CHECK_LE(max_rate, 4 * sc.yaw_amplitude_rad / sc.yaw_period_s * 1.01);
        CHECK(pitch_values[0] > 0);
        if (sc.pitch_period_s > 0)
            CHECK(pitch_values[1] > 0);
    }
}

/* ---- scenario text ----------------------------------------------------------- */

static int scenario_equal(const sim_scenario_t *a, const sim_scenario_t *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

static void test_scenario_text(void)
{
    int i;
    char err[128];
    sim_scenario_t sc, bad;
    static const char *const bad_texts[] = {
        "field spl2013\ncamera nao4-top-320\n",                       /* no waypoint */
        "field nowhere\ncamera nao4-top-320\nwaypoint 0 0\n",         /* field */
        "field spl2013\ncamera nocam\nwaypoint 0 0\n",                /* camera */
        "field spl2013\nrobot aibo\ncamera aibo-ers7\nwaypoint 0 0\n",/* robot late */
        "field spl2013\ncamera nao4-top-320\nwaypoint 0\n",           /* arity */
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nspeed 3\n",/* unknown */
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\np_miss 2\n",/* range */
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nkidnap 5 0 0 0\nkidnap 4 0 0 0\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nframe_hz 0\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nother 1 2 3 green\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nother 1 2 red\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nother 1 2 3 red x\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nother 1e9 2 3 red\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nother nan 2 3 red\n",
        "field spl2013\ncamera nao4-top-320\nwaypoint 0 0\nother 0 0 0 red\nother 0 0 0 red\n"
        "other 0 0 0 red\nother 0 0 0 red\nother 0 0 0 red\nother 0 0 0 red\n"
        "other 0 0 0 red\nother 0 0 0 red\nother 0 0 0 red\n",   /* 9 robots */
    };
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        FILE *f;
        char *buf = NULL;
        size_t len = 0;
        sim_scenario_t back;
        if (load_builtin(&sc, i) != 0)
            continue;
        sc.white_points = 1;   /* the default: the text form does not carry it */
        f = open_memstream(&buf, &len);
        CHECK(f != NULL);
        if (f == NULL)
            continue;
        CHECK_EQ(sim_scenario_write(f, &sc), 0);
        fclose(f);
        CHECK_EQ(sim_scenario_parse(&back, buf, err, (int)sizeof err), 0);
        /* names are stored in fixed arrays, pointers resolve identically */
        CHECK(scenario_equal(&sc, &back));
        free(buf);
        CHECK_EQ(sc.n_events, 2);
        CHECK(sc.duration_s >= 120);
    }
    for (i = 0; i < (int)(sizeof bad_texts / sizeof bad_texts[0]); i++) {
        err[0] = '\0';
        CHECK_EQ(sim_scenario_parse(&bad, bad_texts[i], err, (int)sizeof err), -1);
        CHECK(err[0] != '\0');
    }
    {
        /* a name given twice, the second shorter (found by fuzz_walk): the
         * round trip still gives identical bytes; robots round-trip too */
        static const char twice[] = "name longer_name\nname x\nfield spl2020\n"
                                    "camera nao6-top-640\ncamera nao6-top-320\nwaypoint 0 0\n"
                                    "other -1000.5 20 -90 blue\nother 3 -4 359.25 red\n";
        sim_scenario_t a, b;
        char *buf = NULL;
        size_t len = 0;
        FILE *f;
        CHECK_EQ(sim_scenario_parse(&a, twice, err, (int)sizeof err), 0);
        CHECK_EQ(a.n_others, 2);
        CHECK(a.other[0].jersey == RENDER_JERSEY_BLUE && a.other[1].jersey == RENDER_JERSEY_RED);
        CHECK(a.other[0].x_mm == -1000.5 && a.other[1].heading_deg == 359.25);
        f = open_memstream(&buf, &len);
        CHECK(f != NULL);
        if (f != NULL) {
            CHECK_EQ(sim_scenario_write(f, &a), 0);
            fclose(f);
            CHECK(strstr(buf, "other -1000.5 20 -90 blue\n") != NULL);
            CHECK_EQ(sim_scenario_parse(&b, buf, err, (int)sizeof err), 0);
            CHECK(scenario_equal(&a, &b));
            free(buf);
        }
    }
    CHECK_EQ(sim_scenario_parse(NULL, "x", NULL, 0), -1);
    CHECK_EQ(sim_scenario_parse(&bad, NULL, NULL, 0), -1);
    CHECK_EQ(sim_scenario_builtin(&bad, "nowhere"), -1);
    CHECK(sim_builtin_text(NULL) == NULL);
    CHECK_EQ(sim_init(NULL, &sc), -1);
    {
        sim_t sim;
        sim_step_t st;
        CHECK_EQ(sim_init(&sim, NULL), -1);
        CHECK_EQ(sim_step(&sim, &st), 0);   /* unusable state: no steps */
        CHECK_EQ(sim_step(NULL, &st), 0);
    }
}

/* ---- determinism ----------------------------------------------------------- */

static uint32_t walk_digest(const sim_scenario_t *sc, uint32_t *n_steps)
{
    sim_t sim;
    sim_step_t st;
    uint32_t h = t_hash_init();
    int j;
    *n_steps = 0;
    if (sim_init(&sim, sc) != 0)
        return 0;
    while (sim_step(&sim, &st)) {
        int32_t v[] = {(int32_t)st.index, st.t_ms, st.x_mm, st.y_mm, st.heading,
                       st.true_dx_mm, st.true_dy_mm, st.true_dtheta, st.odo_dx_mm,
                       st.odo_dy_mm, st.odo_dtheta, st.head.neck_height_mm,
                       st.head.head_pitch, st.head.head_yaw, st.head.pitch_offset,
                       (int32_t)st.events, st.obs.n, st.obs.dropped};
        size_t k;
        for (k = 0; k < sizeof v / sizeof v[0]; k++)
            h = t_hash_i32(h, v[k]);
        for (j = 0; j < st.obs.n; j++) {
            const fl_obs_t *o = &st.obs.obs[j];
            int32_t w[] = {(int32_t)o->kind, (int32_t)o->side, (int32_t)o->color,
                           o->range_mm, o->bearing, o->orientation, o->has_orientation,
                           o->confidence, o->u_q4, o->v_q4, st.obs_landmark[j],
                           st.obs_confused[j]};
            for (k = 0; k < sizeof w / sizeof w[0]; k++)
                h = t_hash_i32(h, w[k]);
        }
        (*n_steps)++;
    }
    return h;
}

static void test_determinism(void)
{
    int i;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        sim_scenario_t sc;
        uint32_t a, b, na, nb;
        char label[64];
        if (load_builtin(&sc, i) != 0)
            continue;
        a = walk_digest(&sc, &na);
        b = walk_digest(&sc, &nb);
        CHECK_EQ(a, b);
        CHECK_EQ(na, nb);
        CHECK_EQ(na, (uint32_t)(sc.duration_s * sc.frame_hz) + 1);
        snprintf(label, sizeof label, "sim.walk.%s", sim_builtin_names[i]);
        t_digest(label, a);
        /* a different seed gives a different walk */
        sc.seed++;
        CHECK(walk_digest(&sc, &nb) != a);
    }
}

/* ---- committed fixtures ------------------------------------------------------ */


static void test_fixtures(void)
{
    int i;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++) {
        const char *name = sim_builtin_names[i];
        char path[256], err[128];
        char *walk, *trace, *gen = NULL;
        size_t wlen = 0, tlen = 0, glen = 0;
        sim_scenario_t sc;
        FILE *f;
        snprintf(path, sizeof path, "fixtures/walks/%s.walk", name);
        walk = t_read_file(path, &wlen);
        CHECK(walk != NULL);
        if (walk == NULL) {
            t_fail_msg(__FILE__, __LINE__, "missing %s (run from the repository root)", path);
            continue;
        }
        CHECK(strcmp(walk, sim_builtin_text(name)) == 0);
        CHECK_EQ(sim_scenario_load(&sc, path, err, (int)sizeof err), 0);
        snprintf(path, sizeof path, "fixtures/walks/%s.trace", name);
        trace = t_read_file(path, &tlen);
        CHECK(trace != NULL);
        f = open_memstream(&gen, &glen);
        CHECK(f != NULL);
        if (f != NULL) {
            CHECK_EQ(sim_write_trace(f, &sc), 0);
            fclose(f);
        }
        CHECK(trace != NULL && gen != NULL && tlen == glen && memcmp(trace, gen, glen) == 0);
        CHECK_LE(tlen, 1000000);
        if (trace != NULL && gen != NULL && (tlen != glen || memcmp(trace, gen, glen) != 0))
            t_fail_msg(__FILE__, __LINE__, "%s differs from the generator (%zu vs %zu bytes): "
                       "regenerate with sim_write_walk_fixtures", path, tlen, glen);
        free(walk);
        free(trace);
        free(gen);
    }
}

/* ---- mode (b): sequence file ------------------------------------------------- */

static void test_sequence(void)
{
    sim_scenario_t sc;
    char dir[] = "/tmp/fl_sim_seqXXXXXX", path[256], line[512];
    FILE *f;
    int frames = 0, header = 0, prior = 0;
    if (render_frame == NULL) {
        t_info("sim.sequence: skipped, tools/world/render.c not built");
        return;
    }
    if (t_quick) {
        t_info("sim.sequence: skipped in quick mode (renders frames)");
        return;
    }
    CHECK_EQ(sim_scenario_builtin(&sc, "uva2013"), 0);
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/walk.seq", dir);
    CHECK_EQ(sim_write_sequence(&sc, path, "img/f", 15, 3, 1), 0);
    f = fopen(path, "r");
    CHECK(f != NULL);
    while (f != NULL && fgets(line, sizeof line, f)) {
        char img[128], full[400];
        double dx, dy, dth, p, y;
        render_frame_t fr;
        char err[128];
        if (strncmp(line, "field uva2013", 13) == 0 || strncmp(line, "camera ", 7) == 0)
            header++;
        else if (strncmp(line, "prior ", 6) == 0)
            prior++;
        else {
            CHECK_EQ(sscanf(line, "frame %127s odo %lf %lf %lf head %lf %lf", img, &dx,
                            &dy, &dth, &p, &y), 6);
            snprintf(full, sizeof full, "%s/%s", dir, img);
            CHECK_EQ(render_read_frame(full, &fr, err, (int)sizeof err), 0);
            if (fr.data != NULL) {
                CHECK_EQ(fr.width, 320);
                render_frame_free(&fr);
            }
            remove(full);
            CHECK_LE(fabs(p - (-0.54)), 1e-3);
            if (frames > 0)   /* 15 steps at 150 mm/s: at most ~90 mm */
                CHECK_LE(hypot(dx, dy), 150.0 * 15 / 30 * 1.3 + 5);
            frames++;
        }
    }
    if (f != NULL)
        fclose(f);
    CHECK_EQ(header, 2);
    CHECK_EQ(prior, 1);
    CHECK_EQ(frames, 3);
    remove(path);
    snprintf(path, sizeof path, "%s/img", dir);
    rmdir(path);
    rmdir(dir);
}


/* ---- other robots on the field (spl2020) ------------------------------------ */

static int find_landmark(const fl_field_t *f, int32_t x, int32_t y)
{
    int i;
    for (i = 0; i < f->n_landmarks; i++)
        if (f->landmarks[i].x_mm == x && f->landmarks[i].y_mm == y)
            return i;
    return -1;
}

static int obs_has(const sim_step_t *st, int lm)
{
    int j;
    for (j = 0; j < st->obs.n; j++)
        if (st->obs_landmark[j] == lm)
            return 1;
    return 0;
}

/* The spl2020 walk has robots of both jerseys, the walker keeps clear of
 * them, and a landmark behind one is not reported (feature mode) while the
 * ones beside it are; the renderer's own occlusion test agrees. */
static void test_others(void)
{
    sim_scenario_t sc, bare;
    sim_t sim;
    sim_step_t st;
    fl_camera_t cam;
    fl_camera_pose_t head;
    uint64_t rng = 1;
    int i, blue = 0, red = 0, centre, x_left, x_right, hidden_steps = 0;
    long n_hidden = 0, n_reported_hidden = 0;
    double min_clear = 1e9;
    CHECK_EQ(sim_scenario_builtin(&sc, "spl2020"), 0);
    sc.white_points = 0;
    CHECK_EQ(sc.n_others, 6);
    for (i = 0; i < sc.n_others; i++) {
        blue += sc.other[i].jersey == RENDER_JERSEY_BLUE;
        red += sc.other[i].jersey == RENDER_JERSEY_RED;
    }
    CHECK_EQ(blue, 3);
    CHECK_EQ(red, 3);
    /* the walker (it does not avoid obstacles) keeps clear of the robots:
     * seeds 1-6 (those of make results) with the walk's own kidnap and with
     * two (--kidnaps 2), both penalty sides among them */
    for (i = 0; i < 12; i++) {
        sim_scenario_t w = sc;
        w.seed = (uint64_t)(i / 2 + 1);
        CHECK_EQ(sim_scenario_set_kidnaps(&w, i % 2 ? 2 : 1), 0);
        CHECK_EQ(sim_init(&sim, &w), 0);
        while (sim_step(&sim, &st)) {
            int k;
            for (k = 0; k < w.n_others; k++) {
                double dx = st.true_x_mm - w.other[k].x_mm, dy = st.true_y_mm - w.other[k].y_mm;
                double d = sqrt(dx * dx + dy * dy);
                if (d < min_clear)
                    min_clear = d;
            }
        }
    }
    /* the built-in walk: what a robot hides */
    CHECK_EQ(sim_init(&sim, &sc), 0);
    while (sim_step(&sim, &st)) {
        int k, hid = 0;
        /* every landmark in view that a robot hides is left out */
        if (fl_camera_init(&cam, sc.camera, &st.head) != FL_OK)
            continue;
        for (k = 0; k < sc.field->n_landmarks; k++) {
            const fl_landmark_t *lm = &sc.field->landmarks[k];
            double ch = cos(ang_rad(st.heading)), sh = sin(ang_rad(st.heading));
            double dx = lm->x_mm - st.x_mm, dy = lm->y_mm - st.y_mm;
            fl_point_t gp;
            int32_t u, v;
            gp.x_mm = (int32_t)lround(dx * ch + dy * sh);
            gp.y_mm = (int32_t)lround(-dx * sh + dy * ch);
            if (!fl_camera_ground_to_pixel(&cam, gp, &u, &v) || u < 0 || v < 0 ||
                u >= 16 * sc.camera->width_px || v >= 16 * sc.camera->height_px ||
                sqrt(dx * dx + dy * dy) > sc.max_range_mm)
                continue;   /* not in view anyway */
            if (sim_occluded(&sc, &cam, st.x_mm, st.y_mm, st.heading, lm->x_mm, lm->y_mm, 0)) {
                n_hidden++;
                hid = 1;
                n_reported_hidden += obs_has(&st, k);
            }
        }
        hidden_steps += hid;
    }
    t_info("sim.others: walker (seeds 1-6) at least %.0f mm from the other robots; %ld landmark hidings "
           "in view in %d of %u steps", min_clear, n_hidden, hidden_steps, sim_step_count(&sim));
    CHECK(min_clear >= 600);
    CHECK_EQ(n_reported_hidden, 0);
    CHECK(hidden_steps >= 100);

    /* added kidnaps never put the walker onto another robot */
    {
        unsigned seed;
        int n_targets = 0;
        for (seed = 1; seed <= 10; seed++) {
            sim_scenario_t k = sc;
            int e, o;
            k.seed = seed;
            CHECK_EQ(sim_scenario_set_kidnaps(&k, 8), 0);
            for (e = 0; e < k.n_events; e++) {
                if (k.event[e].kind != SIM_EVENT_KIDNAP)
                    continue;
                n_targets++;
                for (o = 0; o < k.n_others; o++) {
                    double dx = k.event[e].x_mm - k.other[o].x_mm;
                    double dy = k.event[e].y_mm - k.other[o].y_mm;
                    CHECK(dx * dx + dy * dy >= 500.0 * 500.0);
                }
            }
        }
        CHECK_EQ(n_targets, 80);
    }

    /* one robot between the camera and the centre mark: the mark goes, the
     * two centre-line crossings beside it stay */
    bare = sc;
    sim_scenario_noise_off(&bare);
    bare.n_others = 0;
    memset(&head, 0, sizeof head);
    head.neck_height_mm = 460;
    head.head_pitch = (fl_angle_t)2607;   /* 0.25 rad */
    CHECK_EQ(fl_camera_init(&cam, bare.camera, &head), FL_OK);
    centre = find_landmark(bare.field, 0, 0);
    x_left = find_landmark(bare.field, 0, 750);
    x_right = find_landmark(bare.field, 0, -750);
    CHECK(centre >= 0 && x_left >= 0 && x_right >= 0);
    memset(&st, 0, sizeof st);
    sim_observe(&bare, &cam, -2000, 0, 0, &rng, &st);
    CHECK(obs_has(&st, centre));
    CHECK(obs_has(&st, x_left));
    CHECK(obs_has(&st, x_right));
    bare.n_others = 1;
    bare.other[0].x_mm = -1000;
    bare.other[0].y_mm = 40;   /* the ray meets a leg (not the gap between them) */
    bare.other[0].heading_deg = 180;
    bare.other[0].jersey = RENDER_JERSEY_RED;
    memset(&st, 0, sizeof st);
    sim_observe(&bare, &cam, -2000, 0, 0, &rng, &st);
    CHECK(!obs_has(&st, centre));
    CHECK(obs_has(&st, x_left));
    CHECK(obs_has(&st, x_right));
    CHECK(sim_occluded(&bare, &cam, -2000, 0, 0, 0, 0, 0));
    CHECK(!sim_occluded(&bare, &cam, -2000, 0, 0, 0, 750, 0));
    /* a point under its feet is hidden; beside it (and the robot turned
     * sideways) it is not */
    CHECK(sim_occluded(&bare, &cam, -2000, 0, 0, -1000, 40, 0));
    CHECK(!sim_occluded(&bare, &cam, -2000, 0, 0, -1000, 440, 0));
    if (render_occluded != NULL) {
        render_scene_t rs;
        memset(&st, 0, sizeof st);
        st.x_mm = -2000;
        st.head = head;
        sim_render_scene(&bare, &st, &rs);
        CHECK_EQ(rs.n_robots, 1);
        CHECK(render_occluded(&rs, 0, 0, 0, 1, -1));
        CHECK(!render_occluded(&rs, 0, 750, 0, 1, -1));
        CHECK(!render_occluded(&rs, 0, -750, 0, 1, -1));
    }
}

/* The robots are drawn: frames of the spl2020 walk where one stands in
 * view (its chest projects inside the image within 4 m) show robot pixels
 * in the render's class mask. */
static void test_others_rendered(void)
{
    sim_scenario_t sc;
    sim_t sim;
    sim_step_t st;
    int picked = 0, shown = 0;
    long total = 0, least = -1;
    if (render_frame == NULL || render_project_field == NULL) {
        t_info("sim.others_rendered: skipped, tools/world/render.c not built");
        return;
    }
    if (t_quick) {
        t_info("sim.others_rendered: skipped in quick mode (renders frames)");
        return;
    }
    CHECK_EQ(sim_scenario_builtin(&sc, "spl2020"), 0);
    CHECK_EQ(sim_init(&sim, &sc), 0);
    /* one frame every 15 s of walk at most, where a robot is in view */
    while (sim_step(&sim, &st) && picked < 8) {
        render_scene_t rs;
        render_frame_t fr;
        int k, in_view = 0;
        long px = 0;
        size_t p;
        if (st.t_ms < picked * 15000)
            continue;
        sim_render_scene(&sc, &st, &rs);
        CHECK_EQ(rs.n_robots, 6);
        for (k = 0; k < rs.n_robots; k++) {
            double u, v, r;
            if (render_project_field(&rs, rs.robots[k].x_mm, rs.robots[k].y_mm, 450, &u, &v, &r) &&
                u >= 0 && v >= 0 && u < sc.camera->width_px && v < sc.camera->height_px &&
                r < 4000)
                in_view = 1;
        }
        if (!in_view)
            continue;
        picked++;
        rs.supersample = 1;
        if (render_frame(&rs, &fr) != 0) {
            CHECK(0);
            continue;
        }
        for (p = 0; p < (size_t)fr.width * (size_t)fr.height; p++)
            px += fr.mask[p] == RENDER_CLASS_OBJECT;
        render_frame_free(&fr);
        total += px;
        if (least < 0 || px < least)
            least = px;
        shown += px >= 1000;
        t_info("sim.others_rendered: t %.1f s: %ld robot pixels", st.t_ms / 1000.0, px);
    }
    CHECK_EQ(picked, 8);
    CHECK(shown >= 7);
    t_info("sim.others_rendered: %d of %d frames with >= 1000 robot pixels (least %ld, total %ld)",
           shown, picked, least, total);
}

/* Feature mode's white points: with noise off every point, taken back to
 * the field frame with the integer true pose, lies on paint (within half
 * a line width plus rounding of a line or the circle); with noise on within
 * the range noise's reach; never more than SIM_POINTS_PER_FRAME; most
 * frames of every walk carry a full sample; and the landmark observations
 * do not depend on them (the trace digests of test_fixtures compare with
 * the committed traces, made before points existed). */
static double paint_dist(const fl_field_t *f, double x, double y)
{
    double best = f->circle_radius_mm > 0 ? fabs(hypot(x, y) - f->circle_radius_mm) : 1e30;
    uint16_t i;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *l = &f->lines[i];
        double dx = l->x1_mm - l->x0_mm, dy = l->y1_mm - l->y0_mm, t, d;
        double len2 = dx * dx + dy * dy;
        t = len2 > 0 ? ((x - l->x0_mm) * dx + (y - l->y0_mm) * dy) / len2 : 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        d = hypot(x - (l->x0_mm + t * dx), y - (l->y0_mm + t * dy));
        if (d < best)
            best = d;
    }
    return best;
}

static void test_white_points(void)
{
    int i, noise;
    for (i = 0; i < SIM_BUILTIN_COUNT; i++)
        for (noise = 0; noise < 2; noise++) {
            sim_scenario_t sc;
            sim_t sim, bare;
            sim_step_t st, bst;
            long frames = 0, full = 0, pts = 0, differ = 0;
            double worst = 0, worst_rel = 0;
            if (load_builtin(&sc, i) != 0)
                continue;
            sc.white_points = 1;
            if (!noise)
                sim_scenario_noise_off(&sc);
            sc.duration_s = t_quick ? 10 : 60;
            CHECK_EQ(sim_init(&sim, &sc), 0);
            /* the same walk without points: everything else identical */
            sc.white_points = 0;
            CHECK_EQ(sim_init(&bare, &sc), 0);
            sc.white_points = 1;
            while (sim_step(&sim, &st)) {
                double h = ang_rad(st.heading), c = cos(h), s = sin(h);
                int k;
                CHECK(sim_step(&bare, &bst));
                CHECK_EQ(bst.obs.n_points, 0);
                differ += st.x_mm != bst.x_mm || st.y_mm != bst.y_mm ||
                          st.heading != bst.heading || st.obs.n != bst.obs.n ||
                          st.odo_dx_mm != bst.odo_dx_mm ||
                          memcmp(st.obs.obs, bst.obs.obs, sizeof st.obs.obs[0] * st.obs.n) != 0;
                frames++;
                CHECK(st.obs.n_points <= SIM_POINTS_PER_FRAME);
                CHECK_EQ(st.obs.points_dropped, 0);
                full += st.obs.n_points == SIM_POINTS_PER_FRAME;
                for (k = 0; k < st.obs.n_points; k++) {
                    double rx = st.obs.points[k].x_mm, ry = st.obs.points[k].y_mm;
                    double fx = st.x_mm + rx * c - ry * s, fy = st.y_mm + rx * s + ry * c;
                    double d = paint_dist(sc.field, fx, fy), r = hypot(rx, ry);
                    pts++;
                    CHECK(r <= sc.max_range_mm * 1.5 + 1);
                    if (d > worst)
                        worst = d;
                    if (r > 0 && d / r > worst_rel)
                        worst_rel = d / r;
                }
            }
            if (!noise)   /* on paint: half a line width + 1 mm of rounding */
                CHECK_LE(worst, 0.5 * sc.field->line_width_mm + 1.5);
            else          /* range and bearing noise: about 6 sigma of each */
                CHECK_LE(worst_rel, 6 * sc.range_sigma_pct / 100.0 + 6 * sc.bearing_sigma_deg * PI / 180 + 0.05);
            CHECK(full * 2 > frames);
            CHECK_EQ(differ, 0);
            t_info("%s noise %d: %ld frames, %ld full samples, %.1f points/frame, "
                   "farthest from paint %.1f mm (%.3f of range)", sim_builtin_names[i], noise,
                   frames, full, frames ? (double)pts / (double)frames : 0.0, worst, worst_rel);
        }
}

void suite_sim(void)
{
    t_run("sim.consistency", test_consistency);
    t_run("sim.odometry", test_odometry);
    t_run("sim.geometry_noiseless", test_geometry_noiseless);
    t_run("sim.field_of_view", test_field_of_view);
    t_run("sim.observation_noise", test_observation_noise);
    t_run("sim.events", test_events);
    t_run("sim.head", test_head);
    t_run("sim.scenario_text", test_scenario_text);
    t_run("sim.determinism", test_determinism);
    t_run("sim.fixtures", test_fixtures);
    t_run("sim.sequence", test_sequence);
    t_run("sim.others", test_others);
    t_run("sim.others_rendered", test_others_rendered);
    t_run("sim.white_points", test_white_points);
}

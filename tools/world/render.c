/*
 * tools/world/render.c - the synthetic field world: camera geometry, world
 * building (field paint, goals, beacons, robots, ball, a cluttered room) and
 * the ray caster that renders one frame with its class mask and field border.
 * Post-processing (lighting ramps, blur, noise, JPEG-like blocks, pixel
 * formats) and frame files are in render_post.c, the scene text form in
 * render_scene.c.  API: render.h.
 *
 * Algorithm.  One ray per pixel centre (camera.h conventions: the camera
 * frame has x optical, y left, z up; the ray of pixel (u, v) is
 * (f, cx - u, cy - v); R = Rz(yaw) Ry(total tilt) turns it into the robot
 * frame, the robot heading into the field frame).  The ray is intersected
 * with the ground plane, the room (four walls and a ceiling) and the
 * objects (oriented boxes, vertical cylinders, cylinders along y, spheres,
 * grouped under bounding boxes).  A ground point inside the carpet is line
 * paint when its signed distance to the paint (boundary/box/halfway lines as
 * rectangles of the true width with square corners, the centre circle as an
 * annulus, marks as crosses) is <= 0.  Pixels whose centre sample lies
 * within about a pixel footprint of a paint or carpet edge, or whose surface
 * differs from a 4-neighbour's, are re-rendered with n x n stratified
 * samples (anti-aliasing), more along u or v where the pixel's ground
 * footprint is large, so that a far line thinner than a pixel still gets
 * about three samples across (it fades instead of breaking into dashes);
 * the class mask keeps the centre sample.
 *
 * Invariants.  The mask at (u, v) is exactly the class of the ray through
 * the pixel centre; border_v[u] is the first row whose centre ray meets the
 * carpet (objects ignored).  All trigonometry comes from the firmware's
 * integer tables, all randomness from seeds: same scene -> same bytes.
 *
 * Colors (sRGB, measured by us on the 25 UvA 2013 frames in
 * ../shared/realdata, IntelligentRoboticsLab_Datasets_*.ppm, with a small
 * script: per-channel medians of pixel sets picked by simple rules):
 *   carpet  below row 130, G > R + 30 and G > B + 10: median (82, 141, 85),
 *           10%..90% (56,113,64)..(105,163,104), 752849 px
 *   line    below row 110, min > 170, max - min < 50: median (254, 253,
 *           250) (the tape saturates the sensor), 10% (207, 199, 189)
 *   yellow  R, G > 130, B < 90, |R - G| < 60: median (191, 185, 47),
 *           10%..90% (161,162,41)..(221,207,67), 42664 px
 * The carpet and line medians are the default albedos under nominal light
 * (gain 100); posts are cylinders shaded around the yellow median (their
 * albedo is scaled by 1/0.87, the mean shading of a lit cylinder, so the
 * average post pixel matches the measurement).
 *
 * Memory: render_frame allocates 8 doubles + 8 bytes per pixel of scratch
 * plus the outputs; the world holds a few hundred primitives.
 * Cost: O(pixels x primitives), dominated by the 3x3 edge supersampling;
 * four times as much at 640x480 as at 320x240 (timed by make bench).
 */
#include "world/render_int.h"
#include "world/render_cache.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- random numbers and trig ------------------------------------------------ */

void rnd_seed(rnd_t *r, uint64_t seed) { r->s = seed * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL; }

uint32_t rnd_u32(rnd_t *r)
{
    /* splitmix64 */
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return (uint32_t)(z >> 32);
}

double rnd_unit(rnd_t *r) { return rnd_u32(r) * (1.0 / 4294967296.0); }
double rnd_range(rnd_t *r, double lo, double hi) { return lo + (hi - lo) * rnd_unit(r); }

int rnd_int(rnd_t *r, int lo, int hi)
{
    uint32_t span = (uint32_t)(hi - lo) + 1u;
    return lo + (int)(rnd_u32(r) % span);
}

double rnd_gauss(rnd_t *r)
{
    /* Irwin-Hall of 4 uniforms: mean 2, variance 1/3 */
    /* one call per statement: the evaluation order of operands is
     * unspecified in C and differs between compilers/targets */
    double s = rnd_unit(r);
    s += rnd_unit(r);
    s += rnd_unit(r);
    s += rnd_unit(r);
    return (s - 2.0) * 1.7320508075688772;
}

uint32_t rnd_hash3(uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t h = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u ^ (c + 0x165667B1u) * 0xC2B2AE3Du;
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
}

double rsin(fl_angle_t a) { return fl_sin_q30(a) * (1.0 / 1073741824.0); }
double rcos(fl_angle_t a) { return fl_cos_q30(a) * (1.0 / 1073741824.0); }

/* Value noise in [-1, 1] on a square lattice of `cell` mm, smooth. */
static double vnoise(double x, double y, double cell, uint32_t seed)
{
    double fx = x / cell, fy = y / cell;
    double ix = floor(fx), iy = floor(fy);
    double tx = fx - ix, ty = fy - iy;
    int32_t xi = (int32_t)ix, yi = (int32_t)iy;
    double a, b, c, d;
    a = rnd_hash3((uint32_t)xi, (uint32_t)yi, seed) * (2.0 / 4294967295.0) - 1.0;
    b = rnd_hash3((uint32_t)(xi + 1), (uint32_t)yi, seed) * (2.0 / 4294967295.0) - 1.0;
    c = rnd_hash3((uint32_t)xi, (uint32_t)(yi + 1), seed) * (2.0 / 4294967295.0) - 1.0;
    d = rnd_hash3((uint32_t)(xi + 1), (uint32_t)(yi + 1), seed) * (2.0 / 4294967295.0) - 1.0;
    tx = tx * tx * (3.0 - 2.0 * tx);
    ty = ty * ty * (3.0 - 2.0 * ty);
    return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

static double smooth01(double t)
{
    if (t <= 0.0)
        return 0.0;
    if (t >= 1.0)
        return 1.0;
    return t * t * (3.0 - 2.0 * t);
}

/* ---- colors ------------------------------------------------------------------- */

const uint8_t render_color_carpet[3] = {82, 141, 85};
const uint8_t render_color_line[3] = {254, 253, 250};
const uint8_t render_color_goal_yellow[3] = {191, 185, 47};

static void set_rgb(double out[3], double r, double g, double b)
{
    out[0] = r;
    out[1] = g;
    out[2] = b;
}

static void color_rgb(fl_color_t c, double out[3])
{
    switch (c) {
    case FL_COLOR_YELLOW:
        set_rgb(out, render_color_goal_yellow[0] / 0.87, render_color_goal_yellow[1] / 0.87,
                render_color_goal_yellow[2] / 0.87);
        break;
    case FL_COLOR_WHITE: set_rgb(out, 250, 250, 246); break;
    case FL_COLOR_SKYBLUE: set_rgb(out, 80, 175, 230); break;
    case FL_COLOR_PINK: set_rgb(out, 245, 90, 170); break;
    default: set_rgb(out, 128, 128, 128); break;
    }
}

/* ---- scene ----------------------------------------------------------------------- */

static int is_aibo_camera(const fl_camera_model_t *m)
{
    return m && m->name && strncmp(m->name, "aibo", 4) == 0;
}

void render_scene_default(render_scene_t *sc, const fl_field_t *field,
                          const fl_camera_model_t *camera)
{
    if (!sc)
        return;
    memset(sc, 0, sizeof *sc);
    sc->field = field;
    sc->camera = camera;
    sc->format = FL_FMT_RGB888;
    /* the camera's default stance (catalogue), else typical values */
    if (camera && camera->default_neck_height_mm >= FL_CAMERA_NECK_MIN_MM &&
        camera->default_neck_height_mm <= FL_CAMERA_NECK_MAX_MM) {
        sc->head.neck_height_mm = camera->default_neck_height_mm;
        sc->head.pitch_offset = camera->default_pitch_offset;
    } else {
        sc->head.neck_height_mm = is_aibo_camera(camera) ? 160 : 450;
    }
    /* a humanoid with a level-mounted head camera (acyut-640) looks down
     * by its head pitch: 20 deg puts the ground from about 0.5 m to the
     * horizon in view (a NAO's tilt is in its mount instead) */
    if (camera && camera->name && strncmp(camera->name, "acyut", 5) == 0)
        sc->head.head_pitch = RENDER_HUMANOID_HEAD_PITCH;
    sc->seed = 1;
    sc->world_seed = 1;
    sc->background = 1;
    sc->gain_pct = 100;
    sc->shadows = 1;
    sc->noise_x10 = 15;
    sc->supersample = 3;
}

const char *render_field_camera(const fl_field_t *field)
{
    if (field && field->name && strcmp(field->name, "hl3x2") == 0)
        return "acyut-640";
    return NULL;
}

fl_status_t render_scene_camera(const render_scene_t *sc, fl_camera_t *cam)
{
    if (!sc || !cam)
        return FL_ERR_NULL;
    return fl_camera_init(cam, sc->camera, &sc->head);
}

/* ---- world: primitives ---------------------------------------------------------------- */

static prim_t *add_prim(world_t *w)
{
    prim_t *p;
    if (w->np == w->pcap) {
        int ncap = w->pcap ? 2 * w->pcap : 256;
        prim_t *np = (prim_t *)realloc(w->prims, (size_t)ncap * sizeof *np);
        if (!np)
            return NULL;
        w->prims = np;
        w->pcap = ncap;
    }
    p = &w->prims[w->np++];
    memset(p, 0, sizeof *p);
    p->landmark = -1;
    p->cs = 1.0;
    return p;
}

static void prim_bounds(const prim_t *p, double lo[3], double hi[3])
{
    int i;
    double e[3];
    switch (p->type) {
    case PR_BOX:
        e[0] = fabs(p->cs) * p->h[0] + fabs(p->sn) * p->h[1];
        e[1] = fabs(p->sn) * p->h[0] + fabs(p->cs) * p->h[1];
        e[2] = p->h[2];
        for (i = 0; i < 3; i++) {
            lo[i] = p->c[i] - e[i];
            hi[i] = p->c[i] + e[i];
        }
        break;
    case PR_VCYL:
        lo[0] = p->c[0] - p->h[0];
        hi[0] = p->c[0] + p->h[0];
        lo[1] = p->c[1] - p->h[0];
        hi[1] = p->c[1] + p->h[0];
        lo[2] = p->c[2];
        hi[2] = p->h[1];
        break;
    case PR_HCYLY:
        lo[0] = p->c[0] - p->h[0];
        hi[0] = p->c[0] + p->h[0];
        lo[1] = p->h[1];
        hi[1] = p->h[2];
        lo[2] = p->c[2] - p->h[0];
        hi[2] = p->c[2] + p->h[0];
        break;
    default:
        for (i = 0; i < 3; i++) {
            lo[i] = p->c[i] - p->h[0];
            hi[i] = p->c[i] + p->h[0];
        }
        break;
    }
}

static void group_begin(world_t *w)
{
    if (w->ng == w->gcap) {
        int ncap = w->gcap ? 2 * w->gcap : 64;
        group_t *ng = (group_t *)realloc(w->groups, (size_t)ncap * sizeof *ng);
        if (!ng)
            return;
        w->groups = ng;
        w->gcap = ncap;
    }
    w->groups[w->ng].first = w->np;
    w->groups[w->ng].count = 0;
}

static void group_end(world_t *w)
{
    group_t *g;
    int i, k;
    if (w->ng >= w->gcap)
        return;
    g = &w->groups[w->ng];
    g->count = w->np - g->first;
    if (g->count <= 0)
        return;
    for (i = g->first; i < w->np; i++) {
        double lo[3], hi[3];
        prim_bounds(&w->prims[i], lo, hi);
        for (k = 0; k < 3; k++) {
            if (i == g->first || lo[k] < g->lo[k])
                g->lo[k] = lo[k];
            if (i == g->first || hi[k] > g->hi[k])
                g->hi[k] = hi[k];
        }
    }
    w->ng++;
}

/* Local placement frame of an object: origin (ox, oy), own x axis (cs, sn). */
typedef struct {
    double ox, oy, cs, sn;
} frame2_t;

static void f2_point(const frame2_t *F, double lx, double ly, double *x, double *y)
{
    *x = F->ox + F->cs * lx - F->sn * ly;
    *y = F->oy + F->sn * lx + F->cs * ly;
}

static prim_t *box_l(world_t *w, const frame2_t *F, double lx, double ly, double z0, double z1,
                     double hx, double hy, const double rgb[3], int cls, int tex)
{
    prim_t *p = add_prim(w);
    if (!p)
        return NULL;
    p->type = PR_BOX;
    f2_point(F, lx, ly, &p->c[0], &p->c[1]);
    p->c[2] = 0.5 * (z0 + z1);
    p->h[0] = hx;
    p->h[1] = hy;
    p->h[2] = 0.5 * (z1 - z0);
    p->cs = F->cs;
    p->sn = F->sn;
    memcpy(p->rgb, rgb, sizeof p->rgb);
    p->cls = cls;
    p->tex = tex;
    return p;
}

static prim_t *vcyl_l(world_t *w, const frame2_t *F, double lx, double ly, double z0, double z1,
                      double r, const double rgb[3], int cls, int tex)
{
    prim_t *p = add_prim(w);
    if (!p)
        return NULL;
    p->type = PR_VCYL;
    f2_point(F, lx, ly, &p->c[0], &p->c[1]);
    p->c[2] = z0;
    p->h[0] = r;
    p->h[1] = z1;
    memcpy(p->rgb, rgb, sizeof p->rgb);
    p->cls = cls;
    p->tex = tex;
    return p;
}

static prim_t *sphere_l(world_t *w, const frame2_t *F, double lx, double ly, double z, double r,
                        const double rgb[3], int cls, int tex)
{
    prim_t *p = add_prim(w);
    if (!p)
        return NULL;
    p->type = PR_SPHERE;
    f2_point(F, lx, ly, &p->c[0], &p->c[1]);
    p->c[2] = z;
    p->h[0] = r;
    memcpy(p->rgb, rgb, sizeof p->rgb);
    p->cls = cls;
    p->tex = tex;
    return p;
}

/* ---- world: intersections --------------------------------------------------------- */

/* Ray o + t d, t in (tmin, tmax).  Each returns 1 with *t and the outward
 * unit normal n when hit. */
static int hit_box(const prim_t *p, const double o[3], const double d[3], double tmin, double tmax,
                   double *t, double n[3])
{
    double lo[3], ld[3], t0 = tmin, t1 = tmax;
    int axis = -1, k;
    double sgn = 0;
    double ox = o[0] - p->c[0], oy = o[1] - p->c[1];
    lo[0] = p->cs * ox + p->sn * oy;
    lo[1] = -p->sn * ox + p->cs * oy;
    lo[2] = o[2] - p->c[2];
    ld[0] = p->cs * d[0] + p->sn * d[1];
    ld[1] = -p->sn * d[0] + p->cs * d[1];
    ld[2] = d[2];
    for (k = 0; k < 3; k++) {
        double inv, ta, tb, s = -1.0;
        if (ld[k] == 0.0) {
            if (lo[k] < -p->h[k] || lo[k] > p->h[k])
                return 0;
            continue;
        }
        inv = 1.0 / ld[k];
        ta = (-p->h[k] - lo[k]) * inv;
        tb = (p->h[k] - lo[k]) * inv;
        if (ta > tb) {
            double tmp = ta;
            ta = tb;
            tb = tmp;
            s = 1.0;
        }
        if (ta > t0) {
            t0 = ta;
            axis = k;
            sgn = s;
        }
        if (tb < t1)
            t1 = tb;
        if (t0 > t1)
            return 0;
    }
    if (axis < 0)
        return 0; /* origin inside the box */
    *t = t0;
    if (axis == 2) {
        n[0] = 0;
        n[1] = 0;
        n[2] = sgn;
    } else if (axis == 0) {
        n[0] = sgn * p->cs;
        n[1] = sgn * p->sn;
        n[2] = 0;
    } else {
        n[0] = -sgn * p->sn;
        n[1] = sgn * p->cs;
        n[2] = 0;
    }
    return 1;
}

/* Circle in the (a, b) plane: smallest root of |o + t d|^2 = r^2 in range. */
static int circle_roots(double oa, double ob, double da, double db, double r, double *t0,
                        double *t1)
{
    double A = da * da + db * db, B = oa * da + ob * db, C = oa * oa + ob * ob - r * r, D, s;
    if (A <= 0.0)
        return 0;
    D = B * B - A * C;
    if (D < 0.0)
        return 0;
    s = sqrt(D);
    *t0 = (-B - s) / A;
    *t1 = (-B + s) / A;
    return 1;
}

static int hit_vcyl(const prim_t *p, const double o[3], const double d[3], double tmin, double tmax,
                    double *t, double n[3])
{
    double ox = o[0] - p->c[0], oy = o[1] - p->c[1], r = p->h[0], ta, tb, best = tmax;
    int hit = 0;
    if (circle_roots(ox, oy, d[0], d[1], r, &ta, &tb)) {
        if (ta > tmin && ta < best) {
            double z = o[2] + ta * d[2];
            if (z >= p->c[2] && z <= p->h[1]) {
                best = ta;
                n[0] = (ox + ta * d[0]) / r;
                n[1] = (oy + ta * d[1]) / r;
                n[2] = 0;
                hit = 1;
            }
        }
    }
    if (d[2] != 0.0) {
        /* caps */
        double zc[2];
        int k;
        zc[0] = p->h[1];
        zc[1] = p->c[2];
        for (k = 0; k < 2; k++) {
            double tc = (zc[k] - o[2]) / d[2], x, y;
            if (tc <= tmin || tc >= best)
                continue;
            if ((k == 0 && d[2] > 0) || (k == 1 && d[2] < 0))
                continue; /* back face */
            x = ox + tc * d[0];
            y = oy + tc * d[1];
            if (x * x + y * y <= r * r) {
                best = tc;
                n[0] = 0;
                n[1] = 0;
                n[2] = k == 0 ? 1.0 : -1.0;
                hit = 1;
            }
        }
    }
    if (hit)
        *t = best;
    return hit;
}

static int hit_hcyly(const prim_t *p, const double o[3], const double d[3], double tmin,
                     double tmax, double *t, double n[3])
{
    double ox = o[0] - p->c[0], oz = o[2] - p->c[2], r = p->h[0], ta, tb, best = tmax;
    int hit = 0;
    if (circle_roots(ox, oz, d[0], d[2], r, &ta, &tb)) {
        if (ta > tmin && ta < best) {
            double y = o[1] + ta * d[1];
            if (y >= p->h[1] && y <= p->h[2]) {
                best = ta;
                n[0] = (ox + ta * d[0]) / r;
                n[1] = 0;
                n[2] = (oz + ta * d[2]) / r;
                hit = 1;
            }
        }
    }
    if (d[1] != 0.0) {
        double yc[2];
        int k;
        yc[0] = p->h[1];
        yc[1] = p->h[2];
        for (k = 0; k < 2; k++) {
            double tc = (yc[k] - o[1]) / d[1], x, z;
            if (tc <= tmin || tc >= best)
                continue;
            x = ox + tc * d[0];
            z = oz + tc * d[2];
            if (x * x + z * z <= r * r) {
                best = tc;
                n[0] = 0;
                n[1] = k == 0 ? -1.0 : 1.0;
                n[2] = 0;
                hit = 1;
            }
        }
    }
    if (hit)
        *t = best;
    return hit;
}

static int hit_sphere(const prim_t *p, const double o[3], const double d[3], double tmin,
                      double tmax, double *t, double n[3])
{
    double oc[3], A, B, C, D, s, tt, r = p->h[0];
    int k;
    for (k = 0; k < 3; k++)
        oc[k] = o[k] - p->c[k];
    A = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    B = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    C = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r;
    D = B * B - A * C;
    if (D < 0.0)
        return 0;
    s = sqrt(D);
    tt = (-B - s) / A;
    if (tt <= tmin || tt >= tmax)
        return 0;
    *t = tt;
    for (k = 0; k < 3; k++)
        n[k] = (oc[k] + tt * d[k]) / r;
    return 1;
}

static int hit_prim(const prim_t *p, const double o[3], const double d[3], double tmin,
                    double tmax, double *t, double n[3])
{
    switch (p->type) {
    case PR_BOX: return hit_box(p, o, d, tmin, tmax, t, n);
    case PR_VCYL: return hit_vcyl(p, o, d, tmin, tmax, t, n);
    case PR_HCYLY: return hit_hcyly(p, o, d, tmin, tmax, t, n);
    default: return hit_sphere(p, o, d, tmin, tmax, t, n);
    }
}

static int hit_aabb(const group_t *g, const double o[3], const double d[3], double tmin,
                    double tmax)
{
    int k;
    for (k = 0; k < 3; k++) {
        double ta, tb;
        if (d[k] == 0.0) {
            if (o[k] < g->lo[k] || o[k] > g->hi[k])
                return 0;
            continue;
        }
        ta = (g->lo[k] - o[k]) / d[k];
        tb = (g->hi[k] - o[k]) / d[k];
        if (ta > tb) {
            double tmp = ta;
            ta = tb;
            tb = tmp;
        }
        if (ta > tmin)
            tmin = ta;
        if (tb < tmax)
            tmax = tb;
        if (tmin > tmax)
            return 0;
    }
    return 1;
}

/* uv: the pixel whose ray from the camera centre d is (world_ray), or NULL
 * for any other ray; with it, the groups behind the camera or whose pixel
 * box (group_t) lies away from the pixel are skipped: their hit_aabb would
 * be 0 (the ray misses the box by 10 mm or a pixel, orders of magnitude
 * above rounding), so the result is the same, bit for bit. */
static int hit_objects_n(const world_t *w, const double o[3], const double d[3], double tmin,
                         double tmax, int skip_landmark, double *t_out, double n_out[3],
                         const double *uv)
{
    int gi, i, best = -1;
    double tb = tmax, t, n[3];
    for (gi = 0; gi < w->ng; gi++) {
        const group_t *g = &w->groups[gi];
        if (uv && g->on_screen &&
            (g->on_screen == 2 || uv[0] < g->u0 || uv[0] > g->u1 || uv[1] < g->v0 || uv[1] > g->v1))
            continue;
        if (!hit_aabb(g, o, d, tmin, tb))
            continue;
        for (i = g->first; i < g->first + g->count; i++) {
            const prim_t *p = &w->prims[i];
            if (skip_landmark >= 0 && p->landmark == skip_landmark)
                continue;
            if (hit_prim(p, o, d, tmin, tb, &t, n)) {
                tb = t;
                best = i;
                if (n_out)
                    memcpy(n_out, n, sizeof n);
            }
        }
    }
    if (best >= 0 && t_out)
        *t_out = tb;
    return best;
}

int world_hit_objects(const world_t *w, const double o[3], const double d[3], double tmin,
                      double tmax, int skip_landmark, double *t_out)
{
    return hit_objects_n(w, o, d, tmin, tmax, skip_landmark, t_out, NULL, NULL);
}

/* ---- world: paint ------------------------------------------------------------------ */

/* Signed distance to a rectangle centred at (cx, cy) with half sizes (a, b),
 * axes along (ux, uy) and (-uy, ux). */
static double rect_sd(double x, double y, double cx, double cy, double ux, double uy, double a,
                      double b)
{
    double dx = x - cx, dy = y - cy;
    double s = fabs(dx * ux + dy * uy) - a, n = fabs(-dx * uy + dy * ux) - b;
    double ms = s > 0 ? s : 0, mn = n > 0 ? n : 0, inner = s > n ? s : n;
    if (inner > 0)
        return ms > 0 && mn > 0 ? sqrt(ms * ms + mn * mn) : inner;
    return inner;
}

double world_paint_sd(const world_t *w, double x, double y)
{
    const fl_field_t *f = w->field;
    double best = 1e9, sd;
    int i;
    for (i = 0; i < f->n_lines; i++) {
        const fl_field_line_t *l = &f->lines[i];
        double dx = l->x1_mm - l->x0_mm, dy = l->y1_mm - l->y0_mm, len;
        double cxl = 0.5 * (l->x0_mm + l->x1_mm), cyl = 0.5 * (l->y0_mm + l->y1_mm);
        /* quick reject (before the square root: most lines are far) */
        if (fabs(x - cxl) > 0.5 * fabs(dx) + w->lw2 + best + 1.0 ||
            fabs(y - cyl) > 0.5 * fabs(dy) + w->lw2 + best + 1.0)
            continue;
        len = sqrt(dx * dx + dy * dy);
        if (len <= 0.0)
            continue;
        sd = rect_sd(x, y, cxl, cyl, dx / len, dy / len, 0.5 * len + w->lw2, w->lw2);
        if (sd < best)
            best = sd;
    }
    if (f->circle_radius_mm > 0) {
        sd = fabs(sqrt(x * x + y * y) - f->circle_radius_mm) - w->lw2;
        if (sd < best)
            best = sd;
    }
    if (f->mark_size_mm > 0) {
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            if (lm->kind != FL_LM_PENALTY_MARK && lm->kind != FL_LM_CENTRE_MARK)
                continue;
            sd = rect_sd(x, y, lm->x_mm, lm->y_mm, 1, 0, w->mark2, w->lw2);
            if (sd < best)
                best = sd;
            sd = rect_sd(x, y, lm->x_mm, lm->y_mm, 1, 0, w->lw2, w->mark2);
            if (sd < best)
                best = sd;
        }
    }
    return best;
}

/* ---- world: the room and its clutter ------------------------------------------------ */

typedef struct {
    double r, g, b;
} c3_t;

static void pick(rnd_t *r, const c3_t *tab, int n, double out[3])
{
    const c3_t *c = &tab[rnd_int(r, 0, n - 1)];
    double k = rnd_range(r, 0.9, 1.08);
    out[0] = c->r * k;
    out[1] = c->g * k;
    out[2] = c->b * k;
}

static const c3_t shirts[] = {
    {200, 40, 45}, {40, 60, 150}, {235, 235, 230}, {70, 150, 70}, {220, 200, 50},
    {30, 30, 35}, {120, 120, 125}, {150, 90, 160}, {240, 240, 240}, {90, 170, 90},
    {230, 215, 90}, {200, 120, 60}};
static const c3_t trousers[] = {{40, 45, 70}, {30, 30, 32}, {150, 130, 100}, {70, 80, 110}, {90, 90, 95}};
static const c3_t skins[] = {{225, 180, 150}, {200, 150, 115}, {150, 105, 75}, {240, 205, 180}};
static const c3_t hairs[] = {{40, 30, 25}, {90, 60, 35}, {200, 170, 110}, {20, 20, 20}};
static const c3_t furn[] = {{235, 235, 230}, {200, 200, 200}, {140, 110, 80}, {70, 70, 75}, {215, 205, 180}};
static const c3_t chairs[] = {{30, 30, 35}, {170, 40, 40}, {50, 80, 160}, {60, 130, 70}, {40, 40, 45}};
static const c3_t couches[] = {{60, 120, 170}, {70, 140, 80}, {150, 60, 50}, {120, 120, 125}};
static const c3_t boxcols[] = {{225, 205, 50}, {170, 130, 80}, {240, 240, 235}, {200, 180, 60}};
static const c3_t bagcols[] = {{30, 30, 40}, {60, 90, 150}, {120, 40, 40}, {90, 130, 70}};
static const c3_t books[] = {{180, 40, 40}, {40, 80, 160}, {220, 200, 60}, {60, 140, 70}, {230, 230, 225}, {40, 40, 40}};

static void add_person(world_t *w, rnd_t *r, const frame2_t *F, int seated)
{
    double shirt[3], trouser[3], skin[3], hair[3], z0 = seated ? 0 : 0;
    const int B = RENDER_CLASS_BACKGROUND;
    pick(r, shirts, (int)(sizeof shirts / sizeof shirts[0]), shirt);
    pick(r, trousers, (int)(sizeof trousers / sizeof trousers[0]), trouser);
    pick(r, skins, (int)(sizeof skins / sizeof skins[0]), skin);
    pick(r, hairs, (int)(sizeof hairs / sizeof hairs[0]), hair);
    if (!seated) {
        box_l(w, F, 0, 100, z0, 880, 70, 70, trouser, B, TEX_FABRIC);
        box_l(w, F, 0, -100, z0, 880, 70, 70, trouser, B, TEX_FABRIC);
        box_l(w, F, 0, 0, 860, 1460, 115, 200, shirt, B, TEX_FABRIC);
        box_l(w, F, 0, 245, 880, 1420, 50, 45, shirt, B, TEX_FABRIC);
        box_l(w, F, 0, -245, 880, 1420, 50, 45, shirt, B, TEX_FABRIC);
        sphere_l(w, F, 0, 0, 1575, 105, skin, B, TEX_NONE);
        sphere_l(w, F, -20, 0, 1610, 100, hair, B, TEX_FABRIC);
    } else {
        double chair[3];
        pick(r, chairs, (int)(sizeof chairs / sizeof chairs[0]), chair);
        box_l(w, F, 0, 0, 430, 480, 230, 230, chair, B, TEX_NONE);
        box_l(w, F, -230, 0, 480, 1000, 25, 220, chair, B, TEX_NONE);
        vcyl_l(w, F, 0, 0, 60, 430, 25, chair, B, TEX_NONE);
        box_l(w, F, 0, 0, 20, 70, 300, 40, chair, B, TEX_NONE);
        box_l(w, F, 0, 0, 20, 70, 40, 300, chair, B, TEX_NONE);
        box_l(w, F, 150, 100, 480, 600, 200, 75, trouser, B, TEX_FABRIC);
        box_l(w, F, 150, -100, 480, 600, 200, 75, trouser, B, TEX_FABRIC);
        box_l(w, F, 330, 100, 0, 480, 60, 60, trouser, B, TEX_FABRIC);
        box_l(w, F, 330, -100, 0, 480, 60, 60, trouser, B, TEX_FABRIC);
        box_l(w, F, -40, 0, 590, 1150, 110, 200, shirt, B, TEX_FABRIC);
        box_l(w, F, 60, 245, 700, 1120, 50, 45, shirt, B, TEX_FABRIC);
        box_l(w, F, 60, -245, 700, 1120, 50, 45, shirt, B, TEX_FABRIC);
        sphere_l(w, F, -30, 0, 1265, 105, skin, B, TEX_NONE);
        sphere_l(w, F, -50, 0, 1300, 100, hair, B, TEX_FABRIC);
    }
}

/* One piece of room clutter; local x points toward the field.  Returns the
 * depth (along local x) it occupies. */
static void add_clutter(world_t *w, rnd_t *r, const frame2_t *F, int type)
{
    const int B = RENDER_CLASS_BACKGROUND;
    double c[3], c2[3];
    int i;
    switch (type) {
    case 0: /* desk with a seated person */
    case 1: /* desk */
        pick(r, furn, (int)(sizeof furn / sizeof furn[0]), c);
        box_l(w, F, 0, 0, 720, 750, 350, 700, c, B, TEX_GRAIN);
        for (i = 0; i < 4; i++)
            box_l(w, F, (i & 1) ? 310 : -310, (i & 2) ? 660 : -660, 0, 720, 20, 20, c, B, TEX_NONE);
        set_rgb(c2, 35, 35, 40);
        box_l(w, F, -150, rnd_range(r, -300, 300), 760, 1130, 20, 260, c2, B, TEX_NONE);
        if (type == 0) {
            frame2_t P = *F;
            f2_point(F, 650, rnd_range(r, -300, 300), &P.ox, &P.oy);
            P.cs = -F->cs;
            P.sn = -F->sn; /* facing the desk */
            add_person(w, r, &P, 1);
        }
        break;
    case 2: { /* cabinet, maybe with books */
        double h = rnd_range(r, 900, 1900);
        pick(r, furn, (int)(sizeof furn / sizeof furn[0]), c);
        box_l(w, F, 0, 0, 0, h, 200, 400, c, B, TEX_GRAIN);
        if (rnd_unit(r) < 0.6) {
            double y = -370;
            while (y < 360) {
                double bw = rnd_range(r, 20, 60);
                pick(r, books, (int)(sizeof books / sizeof books[0]), c2);
                box_l(w, F, 205, y + bw * 0.5, h * 0.55, h * 0.55 + rnd_range(r, 180, 260), 8,
                      bw * 0.5, c2, B, TEX_NONE);
                y += bw + 2;
            }
        }
        break;
    }
    case 3: /* couch */
        pick(r, couches, (int)(sizeof couches / sizeof couches[0]), c);
        box_l(w, F, 0, 0, 60, 420, 400, 900, c, B, TEX_FABRIC);
        box_l(w, F, -320, 0, 420, 800, 80, 900, c, B, TEX_FABRIC);
        box_l(w, F, 0, 860, 420, 620, 400, 60, c, B, TEX_FABRIC);
        box_l(w, F, 0, -860, 420, 620, 400, 60, c, B, TEX_FABRIC);
        if (rnd_unit(r) < 0.5) { /* robots lying on the couch (white decoys) */
            set_rgb(c2, 230, 230, 232);
            for (i = 0; i < 3; i++)
                box_l(w, F, 50, -400 + 300 * i, 420, 540, 150, 110, c2, B, TEX_NONE);
        }
        break;
    case 4: { /* office chair */
        pick(r, chairs, (int)(sizeof chairs / sizeof chairs[0]), c);
        box_l(w, F, 0, 0, 430, 490, 230, 230, c, B, TEX_FABRIC);
        box_l(w, F, -210, 0, 490, 1000, 25, 220, c, B, TEX_FABRIC);
        set_rgb(c2, 120, 120, 125);
        vcyl_l(w, F, 0, 0, 60, 430, 25, c2, B, TEX_NONE);
        box_l(w, F, 0, 0, 20, 60, 300, 30, c2, B, TEX_NONE);
        box_l(w, F, 0, 0, 20, 60, 30, 300, c2, B, TEX_NONE);
        break;
    }
    case 5: /* standing person */
        add_person(w, r, F, 0);
        break;
    case 6: /* bin: green or grey */
        if (rnd_unit(r) < 0.7)
            set_rgb(c, 60, 150, 75);
        else
            set_rgb(c, 130, 130, 135);
        {
            double h = rnd_range(r, 450, 700), rad = rnd_range(r, 150, 220);
            vcyl_l(w, F, 0, 0, 0, h, rad, c, B, TEX_GRAIN);
        }
        break;
    case 7: { /* boxes: yellow, cardboard, white */
        int n = rnd_int(r, 1, 3);
        double z = 0;
        for (i = 0; i < n; i++) {
            double hh = rnd_range(r, 200, 400);
            pick(r, boxcols, (int)(sizeof boxcols / sizeof boxcols[0]), c);
            double ox = rnd_range(r, -40, 40), oy = rnd_range(r, -40, 40);
            double hx = rnd_range(r, 150, 280), hy = rnd_range(r, 150, 300);
            box_l(w, F, ox, oy, z, z + hh, hx, hy, c, B, TEX_GRAIN);
            z += hh;
        }
        break;
    }
    case 8: /* printer on a low cabinet */
        set_rgb(c, 200, 200, 200);
        box_l(w, F, 0, 0, 0, 700, 280, 300, c, B, TEX_GRAIN);
        set_rgb(c2, 238, 238, 235);
        box_l(w, F, 0, 0, 700, 1080, 250, 260, c2, B, TEX_GRAIN);
        break;
    case 9: /* bag */
        pick(r, bagcols, (int)(sizeof bagcols / sizeof bagcols[0]), c);
        box_l(w, F, 0, 0, 0, rnd_range(r, 300, 450), 120, 180, c, B, TEX_FABRIC);
        break;
    default: /* plant */
        set_rgb(c, 150, 90, 60);
        vcyl_l(w, F, 0, 0, 0, 350, 160, c, B, TEX_GRAIN);
        set_rgb(c2, 55, 125, 50);
        sphere_l(w, F, 0, 0, 720, 360, c2, B, TEX_FABRIC);
        break;
    }
}

/* Wall decoration, flush with the wall; F's local x points into the room. */
static void add_wall_decor(world_t *w, rnd_t *r, const frame2_t *F, int type)
{
    const int B = RENDER_CLASS_BACKGROUND;
    double c[3];
    switch (type) {
    case 0: /* whiteboard */
        set_rgb(c, 240, 240, 238);
        box_l(w, F, 15, 0, 900, 2100, 15, 900, c, B, TEX_NONE);
        break;
    case 1: /* poster: green or yellow */
        if (rnd_unit(r) < 0.5)
            set_rgb(c, 80, 160, 80);
        else
            set_rgb(c, 230, 210, 60);
        {
            double h = rnd_range(r, 600, 1000), hw = rnd_range(r, 250, 450);
            box_l(w, F, 10, 0, 1000, 1000 + h, 10, hw, c, B, TEX_GRAIN);
        }
        break;
    case 2: /* window: bright */
        set_rgb(c, 250, 252, 255);
        box_l(w, F, 10, 0, 900, 2300, 10, rnd_range(r, 600, 900), c, B, TEX_NONE);
        break;
    default: /* door */
        set_rgb(c, 140, 100, 65);
        box_l(w, F, 10, 0, 0, 2100, 10, 450, c, B, TEX_GRAIN);
        break;
    }
}

static void build_room(world_t *w, rnd_t *r)
{
    int side;
    for (side = 0; side < 4; side++) {
        /* side 0: +x end, 1: -x end, 2: +y side, 3: -y side */
        double wall = side < 2 ? w->room_hx : w->room_hy;
        double carpet = side < 2 ? w->carpet_hx : w->carpet_hy;
        double half_len = side < 2 ? w->room_hy : w->room_hx;
        double band = wall - carpet;
        double nx = side == 0 ? -1 : side == 1 ? 1 : 0, ny = side == 2 ? -1 : side == 3 ? 1 : 0;
        double s;
        /* along-wall axis (ax, ay) */
        double ax = -ny, ay = nx;
        /* a cleared side still draws its pieces from r and then drops them,
         * so the other sides keep their clutter */
        int clear = (w->sc->clear_sides >> side) & 1;
        int np0, ng0;
        frame2_t F;
        if (!w->sc->background)
            continue;
        /* wall decorations */
        s = -half_len + rnd_range(r, 200, 1500);
        while (s < half_len - 600) {
            F.cs = nx;
            F.sn = ny;
            F.ox = -nx * wall + ax * s;
            F.oy = -ny * wall + ay * s;
            np0 = w->np;
            ng0 = w->ng;
            group_begin(w);
            add_wall_decor(w, r, &F, rnd_int(r, 0, 3));
            group_end(w);
            if (clear) {
                w->np = np0;
                w->ng = ng0;
            }
            s += rnd_range(r, 1500, 3500);
        }
        /* floor clutter */
        s = -half_len + rnd_range(r, 100, 800);
        while (s < half_len - 400) {
            int type;
            double u = rnd_unit(r), depth_from_wall;
            fl_angle_t jitter;
            if (u < 0.12) type = 0;
            else if (u < 0.2) type = 1;
            else if (u < 0.3) type = 2;
            else if (u < 0.36) type = 3;
            else if (u < 0.44) type = 4;
            else if (u < 0.6) type = 5;
            else if (u < 0.68) type = 6;
            else if (u < 0.78) type = 7;
            else if (u < 0.83) type = 8;
            else if (u < 0.92) type = 9;
            else type = 10;
            /* distance of the object centre from the wall */
            if (type == 5 || type == 6 || type == 7 || type == 9)
                depth_from_wall = rnd_range(r, 300, band - 250 > 300 ? band - 250 : 300);
            else
                depth_from_wall = rnd_range(r, 350, 500);
            if (depth_from_wall > band - 200)
                depth_from_wall = band - 200;
            if (depth_from_wall < 150)
                depth_from_wall = 150;
            jitter = (fl_angle_t)rnd_int(r, -1500, 1500);
            if (type == 5 || type == 4)
                jitter = (fl_angle_t)rnd_int(r, -9000, 9000);
            {
                double c0 = nx, s0 = ny, cj = rcos(jitter), sj = rsin(jitter);
                F.cs = c0 * cj - s0 * sj;
                F.sn = s0 * cj + c0 * sj;
            }
            F.ox = -nx * (wall - depth_from_wall) + ax * s;
            F.oy = -ny * (wall - depth_from_wall) + ay * s;
            np0 = w->np;
            ng0 = w->ng;
            group_begin(w);
            add_clutter(w, r, &F, type);
            group_end(w);
            if (clear) {
                w->np = np0;
                w->ng = ng0;
            }
            s += rnd_range(r, 900, 2200);
        }
    }
}

/* ---- world: field objects ------------------------------------------------------------ */

static void build_goals(world_t *w)
{
    const fl_field_t *f = w->field;
    double rpost = 0.5 * f->post_diameter_mm, h = f->post_height_mm;
    int i, goal;
    frame2_t F = {0, 0, 1, 0};
    for (goal = -1; goal <= 1; goal += 2) {
        double gx = 0, ymin = 1e9, ymax = -1e9, rgb[3] = {128, 128, 128};
        int n = 0;
        group_begin(w);
        for (i = 0; i < f->n_landmarks; i++) {
            const fl_landmark_t *lm = &f->landmarks[i];
            prim_t *p;
            if (lm->kind != FL_LM_POST || lm->goal != goal)
                continue;
            color_rgb(lm->color, rgb);
            F.ox = lm->x_mm;
            F.oy = lm->y_mm;
            p = vcyl_l(w, &F, 0, 0, 0, h, rpost, rgb, RENDER_CLASS_GOAL, TEX_GRAIN);
            if (p)
                p->landmark = i;
            gx = lm->x_mm;
            if (lm->y_mm < ymin) ymin = lm->y_mm;
            if (lm->y_mm > ymax) ymax = lm->y_mm;
            n++;
        }
        if (n == 2) {
            prim_t *p = add_prim(w);
            if (p) {
                p->type = PR_HCYLY;
                p->c[0] = gx;
                p->c[2] = h - rpost;
                p->h[0] = rpost;
                p->h[1] = ymin;
                p->h[2] = ymax;
                memcpy(p->rgb, rgb, sizeof rgb);
                p->cls = RENDER_CLASS_GOAL;
                p->tex = TEX_GRAIN;
            }
            if (w->aibo) {
                /* AIBO goals: colored back and side panels */
                double sgn = gx > 0 ? 1 : -1, back = fabs(gx) + 140;
                F.ox = sgn * (0.5 * (fabs(gx) + back));
                F.oy = 0;
                box_l(w, &F, 0, ymax, 0, h, 0.5 * (back - fabs(gx)), 8, rgb, RENDER_CLASS_GOAL, TEX_GRAIN);
                box_l(w, &F, 0, ymin, 0, h, 0.5 * (back - fabs(gx)), 8, rgb, RENDER_CLASS_GOAL, TEX_GRAIN);
                F.ox = sgn * back;
                box_l(w, &F, 0, 0, 0, h, 8, ymax, rgb, RENDER_CLASS_GOAL, TEX_GRAIN);
            }
        }
        group_end(w);
    }
}

static void build_beacons(world_t *w)
{
    const fl_field_t *f = w->field;
    int i;
    frame2_t F = {0, 0, 1, 0};
    double r = 0.5 * f->beacon_diameter_mm, h = f->beacon_height_mm;
    if (f->beacon_diameter_mm <= 0 || f->beacon_height_mm <= 0)
        return;
    for (i = 0; i < f->n_landmarks; i++) {
        const fl_landmark_t *lm = &f->landmarks[i];
        double c[3];
        prim_t *p;
        if (lm->kind != FL_LM_BEACON)
            continue;
        F.ox = lm->x_mm;
        F.oy = lm->y_mm;
        group_begin(w);
        if (lm->color == lm->color2) {
            /* A landmark pole of the humanoid league (hl3x2): three equal
             * bands, top and bottom of color, the middle of the other
             * goal color (YBY, BYB), standing on the carpet with no base.
             * Two-color AIBO beacons (color != color2) keep their look
             * below. */
            fl_color_t mid = f->goal_color[0] == lm->color ? f->goal_color[1] : f->goal_color[0];
            color_rgb(lm->color, c);
            p = vcyl_l(w, &F, 0, 0, 0, h / 3.0, r, c, RENDER_CLASS_BEACON, TEX_NONE);
            if (p) p->landmark = i;
            color_rgb(mid, c);
            p = vcyl_l(w, &F, 0, 0, h / 3.0, 2.0 * h / 3.0, r, c, RENDER_CLASS_BEACON, TEX_NONE);
            if (p) p->landmark = i;
            color_rgb(lm->color, c);
            p = vcyl_l(w, &F, 0, 0, 2.0 * h / 3.0, h, r, c, RENDER_CLASS_BEACON, TEX_NONE);
            if (p) p->landmark = i;
            group_end(w);
            continue;
        }
        set_rgb(c, 240, 240, 238);
        p = vcyl_l(w, &F, 0, 0, 0, 0.5 * h, r, c, RENDER_CLASS_BEACON, TEX_NONE);
        if (p) p->landmark = i;
        color_rgb(lm->color2, c);
        p = vcyl_l(w, &F, 0, 0, 0.5 * h, 0.75 * h, r, c, RENDER_CLASS_BEACON, TEX_NONE);
        if (p) p->landmark = i;
        color_rgb(lm->color, c);
        p = vcyl_l(w, &F, 0, 0, 0.75 * h, h, r, c, RENDER_CLASS_BEACON, TEX_NONE);
        if (p) p->landmark = i;
        group_end(w);
    }
}

static void build_robot(world_t *w, const render_robot_t *rb)
{
    const int O = RENDER_CLASS_OBJECT;
    double white[3] = {232, 232, 235}, grey[3] = {120, 122, 128}, jersey[3];
    frame2_t F;
    int k;
    F.ox = rb->x_mm;
    F.oy = rb->y_mm;
    F.cs = rcos(rb->heading);
    F.sn = rsin(rb->heading);
    if (rb->jersey == RENDER_JERSEY_BLUE)
        set_rgb(jersey, 40, 70, 190);
    else
        set_rgb(jersey, 205, 40, 45);
    group_begin(w);
    if (!w->aibo) {
        for (k = -1; k <= 1; k += 2) {
            box_l(w, &F, 20, 50 * k, 0, 40, 80, 45, grey, O, TEX_NONE);
            box_l(w, &F, 0, 50 * k, 40, 290, 45, 40, white, O, TEX_NONE);
            box_l(w, &F, 0, 50 * k, 290, 380, 45, 45, grey, O, TEX_NONE);
            box_l(w, &F, 0, 118 * k, 290, 530, 35, 30, white, O, TEX_NONE);
        }
        box_l(w, &F, 0, 0, 375, 425, 55, 90, grey, O, TEX_NONE);
        box_l(w, &F, 0, 0, 425, 565, 60, 85, white, O, TEX_NONE);
        box_l(w, &F, 0, 0, 430, 545, 65, 89, jersey, O, TEX_FABRIC);
        vcyl_l(w, &F, 0, 0, 565, 585, 25, grey, O, TEX_NONE);
        sphere_l(w, &F, 0, 0, 645, 72, white, O, TEX_NONE);
        sphere_l(w, &F, 30, 0, 640, 55, grey, O, TEX_NONE);
    } else {
        double silver[3] = {205, 205, 210};
        for (k = 0; k < 4; k++)
            vcyl_l(w, &F, (k & 1) ? 95 : -95, (k & 2) ? 55 : -55, 0, 140, 22, grey, O, TEX_NONE);
        box_l(w, &F, 0, 0, 130, 250, 130, 70, silver, O, TEX_NONE);
        box_l(w, &F, -10, 0, 150, 245, 80, 73, jersey, O, TEX_FABRIC);
        sphere_l(w, &F, 150, 0, 285, 55, white, O, TEX_NONE);
        sphere_l(w, &F, 195, 0, 275, 25, grey, O, TEX_NONE);
    }
    group_end(w);
}

/* The black-and-white foam ball (100 mm) of the white-goal fields
 * (SPL from 2016); the orange street hockey ball (65 mm) before. */
static int modern_ball(const world_t *w)
{
    return strcmp(w->field->name, "spl2020") == 0 || strcmp(w->field->name, "spl2016") == 0;
}

static double ball_radius(const world_t *w)
{
    if (w->aibo)
        return 42.5;
    return modern_ball(w) ? 50.0 : 32.5;
}

static void build_ball(world_t *w)
{
    double c[3];
    frame2_t F = {0, 0, 1, 0};
    int spl2020 = modern_ball(w);
    prim_t *p;
    F.ox = w->sc->ball_x_mm;
    F.oy = w->sc->ball_y_mm;
    if (spl2020)
        set_rgb(c, 240, 240, 240);
    else
        set_rgb(c, 245, 115, 25);
    group_begin(w);
    p = sphere_l(w, &F, 0, 0, ball_radius(w), ball_radius(w), c, RENDER_CLASS_BALL,
                 spl2020 ? TEX_BALL : TEX_NONE);
    if (p)
        p->landmark = 100000; /* skip id used by truth.c for the ball centre */
    group_end(w);
}

static void build_aibo_walls(world_t *w)
{
    double c[3] = {238, 238, 235};
    frame2_t F = {0, 0, 1, 0};
    double hx = w->carpet_hx, hy = w->carpet_hy, t = 20, h = 100;
    group_begin(w);
    box_l(w, &F, hx + t, 0, 0, h, t, hy + 2 * t, c, RENDER_CLASS_BACKGROUND, TEX_GRAIN);
    box_l(w, &F, -hx - t, 0, 0, h, t, hy + 2 * t, c, RENDER_CLASS_BACKGROUND, TEX_GRAIN);
    box_l(w, &F, 0, hy + t, 0, h, hx, t, c, RENDER_CLASS_BACKGROUND, TEX_GRAIN);
    box_l(w, &F, 0, -hy - t, 0, h, hx, t, c, RENDER_CLASS_BACKGROUND, TEX_GRAIN);
    group_end(w);
}

/* ---- world: build ---------------------------------------------------------------- */

/* The torso and roll offset of camera.h on the head-only camera: R (camera
 * -> robot) becomes T R Rx(roll_offset) and the centre offset from the
 * head pitch axis c becomes T c, T = Ry(torso_pitch) Rx(torso_roll). */
static void world_tilt(const render_scene_t *sc, double R[3][3], double c[3])
{
    double cr = rcos(sc->head.roll_offset), sr = rsin(sc->head.roll_offset);
    double tp = rcos(sc->head.torso_pitch), sp = rsin(sc->head.torso_pitch);
    double tr = rcos(sc->head.torso_roll), st = rsin(sc->head.torso_roll);
    double T[3][3], A[3][3], v[3];
    int i, j, k;
    for (i = 0; i < 3; i++) { /* R Rx(roll_offset): columns y, z turn */
        double y = R[i][1], z = R[i][2];
        R[i][1] = cr * y + sr * z;
        R[i][2] = -sr * y + cr * z;
    }
    /* T = Ry(tp) Rx(tr) */
    T[0][0] = tp; T[0][1] = sp * st;  T[0][2] = sp * tr;
    T[1][0] = 0;  T[1][1] = tr;       T[1][2] = -st;
    T[2][0] = -sp; T[2][1] = tp * st; T[2][2] = tp * tr;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            A[i][j] = 0;
            for (k = 0; k < 3; k++)
                A[i][j] += T[i][k] * R[k][j];
        }
        v[i] = T[i][0] * c[0] + T[i][1] * c[1] + T[i][2] * c[2];
    }
    memcpy(R, A, sizeof A);
    memcpy(c, v, sizeof v);
}

/* The pixel box of every group (group_t.on_screen).  The corners are
 * mapped to ray coordinates e = M^-1 (corner - P), exactly inverting
 * world_ray (a pixel's ray is M (f, cx - u, cy - v); M is orthonormal only
 * to the precision of the angle tables), so a point of the box and the
 * pixel whose ray passes through it agree to rounding: the point's pixel
 * is u = cx - f e1 / e0, v = cy - f e2 / e0, reached when e0 > 0.
 *  - every corner at e0 >= 10 mm: the box of the corners' pixels, 1 px
 *    wider on each side;
 *  - every corner at e0 <= -10 mm: behind the camera, never reached;
 *  - otherwise, when the camera is 10 mm or more outside the box and the
 *    box lies wholly beyond a line 2 px outside the image (a linear
 *    function of e, positive at the 8 corners, so on the whole box), the
 *    pixels up to 1 px outside the image skip it (a half-plane box). */
static void group_screens(world_t *w)
{
    double A[3][3], det, e[8][3], W = w->W, H = w->H;
    int gi, c, j, k;
    for (j = 0; j < 3; j++)
        for (k = 0; k < 3; k++)
            A[j][k] = w->M[(k + 1) % 3][(j + 1) % 3] * w->M[(k + 2) % 3][(j + 2) % 3] -
                      w->M[(k + 1) % 3][(j + 2) % 3] * w->M[(k + 2) % 3][(j + 1) % 3];
    det = w->M[0][0] * A[0][0] + w->M[0][1] * A[1][0] + w->M[0][2] * A[2][0];
    for (gi = 0; gi < w->ng; gi++) {
        group_t *g = &w->groups[gi];
        int front = 0, behind = 0, away = 0, side[4] = {0, 0, 0, 0};
        g->on_screen = 0;
        if (!(fabs(det) > 0.5) || !(w->f > 0.0))
            continue;
        for (c = 0; c < 8; c++) {
            double q[3];
            for (k = 0; k < 3; k++)
                q[k] = ((c >> k) & 1 ? g->hi[k] : g->lo[k]) - w->P[k];
            for (j = 0; j < 3; j++)
                e[c][j] = (A[j][0] * q[0] + A[j][1] * q[1] + A[j][2] * q[2]) / det;
            front += e[c][0] >= 10.0;
            behind += e[c][0] <= -10.0;
            /* beyond u = -2, u = W + 2, v = -2, v = H + 2 */
            side[0] += w->f * e[c][1] - (w->cx + 2.0) * e[c][0] > 0.0;
            side[1] += (w->cx - W - 2.0) * e[c][0] - w->f * e[c][1] > 0.0;
            side[2] += w->f * e[c][2] - (w->cy + 2.0) * e[c][0] > 0.0;
            side[3] += (w->cy - H - 2.0) * e[c][0] - w->f * e[c][2] > 0.0;
        }
        for (k = 0; k < 3; k++)
            away |= w->P[k] <= g->lo[k] - 10.0 || w->P[k] >= g->hi[k] + 10.0;
        if (front == 8) {
            for (c = 0; c < 8; c++) {
                double u = w->cx - w->f * e[c][1] / e[c][0], v = w->cy - w->f * e[c][2] / e[c][0];
                if (c == 0 || u < g->u0)
                    g->u0 = u;
                if (c == 0 || u > g->u1)
                    g->u1 = u;
                if (c == 0 || v < g->v0)
                    g->v0 = v;
                if (c == 0 || v > g->v1)
                    g->v1 = v;
            }
            g->u0 -= 1.0;
            g->u1 += 1.0;
            g->v0 -= 1.0;
            g->v1 += 1.0;
            g->on_screen = 1;
        } else if (behind == 8) {
            g->on_screen = 2;
        } else if (away && (side[0] == 8 || side[1] == 8 || side[2] == 8 || side[3] == 8)) {
            g->u0 = side[1] == 8 ? W + 1.0 : -HUGE_VAL;
            g->u1 = side[0] == 8 ? -1.0 : HUGE_VAL;
            g->v0 = side[3] == 8 ? H + 1.0 : -HUGE_VAL;
            g->v1 = side[2] == 8 ? -1.0 : HUGE_VAL;
            g->on_screen = 1;
        }
    }
}

int world_build(world_t *w, const render_scene_t *sc)
{
    fl_camera_t fc;
    const fl_camera_model_t *m;
    fl_angle_t alpha, theta, yaw;
    double sa, ca, st, ct, sy, cy, R[3][3], xh, zh;
    int i, j, k;
    rnd_t r;

    memset(w, 0, sizeof *w);
    if (!sc || !sc->field || !sc->camera)
        return -1;
    if (fl_camera_init(&fc, sc->camera, &sc->head) != FL_OK)
        return -1;
    if (sc->n_robots < 0 || sc->n_robots > RENDER_MAX_ROBOTS)
        return -1;
    m = sc->camera;
    w->sc = sc;
    w->field = sc->field;
    w->W = (int)m->width_px;
    w->H = (int)m->height_px;
    w->f = m->focal_q4 / 16.0;
    w->cx = m->cx_q4 / 16.0;
    w->cy = m->cy_q4 / 16.0;
    w->aibo = strncmp(sc->field->name, "aibo", 4) == 0 || is_aibo_camera(m);

    alpha = fl_angle_wrap((int32_t)m->mount_tilt + sc->head.head_pitch + sc->head.pitch_offset);
    theta = fl_angle_wrap((int32_t)sc->head.head_pitch + sc->head.pitch_offset);
    yaw = sc->head.head_yaw;
    sa = rsin(alpha);
    ca = rcos(alpha);
    st = rsin(theta);
    ct = rcos(theta);
    sy = rsin(yaw);
    cy = rcos(yaw);
    /* camera frame -> robot frame, as src/model/camera.c */
    R[0][0] = cy * ca; R[0][1] = -sy; R[0][2] = cy * sa;
    R[1][0] = sy * ca; R[1][1] = cy;  R[1][2] = sy * sa;
    R[2][0] = -sa;     R[2][1] = 0;   R[2][2] = ca;
    xh = m->mount_x_mm * ct + m->mount_z_mm * st;
    zh = -m->mount_x_mm * st + m->mount_z_mm * ct;
    w->cam_r[0] = xh * cy;
    w->cam_r[1] = xh * sy;
    w->cam_r[2] = zh;
    if (sc->head.roll_offset != 0 || sc->head.torso_pitch != 0 || sc->head.torso_roll != 0)
        world_tilt(sc, R, w->cam_r);
    w->cam_r[2] += sc->head.neck_height_mm;
    w->rc = rcos(sc->robot_heading);
    w->rs = rsin(sc->robot_heading);
    w->P[0] = sc->robot_x_mm + w->rc * w->cam_r[0] - w->rs * w->cam_r[1];
    w->P[1] = sc->robot_y_mm + w->rs * w->cam_r[0] + w->rc * w->cam_r[1];
    w->P[2] = w->cam_r[2];
    for (j = 0; j < 3; j++) {
        w->M[0][j] = w->rc * R[0][j] - w->rs * R[1][j];
        w->M[1][j] = w->rs * R[0][j] + w->rc * R[1][j];
        w->M[2][j] = R[2][j];
    }
    if (R[2][1] == 0.0)
        w->horizon_v = ca > 1e-12 ? w->cy - w->f * sa / ca : (sa > 0 ? -1e9 : 1e9);
    else /* rolled: the row at the principal point's column */
        w->horizon_v = R[2][2] > 1e-12 ? w->cy + w->f * R[2][0] / R[2][2] : (R[2][0] < 0 ? -1e9 : 1e9);

    w->carpet_hx = fl_field_carpet_half_x_mm(w->field);
    w->carpet_hy = fl_field_carpet_half_y_mm(w->field);
    w->lw2 = 0.5 * w->field->line_width_mm;
    w->mark2 = 0.5 * w->field->mark_size_mm;
    w->wseed = rnd_hash3(sc->world_seed, (uint32_t)w->field->length_mm, (uint32_t)w->field->width_mm);
    rnd_seed(&r, w->wseed);
    w->room_hx = w->carpet_hx + (w->aibo ? rnd_range(&r, 900, 1600) : rnd_range(&r, 1300, 2600));
    w->room_hy = w->carpet_hy + (w->aibo ? rnd_range(&r, 900, 1600) : rnd_range(&r, 1300, 2600));
    w->room_h = 2900;
    w->seam_step = w->aibo ? 1000 : 2000;
    w->seam_off = rnd_range(&r, 0, w->seam_step);
    w->seam_w = 6;
    for (k = 0; k < 3; k++) {
        w->carpet_rgb[k] = render_color_carpet[k];
        w->line_rgb[k] = render_color_line[k];
    }
    {
        double t = rnd_range(&r, 0.92, 1.05);
        set_rgb(w->floor_rgb, 175 * t, 168 * t, 155 * t);
        t = rnd_range(&r, 0.9, 1.0);
        set_rgb(w->wall_rgb, 232 * t, 228 * t, 214 * t);
        set_rgb(w->ceil_rgb, 205, 205, 200);
    }
    {
        fl_angle_t la = (fl_angle_t)rnd_int(&r, -32768, 32767);
        double lx = 0.35 * rcos(la), ly = 0.35 * rsin(la), lz = 0.9367496997597597; /* sqrt(1 - .35^2) */
        set_rgb(w->light, lx, ly, lz);
    }
    /* soft shadow patches (lighting of the room), world-fixed */
    if (sc->shadows) {
        int n = rnd_int(&r, 2, 4);
        for (i = 0; i < n; i++) {
            blob_t *b = &w->blobs[w->nblobs++];
            b->x = rnd_range(&r, -w->carpet_hx, w->carpet_hx);
            b->y = rnd_range(&r, -w->carpet_hy, w->carpet_hy);
            b->r = w->aibo ? rnd_range(&r, 300, 700) : rnd_range(&r, 600, 1500);
            b->dark = rnd_range(&r, 0.12, 0.3);
        }
        for (i = 0; i < sc->n_robots; i++) {
            blob_t *b = &w->blobs[w->nblobs++];
            b->x = sc->robots[i].x_mm;
            b->y = sc->robots[i].y_mm;
            b->r = w->aibo ? 220 : 260;
            b->dark = 0.45;
        }
        if (sc->ball) {
            blob_t *b = &w->blobs[w->nblobs++];
            b->x = sc->ball_x_mm;
            b->y = sc->ball_y_mm;
            b->r = 1.3 * ball_radius(w);
            b->dark = 0.4;
        }
    }

    build_goals(w);
    build_beacons(w);
    for (i = 0; i < sc->n_robots; i++)
        build_robot(w, &sc->robots[i]);
    if (sc->ball)
        build_ball(w);
    if (w->aibo)
        build_aibo_walls(w);
    build_room(w, &r);
    if (w->np > 0 && (!w->prims || !w->groups)) {
        world_free(w);
        return -1;
    }
    group_screens(w);
    return 0;
}

void world_free(world_t *w)
{
    free(w->prims);
    free(w->groups);
    w->prims = NULL;
    w->groups = NULL;
    w->np = w->ng = 0;
}

/* ---- tracing ------------------------------------------------------------------------- */

void world_ray(const world_t *w, double u, double v, double d[3])
{
    double a = w->f, b = w->cx - u, c = w->cy - v;
    int k;
    for (k = 0; k < 3; k++)
        d[k] = w->M[k][0] * a + w->M[k][1] * b + w->M[k][2] * c;
}

int world_project(const world_t *w, const double q[3], double *u, double *v, double *dist)
{
    double d[3], c[3];
    int k;
    for (k = 0; k < 3; k++)
        d[k] = q[k] - w->P[k];
    for (k = 0; k < 3; k++)
        c[k] = w->M[0][k] * d[0] + w->M[1][k] * d[1] + w->M[2][k] * d[2];
    if (dist)
        *dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (c[0] <= 1e-9)
        return 0;
    *u = w->cx - w->f * c[1] / c[0];
    *v = w->cy - w->f * c[2] / c[0];
    return 1;
}

static double shadow_factor(const world_t *w, double x, double y)
{
    double s = 1.0;
    int i;
    for (i = 0; i < w->nblobs; i++) {
        const blob_t *b = &w->blobs[i];
        double dx = x - b->x, dy = y - b->y, d2 = dx * dx + dy * dy;
        if (d2 < b->r * b->r)
            s *= 1.0 - b->dark * smooth01(1.0 - sqrt(d2) / b->r);
    }
    return s;
}

/* Texture attenuation for features of `cell` mm seen with a footprint of fp
 * mm per pixel (cheap mip-mapping). */
static double att(double cell, double fp) { return cell / (cell + fp); }

static void shade_ground(const world_t *w, double x, double y, double fp, sample_t *s)
{
    double k, sd_c = (fabs(x) - w->carpet_hx) > (fabs(y) - w->carpet_hy)
                         ? fabs(x) - w->carpet_hx
                         : fabs(y) - w->carpet_hy;
    int c;
    s->sid = 1;
    if (sd_c <= 0.0) {
        double sd = world_paint_sd(w, x, y);
        s->carpet = 1;
        if (fabs(sd) < 0.75 * fp + 0.5 || fabs(sd_c) < 0.75 * fp + 0.5)
            s->near_edge = 1;
        if (sd <= 0.0) {
            s->cls = RENDER_CLASS_LINE;
            k = 1.0 + 0.03 * vnoise(x, y, 25, w->wseed + 7) * att(25, fp);
            for (c = 0; c < 3; c++)
                s->rgb[c] = w->line_rgb[c] * k;
        } else {
            double n1 = vnoise(x, y, 6, w->wseed + 1) * att(6, fp);
            double n2 = vnoise(x, y, 35, w->wseed + 2) * att(35, fp);
            double n3 = vnoise(x, y, 450, w->wseed + 3);
            double hue = vnoise(x, y, 900, w->wseed + 4);
            double strip, ys, dseam;
            s->cls = RENDER_CLASS_GREEN;
            k = 1.0 + 0.11 * n1 + 0.06 * n2 + 0.05 * n3;
            /* carpet rolls: strips along x, slightly different dye lots,
             * darker seams between them */
            ys = (y - w->seam_off) / w->seam_step;
            strip = floor(ys);
            k *= 1.0 + 0.025 * (rnd_hash3((uint32_t)(int32_t)strip, w->wseed, 5) * (2.0 / 4294967295.0) - 1.0);
            dseam = fabs(ys - floor(ys + 0.5)) * w->seam_step;
            if (dseam < 0.5 * w->seam_w + 0.5 * fp) {
                double cover = w->seam_w / (w->seam_w + fp);
                k *= 1.0 - 0.25 * cover;
            }
            s->rgb[0] = w->carpet_rgb[0] * k * (1.0 + 0.04 * hue);
            s->rgb[1] = w->carpet_rgb[1] * k;
            s->rgb[2] = w->carpet_rgb[2] * k * (1.0 - 0.03 * hue);
        }
    } else {
        if (fabs(sd_c) < 0.75 * fp + 0.5)
            s->near_edge = 1;
        s->cls = RENDER_CLASS_BACKGROUND;
        k = 1.0 + 0.05 * vnoise(x, y, 300, w->wseed + 11) + 0.04 * vnoise(x, y, 20, w->wseed + 12) * att(20, fp);
        for (c = 0; c < 3; c++)
            s->rgb[c] = w->floor_rgb[c] * k;
    }
    k = shadow_factor(w, x, y);
    for (c = 0; c < 3; c++)
        s->rgb[c] *= k;
}

static void shade_object(const world_t *w, const prim_t *p, const double h[3], const double n[3],
                         const double d[3], sample_t *s)
{
    double nl = n[0] * w->light[0] + n[1] * w->light[1] + n[2] * w->light[2];
    double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double nv = -(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / dl;
    double k = 0.5 + 0.42 * (nl > 0 ? nl : 0) + 0.22 * (nv > 0 ? nv : 0);
    int c;
    switch (p->tex) {
    case TEX_GRAIN:
        k *= 1.0 + 0.04 * vnoise(h[0] + 0.7 * h[1], h[2] + 0.3 * h[1], 15, w->wseed + 21);
        break;
    case TEX_FABRIC:
        k *= 1.0 + 0.08 * vnoise(h[0] + 0.7 * h[1], h[2] - 0.4 * h[0], 40, w->wseed + 22);
        break;
    case TEX_BALL: {
        /* black patches on a white ball */
        double v = vnoise(n[0] * 90 + n[2] * 13, n[1] * 90 - n[2] * 37, 40, 77);
        if (v > 0.35)
            k *= 0.12;
        break;
    }
    default:
        break;
    }
    s->cls = p->cls;
    for (c = 0; c < 3; c++)
        s->rgb[c] = p->rgb[c] * k;
    if (p->cls != RENDER_CLASS_BACKGROUND && h[2] < 60.0) {
        /* contact darkening at the foot of objects standing on the carpet */
        double f = 0.75 + 0.25 * (h[2] / 60.0);
        for (c = 0; c < 3; c++)
            s->rgb[c] *= f;
    }
}

void world_trace(const world_t *w, double u, double v, sample_t *s)
{
    double d[3], tg = 1e30, te, tx, ty, tz, to;
    double n[3], uv[2];
    int pi, c, wall = 0;

    memset(s, 0, sizeof *s);
    world_ray(w, u, v, d);
    if (d[2] < 0.0) {
        tg = -w->P[2] / d[2];
        s->has_ground = 1;
        s->gx = w->P[0] + tg * d[0];
        s->gy = w->P[1] + tg * d[1];
        if (fabs(s->gx) <= w->carpet_hx && fabs(s->gy) <= w->carpet_hy)
            s->carpet = 1;
    }
    tx = d[0] > 0 ? (w->room_hx - w->P[0]) / d[0] : d[0] < 0 ? (-w->room_hx - w->P[0]) / d[0] : 1e30;
    ty = d[1] > 0 ? (w->room_hy - w->P[1]) / d[1] : d[1] < 0 ? (-w->room_hy - w->P[1]) / d[1] : 1e30;
    tz = d[2] > 0 ? (w->room_h - w->P[2]) / d[2] : 1e30;
    te = tx;
    wall = d[0] > 0 ? 2 : 3;
    if (ty < te) {
        te = ty;
        wall = d[1] > 0 ? 4 : 5;
    }
    if (tz < te) {
        te = tz;
        wall = 6;
    }
    if (tg < te) {
        te = tg;
        wall = 1;
    }
    uv[0] = u;
    uv[1] = v;
    pi = hit_objects_n(w, w->P, d, 1e-9, te, -1, &to, n, uv);
    if (pi >= 0) {
        double h[3];
        for (c = 0; c < 3; c++)
            h[c] = w->P[c] + to * d[c];
        shade_object(w, &w->prims[pi], h, n, d, s);
        s->sid = 16 + pi;
        return;
    }
    if (wall == 1) {
        /* footprint of the pixel on the ground: |dG/du| + |dG/dv| */
        double gu[2], gv[2], fp;
        for (c = 0; c < 2; c++) {
            gu[c] = tg * (-w->M[c][1] + d[c] * w->M[2][1] / d[2]);
            gv[c] = tg * (-w->M[c][2] + d[c] * w->M[2][2] / d[2]);
        }
        s->fpu = sqrt(gu[0] * gu[0] + gu[1] * gu[1]);
        s->fpv = sqrt(gv[0] * gv[0] + gv[1] * gv[1]);
        fp = s->fpu + s->fpv;
        shade_ground(w, s->gx, s->gy, fp, s);
        return;
    }
    {
        double h[3], k;
        for (c = 0; c < 3; c++)
            h[c] = w->P[c] + te * d[c];
        s->sid = wall;
        s->cls = RENDER_CLASS_BACKGROUND;
        if (wall == 6) {
            for (c = 0; c < 3; c++)
                s->rgb[c] = w->ceil_rgb[c];
        } else if (h[2] < 90) {
            set_rgb(s->rgb, 110, 105, 98);
        } else {
            double along = wall <= 3 ? h[1] : h[0];
            k = 1.0 + 0.04 * vnoise(along, h[2], 500, w->wseed + 31) - 0.08 * (h[2] / w->room_h);
            k *= wall <= 3 ? 1.0 : 0.92; /* side walls lit differently */
            for (c = 0; c < 3; c++)
                s->rgb[c] = w->wall_rgb[c] * k;
        }
    }
}

/* ---- the frame ------------------------------------------------------------------------ */

void render_frame_free(render_frame_t *fr)
{
    if (!fr)
        return;
    if (fr->rgb != fr->data)
        free(fr->rgb);
    free(fr->data);
    free(fr->mask);
    free(fr->border_v);
    free(fr->border_end_v);
    free(fr->border_visible_v);
    memset(fr, 0, sizeof *fr);
}

static int render_frame_fresh(const render_scene_t *sc, render_frame_t *out)
{
    world_t w;
    int W, H, u, v, n, i, j, c;
    double *img = NULL;
    int *sid = NULL;
    uint8_t *near = NULL, *carpet = NULL;
    double sub_mm;
    size_t npx;
    fl_status_t st;

    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    if (!sc || (sc->format != FL_FMT_RGB888 && sc->format != FL_FMT_YUYV422 &&
                sc->format != FL_FMT_YCBCR_PLANAR))
        return -1;
    if (world_build(&w, sc) != 0)
        return -1;
    W = w.W;
    H = w.H;
    if (sc->format == FL_FMT_YUYV422 && (W & 1)) {
        world_free(&w);
        return -1;
    }
    npx = (size_t)W * (size_t)H;
    img = (double *)malloc(npx * 3 * sizeof *img);
    sid = (int *)malloc(npx * sizeof *sid);
    near = (uint8_t *)malloc(npx);
    carpet = (uint8_t *)malloc(npx);
    out->mask = (uint8_t *)malloc(npx);
    out->rgb = (uint8_t *)malloc(npx * 3);
    out->border_v = (int16_t *)malloc((size_t)W * sizeof(int16_t));
    out->border_end_v = (int16_t *)malloc((size_t)W * sizeof(int16_t));
    out->border_visible_v = (int16_t *)malloc((size_t)W * sizeof(int16_t));
    out->size = sc->format == FL_FMT_YUYV422 ? npx * 2 : npx * 3;
    out->data = sc->format == FL_FMT_RGB888 ? out->rgb : (uint8_t *)malloc(out->size);
    if (!img || !sid || !near || !carpet || !out->mask || !out->rgb || !out->border_v ||
        !out->border_end_v || !out->border_visible_v || !out->data) {
        free(img);
        free(sid);
        free(near);
        free(carpet);
        render_frame_free(out);
        world_free(&w);
        return -1;
    }
    out->width = W;
    out->height = H;
    out->format = sc->format;

    /* pass 1: pixel centres.  near[p] = 0: no supersampling needed by the
     * ground; else the sub-sample counts along u (low nibble) and v (high
     * nibble): a grid fine enough that a line of the true width, however far
     * and thin in the image, is hit by about 3 sub-samples across (no
     * dashed far lines), at least n x n, at most 15 x 15. */
    n = sc->supersample < 1 ? 1 : sc->supersample > 4 ? 4 : sc->supersample;
    sub_mm = w.field->line_width_mm / 3.0;
    for (v = 0; v < H; v++) {
        for (u = 0; u < W; u++) {
            sample_t s;
            size_t p = (size_t)v * (size_t)W + (size_t)u;
            world_trace(&w, u, v, &s);
            for (c = 0; c < 3; c++)
                img[3 * p + (size_t)c] = s.rgb[c];
            out->mask[p] = (uint8_t)s.cls;
            sid[p] = s.sid;
            near[p] = 0;
            if (s.near_edge && n > 1) {
                double cu = ceil(s.fpu / sub_mm), cv = ceil(s.fpv / sub_mm);
                int nu = cu < n ? n : cu > 15 ? 15 : (int)cu;
                int nv = cv < n ? n : cv > 15 ? 15 : (int)cv;
                near[p] = (uint8_t)(nu | (nv << 4));
            }
            carpet[p] = (uint8_t)s.carpet;
        }
    }
    /* pass 2: supersample edges */
    if (n > 1) {
        for (v = 0; v < H; v++) {
            for (u = 0; u < W; u++) {
                size_t p = (size_t)v * (size_t)W + (size_t)u;
                int ss = near[p] != 0, nu = n, nv = n;
                if (ss) {
                    nu = near[p] & 15;
                    nv = near[p] >> 4;
                } else {
                    if ((u > 0 && sid[p - 1] != sid[p]) || (u + 1 < W && sid[p + 1] != sid[p]) ||
                        (v > 0 && sid[p - (size_t)W] != sid[p]) ||
                        (v + 1 < H && sid[p + (size_t)W] != sid[p]))
                        ss = 1;
                }
                if (ss) {
                    double acc[3] = {0, 0, 0};
                    for (j = 0; j < nv; j++) {
                        for (i = 0; i < nu; i++) {
                            sample_t s;
                            world_trace(&w, u + (i + 0.5) / nu - 0.5, v + (j + 0.5) / nv - 0.5, &s);
                            for (c = 0; c < 3; c++)
                                acc[c] += s.rgb[c];
                        }
                    }
                    for (c = 0; c < 3; c++)
                        img[3 * p + (size_t)c] = acc[c] / (nu * nv);
                }
            }
        }
    }
    /* field border per column */
    for (u = 0; u < W; u++) {
        int first = H, end = H, vis = H;
        for (v = 0; v < H; v++) {
            size_t p = (size_t)v * (size_t)W + (size_t)u;
            if (carpet[p]) {
                if (first == H)
                    first = v;
                end = v + 1;
            }
            if (vis == H && (out->mask[p] == RENDER_CLASS_GREEN || out->mask[p] == RENDER_CLASS_LINE))
                vis = v;
        }
        if (first == H)
            end = H;
        out->border_v[u] = (int16_t)first;
        out->border_end_v[u] = (int16_t)end;
        out->border_visible_v[u] = (int16_t)vis;
    }
    post_process(sc, W, H, img, out->rgb);
    if (sc->format != FL_FMT_RGB888)
        post_convert(sc->format, W, H, out->rgb, out->data);
    if (sc->format == FL_FMT_YCBCR_PLANAR)
        st = fl_image_init_planar(&out->view, out->data, W, out->data + npx, W, out->data + 2 * npx,
                                  W, W, H);
    else
        st = fl_image_init_packed(&out->view, sc->format, out->data, W, H,
                                  sc->format == FL_FMT_YUYV422 ? 2 * W : 3 * W);
    free(img);
    free(sid);
    free(near);
    free(carpet);
    world_free(&w);
    if (st != FL_OK) {
        render_frame_free(out);
        return -1;
    }
    return 0;
}

int render_frame(const render_scene_t *sc, render_frame_t *out)
{
    int rc;
    /* FIELDLOC_RENDER_CACHE (render_cache.c): the host's frames under
     * emulators; off in ordinary runs */
    if (sc != NULL && out != NULL && render_cache_load(sc, out) == 0)
        return 0;
    rc = render_frame_fresh(sc, out);
    if (rc == 0)
        render_cache_store(sc, out);
    return rc;
}

/* ---- public helpers ---------------------------------------------------------------------- */

render_class_t render_classify_pixel(const render_scene_t *sc, double u, double v,
                                     double field_xy[2])
{
    world_t w;
    sample_t s;
    if (world_build(&w, sc) != 0)
        return RENDER_CLASS_BACKGROUND;
    world_trace(&w, u, v, &s);
    if (field_xy && (s.cls == RENDER_CLASS_GREEN || s.cls == RENDER_CLASS_LINE)) {
        field_xy[0] = s.gx;
        field_xy[1] = s.gy;
    }
    world_free(&w);
    return (render_class_t)s.cls;
}

int render_project_field(const render_scene_t *sc, double fx, double fy, double fz, double *u,
                         double *v, double *range_mm)
{
    world_t w;
    double q[3], uu = 0, vv = 0;
    int ok;
    if (world_build(&w, sc) != 0)
        return 0;
    q[0] = fx;
    q[1] = fy;
    q[2] = fz;
    ok = world_project(&w, q, &uu, &vv, range_mm);
    world_free(&w);
    if (u)
        *u = uu;
    if (v)
        *v = vv;
    return ok;
}

void render_field_to_robot(const render_scene_t *sc, double fx, double fy, double *rx, double *ry)
{
    double c = rcos(sc->robot_heading), s = rsin(sc->robot_heading);
    double dx = fx - sc->robot_x_mm, dy = fy - sc->robot_y_mm;
    *rx = c * dx + s * dy;
    *ry = -s * dx + c * dy;
}

void render_robot_to_field(const render_scene_t *sc, double rx, double ry, double *fx, double *fy)
{
    double c = rcos(sc->robot_heading), s = rsin(sc->robot_heading);
    *fx = sc->robot_x_mm + c * rx - s * ry;
    *fy = sc->robot_y_mm + s * rx + c * ry;
}

int render_occluded(const render_scene_t *sc, double fx, double fy, double fz, double tolerance_mm,
                    int exclude_landmark)
{
    world_t w;
    double d[3], len;
    int hit;
    if (world_build(&w, sc) != 0)
        return 0;
    d[0] = fx - w.P[0];
    d[1] = fy - w.P[1];
    d[2] = fz - w.P[2];
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len <= tolerance_mm) {
        world_free(&w);
        return 0;
    }
    /* t in units of the full segment: blocked before (len - tol) / len */
    hit = world_hit_objects(&w, w.P, d, 1e-9, (len - tolerance_mm) / len, exclude_landmark, NULL) >= 0;
    world_free(&w);
    return hit;
}

/*
 * tools/world/render_int.h - internals shared by tools/render*.c and tools/world/truth.c
 * (not an API: colleagues use render.h / truth.h).
 */
#ifndef FL_TOOLS_RENDER_INT_H
#define FL_TOOLS_RENDER_INT_H

#include "world/render.h"

#include <stdint.h>

/* ---- deterministic random numbers ---------------------------------------- */

typedef struct { uint64_t s; } rnd_t;
void rnd_seed(rnd_t *r, uint64_t seed);
uint32_t rnd_u32(rnd_t *r);
double rnd_unit(rnd_t *r);                    /* [0, 1) */
double rnd_range(rnd_t *r, double lo, double hi);
int rnd_int(rnd_t *r, int lo, int hi);        /* inclusive */
double rnd_gauss(rnd_t *r);                   /* approx N(0, 1), Irwin-Hall(4) */
uint32_t rnd_hash3(uint32_t a, uint32_t b, uint32_t c);

/* sin / cos of a binary angle from the firmware tables (exact same values on
 * every machine). */
double rsin(fl_angle_t a);
double rcos(fl_angle_t a);

/* ---- the world: primitives the rays hit ----------------------------------- */

enum { PR_BOX = 0, PR_VCYL = 1, PR_HCYLY = 2, PR_SPHERE = 3 };
enum { TEX_NONE = 0, TEX_GRAIN = 1, TEX_FABRIC = 2, TEX_BALL = 3 };

typedef struct {
    int type;
    double c[3];     /* box: centre (z = centre height); vcyl: (x, y, z0);
                        hcyly: (x, ?, z) axis; sphere: centre */
    double h[3];     /* box: half sizes along its own x, y, z; vcyl: r, z1;
                        hcyly: r, y0, y1; sphere: r */
    double cs, sn;   /* box: heading (own x axis = (cs, sn)) */
    double rgb[3];
    int cls;         /* render_class_t */
    int tex;
    int landmark;    /* field landmark index (posts, beacons) or -1 */
} prim_t;

typedef struct {
    double lo[3], hi[3];  /* bounding box */
    int first, count;
    /* on_screen 1: every corner of the box is at least 10 mm in front of
     * the camera and u0..u1 x v0..v1 holds their pixels with a 1 px margin,
     * so a pixel's ray outside it misses the box (world_trace skips the
     * group); 2: every corner is at least 10 mm behind the camera (no
     * pixel's ray meets the box); 0: neither */
    int on_screen;
    double u0, u1, v0, v1;
} group_t;

typedef struct {
    double x, y, r, dark;  /* soft shadow disc on the ground */
} blob_t;

typedef struct {
    const render_scene_t *sc;
    const fl_field_t *field;
    int W, H;
    double f, cx, cy;
    double P[3];          /* camera centre, field frame, mm */
    double M[3][3];       /* camera axes (optical, left, up) -> field frame */
    double cam_r[3];      /* camera centre, robot frame */
    double rc, rs;        /* robot heading */
    double horizon_v;
    double carpet_hx, carpet_hy;
    double room_hx, room_hy, room_h;
    double lw2;           /* half line width */
    double mark2;         /* half mark size */
    double seam_step, seam_off, seam_w;
    int aibo;             /* AIBO-scale world */
    double carpet_rgb[3], line_rgb[3], floor_rgb[3], wall_rgb[3], ceil_rgb[3];
    double light[3];      /* unit vector toward the main light */
    prim_t *prims;
    int np, pcap;
    group_t *groups;
    int ng, gcap;
    blob_t blobs[16 + RENDER_MAX_ROBOTS + 1];
    int nblobs;
    uint32_t wseed;
} world_t;

/* Build / free the world of a scene (-1 on bad scene). */
int world_build(world_t *w, const render_scene_t *sc);
void world_free(world_t *w);

/* One sample along the ray through pixel (u, v) (pixel-centre convention). */
typedef struct {
    double rgb[3];
    int cls;
    int sid;          /* surface id: 1 ground/floor, 2..6 walls/ceiling,
                         16 + primitive index for objects */
    int near_edge;    /* ground sample within a pixel of a paint/carpet edge */
    int carpet;       /* ray hit the ground inside the carpet (objects are
                         ignored for this flag) */
    double gx, gy;    /* ground point of the ray (objects ignored), valid
                         when has_ground */
    int has_ground;
    double fpu, fpv;  /* ground samples: mm per pixel along u and v */
} sample_t;

void world_ray(const world_t *w, double u, double v, double d[3]);
void world_trace(const world_t *w, double u, double v, sample_t *s);

/* Nearest object hit along origin + t*d for t in (tmin, tmax); returns the
 * primitive index or -1.  skip_landmark >= 0 ignores that landmark's prims. */
int world_hit_objects(const world_t *w, const double o[3], const double d[3],
                      double tmin, double tmax, int skip_landmark, double *t_out);

/* Signed distance (mm) from a field point to the paint (negative inside). */
double world_paint_sd(const world_t *w, double x, double y);

/* Project a field point; 0 when behind the camera. */
int world_project(const world_t *w, const double q[3], double *u, double *v,
                  double *dist);

/* Post-processing (render_post.c): img is W*H*3 doubles in 0..255 scale
 * (already lit), turned into 8-bit RGB in rgb8. */
void post_process(const render_scene_t *sc, int W, int H, double *img,
                  uint8_t *rgb8);
/* 8-bit RGB -> the scene's pixel format. */
void post_convert(fl_pixel_format_t fmt, int W, int H, const uint8_t *rgb8,
                  uint8_t *out);

#endif

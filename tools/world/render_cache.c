/*
 * tools/world/render_cache.c - an optional on-disk cache of rendered
 * frames, so that a run under an emulator (make cross-test: qemu-mips,
 * qemu-mipsel) or valgrind can feed the firmware the very frames the host
 * rendered instead of ray-tracing them again in emulated double precision.
 * Rendering is more than half the host test suite's CPU time (perf, `make
 * test` quick suite) and a larger share under qemu, while what cross-test
 * must prove is that the firmware gives identical results on identical
 * input: reading the host's frames tests exactly that.
 *
 * Off unless the environment variable FIELDLOC_RENDER_CACHE names a
 * directory (the Makefile's cross-test and valgrind targets set it, after
 * emptying the directory, so that no frame of an older renderer survives;
 * `make test` never sets it, so every ordinary run renders).  Then
 * render_frame looks for the scene's file and, failing that, renders and
 * stores.
 *
 * Key: the scene's text form (render_scene_write: every field of the scene,
 * integers only, the same bytes on every target) plus every number of the
 * camera model (a caller may pass a model that is not the catalogue's
 * under a catalogue name).  The file name is a 64-bit FNV-1a hash of the
 * key; the file stores the whole key and a reader compares it, so a hash
 * collision renders afresh instead of returning another scene's frame.
 * Files are written to a temporary name and renamed into place, so
 * parallel test workers never read a half-written frame.
 *
 * File: "fieldloc-render-cache 1\n", key length (4 bytes) and key, width,
 * height, format (4 bytes each), then data (size bytes), rgb (w*h*3), mask
 * (w*h), border_v, border_end_v, border_visible_v (w int16 each).  Every
 * multi-byte number little-endian, whatever the host.
 */
#include "world/render.h"
#include "world/render_cache.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define RC_MAGIC "fieldloc-render-cache 1\n"

/* The key in a malloc'ed buffer (*len bytes), or NULL. */
static char *cache_key(const render_scene_t *sc, size_t *len)
{
    char *buf = NULL;
    size_t n = 0;
    FILE *f;
    const fl_camera_model_t *m = sc->camera;
    if (sc->field == NULL || m == NULL)
        return NULL;
    f = open_memstream(&buf, &n);
    if (f == NULL)
        return NULL;
    if (render_scene_write(f, sc) != 0) {
        fclose(f);
        free(buf);
        return NULL;
    }
    fprintf(f, "model %s %ld %ld %ld %ld %ld %ld %ld %d %ld %d\n", m->name ? m->name : "-",
            (long)m->width_px, (long)m->height_px, (long)m->focal_q4, (long)m->cx_q4,
            (long)m->cy_q4, (long)m->mount_x_mm, (long)m->mount_z_mm, (int)m->mount_tilt,
            (long)m->default_neck_height_mm, (int)m->default_pitch_offset);
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

static unsigned long long fnv1a(const char *s, size_t n)
{
    unsigned long long h = 14695981039346656037ULL;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= (unsigned char)s[i];
        h *= 1099511628211ULL;
    }
    return h;
}

static int put32(FILE *f, uint32_t v)
{
    unsigned char b[4];
    b[0] = (unsigned char)v;
    b[1] = (unsigned char)(v >> 8);
    b[2] = (unsigned char)(v >> 16);
    b[3] = (unsigned char)(v >> 24);
    return fwrite(b, 1, 4, f) == 4 ? 0 : -1;
}

static int get32(FILE *f, uint32_t *v)
{
    unsigned char b[4];
    if (fread(b, 1, 4, f) != 4)
        return -1;
    *v = (uint32_t)b[0] | ((uint32_t)b[1] << 8) | ((uint32_t)b[2] << 16) | ((uint32_t)b[3] << 24);
    return 0;
}

static int put16s(FILE *f, const int16_t *a, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        unsigned char b[2];
        uint16_t v = (uint16_t)a[i];
        b[0] = (unsigned char)v;
        b[1] = (unsigned char)(v >> 8);
        if (fwrite(b, 1, 2, f) != 2)
            return -1;
    }
    return 0;
}

static int get16s(FILE *f, int16_t *a, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        unsigned char b[2];
        if (fread(b, 1, 2, f) != 2)
            return -1;
        a[i] = (int16_t)(uint16_t)((unsigned)b[0] | ((unsigned)b[1] << 8));
    }
    return 0;
}

/* Path of the scene's file in the cache directory (0), or -1 when the
 * cache is off or the key cannot be made; *key / *key_len then own the
 * key (free it). */
static int cache_path(const render_scene_t *sc, char *path, size_t cap, char **key,
                      size_t *key_len)
{
    const char *dir = getenv("FIELDLOC_RENDER_CACHE");
    int n;
    if (dir == NULL || dir[0] == '\0')
        return -1;
    *key = cache_key(sc, key_len);
    if (*key == NULL)
        return -1;
    n = snprintf(path, cap, "%s/%016llx.frame", dir, fnv1a(*key, *key_len));
    if (n < 0 || (size_t)n >= cap) {
        free(*key);
        *key = NULL;
        return -1;
    }
    return 0;
}

int render_cache_file(const render_scene_t *sc, char *path, size_t cap)
{
    char *key = NULL;
    size_t key_len = 0;
    if (sc == NULL || path == NULL || cache_path(sc, path, cap, &key, &key_len) != 0)
        return -1;
    free(key);
    return 0;
}

int render_cache_load(const render_scene_t *sc, render_frame_t *out)
{
    char path[1024], *key = NULL, *stored = NULL;
    size_t key_len = 0, npx;
    uint32_t klen, w, h, fmt;
    FILE *f;
    char magic[sizeof RC_MAGIC - 1];
    int ok = 0;
    fl_status_t st;
    if (cache_path(sc, path, sizeof path, &key, &key_len) != 0)
        return -1;
    f = fopen(path, "rb");
    if (f == NULL) {
        free(key);
        return -1;
    }
    memset(out, 0, sizeof *out);
    if (fread(magic, 1, sizeof magic, f) != sizeof magic || memcmp(magic, RC_MAGIC, sizeof magic) != 0 ||
        get32(f, &klen) != 0 || klen != key_len)
        goto done;
    stored = (char *)malloc(klen ? klen : 1);
    if (stored == NULL || fread(stored, 1, klen, f) != klen || memcmp(stored, key, klen) != 0)
        goto done;
    if (get32(f, &w) != 0 || get32(f, &h) != 0 || get32(f, &fmt) != 0 || w == 0 || h == 0 ||
        w > 4096 || h > 4096 || (int)fmt != (int)sc->format)
        goto done;
    npx = (size_t)w * h;
    out->width = (int)w;
    out->height = (int)h;
    out->format = sc->format;
    out->size = sc->format == FL_FMT_YUYV422 ? npx * 2 : npx * 3;
    out->rgb = (uint8_t *)malloc(npx * 3);
    out->mask = (uint8_t *)malloc(npx);
    out->border_v = (int16_t *)malloc(w * sizeof(int16_t));
    out->border_end_v = (int16_t *)malloc(w * sizeof(int16_t));
    out->border_visible_v = (int16_t *)malloc(w * sizeof(int16_t));
    out->data = sc->format == FL_FMT_RGB888 ? out->rgb : (uint8_t *)malloc(out->size);
    if (!out->rgb || !out->mask || !out->border_v || !out->border_end_v || !out->border_visible_v ||
        !out->data)
        goto done;
    if ((sc->format != FL_FMT_RGB888 && fread(out->data, 1, out->size, f) != out->size) ||
        fread(out->rgb, 1, npx * 3, f) != npx * 3 || fread(out->mask, 1, npx, f) != npx ||
        get16s(f, out->border_v, (int)w) != 0 || get16s(f, out->border_end_v, (int)w) != 0 ||
        get16s(f, out->border_visible_v, (int)w) != 0 || fgetc(f) != EOF)
        goto done;
    if (sc->format == FL_FMT_YCBCR_PLANAR)
        st = fl_image_init_planar(&out->view, out->data, (int32_t)w, out->data + npx, (int32_t)w,
                                  out->data + 2 * npx, (int32_t)w, (int32_t)w, (int32_t)h);
    else
        st = fl_image_init_packed(&out->view, sc->format, out->data, (int32_t)w, (int32_t)h,
                                  (int32_t)(sc->format == FL_FMT_YUYV422 ? w * 2 : w * 3));
    ok = st == FL_OK;
done:
    fclose(f);
    free(key);
    free(stored);
    if (!ok) {
        render_frame_free(out);
        memset(out, 0, sizeof *out);
        return -1;
    }
    return 0;
}

void render_cache_store(const render_scene_t *sc, const render_frame_t *fr)
{
    char path[1024], tmp[1100], *key = NULL;
    size_t key_len = 0, npx;
    FILE *f;
    int bad;
    if (fr == NULL || fr->data == NULL || cache_path(sc, path, sizeof path, &key, &key_len) != 0)
        return;
    npx = (size_t)fr->width * (size_t)fr->height;
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    f = fopen(tmp, "wb");
    if (f == NULL) {
        free(key);
        return;
    }
    bad = fwrite(RC_MAGIC, 1, sizeof RC_MAGIC - 1, f) != sizeof RC_MAGIC - 1 ||
          put32(f, (uint32_t)key_len) != 0 || fwrite(key, 1, key_len, f) != key_len ||
          put32(f, (uint32_t)fr->width) != 0 || put32(f, (uint32_t)fr->height) != 0 ||
          put32(f, (uint32_t)fr->format) != 0 ||
          (fr->format != FL_FMT_RGB888 && fwrite(fr->data, 1, fr->size, f) != fr->size) ||
          fwrite(fr->rgb, 1, npx * 3, f) != npx * 3 || fwrite(fr->mask, 1, npx, f) != npx ||
          put16s(f, fr->border_v, fr->width) != 0 || put16s(f, fr->border_end_v, fr->width) != 0 ||
          put16s(f, fr->border_visible_v, fr->width) != 0;
    if (fclose(f) != 0)
        bad = 1;
    if (bad || rename(tmp, path) != 0)
        remove(tmp);
    free(key);
}

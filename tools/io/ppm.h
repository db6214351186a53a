/*
 * tools/io/ppm.h - host-only image files: binary PPM (P6, maxval 255) read and
 * write, plus PNG output (tools/io/png.c, no library).
 */
#ifndef FL_TOOLS_PPM_H
#define FL_TOOLS_PPM_H

#include <stdint.h>
#include <stdio.h>

typedef struct {
    int width, height;
    uint8_t *rgb;          /* width * height * 3 bytes, malloc'd */
} host_image_t;

/* Read a P6 (maxval 255; comments allowed) file.  0 on success, -1 with a
 * message in err (may be NULL) on failure; out->rgb is NULL then. */
int ppm_read(const char *path, host_image_t *out, char *err, int err_len);
/* The same from an open stream (e.g. fmemopen in the fuzz harness); name is
 * used in messages only. */
int ppm_read_file(FILE *f, const char *name, host_image_t *out, char *err, int err_len);
/* Write P6.  0 on success. */
int ppm_write(const char *path, const uint8_t *rgb, int width, int height);
/* Allocate a width x height image filled with one color (NULL rgb on failure). */
host_image_t host_image_new(int width, int height, uint8_t r, uint8_t g, uint8_t b);
void host_image_free(host_image_t *img);
/* Write PNG (8-bit RGB; tools/io/png.c, no library).  0 on success. */
int png_write(const char *path, const uint8_t *rgb, int width, int height);

#endif

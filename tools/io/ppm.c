/* tools/io/ppm.c - binary PPM I/O for host tools and tests. */
#include "io/ppm.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int skip_ws_comments(FILE *f)
{
    int c;
    for (;;) {
        c = fgetc(f);
        if (c == '#') {
            while (c != '\n' && c != EOF)
                c = fgetc(f);
        } else if (c != ' ' && c != '\t' && c != '\n' && c != '\r') {
            return c;
        }
    }
}

static int read_uint(FILE *f, int *v)
{
    int c = skip_ws_comments(f);
    long x = 0;
    int digits = 0;
    while (c >= '0' && c <= '9') {
        x = x * 10 + (c - '0');
        if (x > 1000000)
            return -1;
        digits++;
        c = fgetc(f);
    }
    if (!digits)
        return -1;
    *v = (int)x;
    return 0;   /* c (one whitespace) consumed */
}

int ppm_read_file(FILE *f, const char *name, host_image_t *out, char *err, int err_len)
{
    int w, h, maxv;
    size_t n;
    out->rgb = NULL;
    out->width = out->height = 0;
    if (fgetc(f) != 'P' || fgetc(f) != '6' || read_uint(f, &w) || read_uint(f, &h) ||
        read_uint(f, &maxv) || maxv != 255 || w < 1 || h < 1 || w > 16384 || h > 16384) {
        if (err) snprintf(err, (size_t)err_len, "%s: not a binary PPM (P6, maxval 255)", name);
        return -1;
    }
    n = (size_t)w * (size_t)h * 3;
    out->rgb = malloc(n);
    if (!out->rgb || fread(out->rgb, 1, n, f) != n) {
        if (err) snprintf(err, (size_t)err_len, "%s: truncated pixel data", name);
        free(out->rgb);
        out->rgb = NULL;
        return -1;
    }
    out->width = w;
    out->height = h;
    return 0;
}

int ppm_read(const char *path, host_image_t *out, char *err, int err_len)
{
    FILE *f;
    int rc;
    out->rgb = NULL;
    out->width = out->height = 0;
    f = fopen(path, "rb");
    if (!f) {
        if (err) snprintf(err, (size_t)err_len, "%s: cannot open", path);
        return -1;
    }
    rc = ppm_read_file(f, path, out, err, err_len);
    fclose(f);
    return rc;
}

int ppm_write(const char *path, const uint8_t *rgb, int width, int height)
{
    FILE *f = fopen(path, "wb");
    size_t n = (size_t)width * (size_t)height * 3;
    int ok;
    if (!f)
        return -1;
    fprintf(f, "P6\n%d %d\n255\n", width, height);
    ok = fwrite(rgb, 1, n, f) == n;
    return (fclose(f) == 0 && ok) ? 0 : -1;
}

host_image_t host_image_new(int width, int height, uint8_t r, uint8_t g, uint8_t b)
{
    host_image_t img;
    size_t i, n = (size_t)width * (size_t)height;
    img.width = width;
    img.height = height;
    img.rgb = malloc(n * 3);
    if (!img.rgb) {
        img.width = img.height = 0;
        return img;
    }
    for (i = 0; i < n; i++) {
        img.rgb[3 * i] = r;
        img.rgb[3 * i + 1] = g;
        img.rgb[3 * i + 2] = b;
    }
    return img;
}

void host_image_free(host_image_t *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->width = img->height = 0;
}


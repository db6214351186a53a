/*
 * host_tests/test_png.c - the PNG writer (tools/io/png.c, no library) read
 * back by independent code: the chunks and their CRCs checked here (bitwise
 * CRC-32, no table), the IDAT zlib stream inflated by python3's zlib (which
 * checks the Adler-32 too), and the scanlines unfiltered here (all five PNG
 * filters) and compared with the written pixels, every byte.  Images: 1x1,
 * thin and odd widths, noise, flat areas, a field-sized 832x592 picture of
 * flat areas, lines and noise, and rows longer than the 32 KiB window.
 * Without python3 only the container (signature, chunks, CRCs, IHDR) is
 * checked.
 */
#include "test.h"
#include "io/ppm.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PNG_CASES 12

typedef struct {
    const char *name;
    int width, height;
    uint8_t *rgb;
} png_case_t;

static uint32_t be32(const uint8_t *p)
{
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | p[3];
}

/* CRC-32 (ISO-HDLC) bit by bit */
static uint32_t crc_bitwise(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        c ^= p[i];
        for (k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

/* signature, IHDR (8-bit RGB, no interlace), IDAT..., IEND last, every CRC */
static int check_container(const uint8_t *f, size_t n, int width, int height)
{
    static const uint8_t sig[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
    size_t at = 8;
    int chunks = 0, idat = 0, iend = 0;
    if (n < 8 || memcmp(f, sig, 8) != 0)
        return 1;
    while (at + 12 <= n) {
        uint32_t len = be32(f + at);
        const uint8_t *type = f + at + 4;
        if (len > n - at - 12 || iend)
            return 2;
        if (be32(f + at + 8 + len) != crc_bitwise(type, (size_t)len + 4))
            return 3;
        if (chunks == 0) {
            const uint8_t *d = type + 4;
            if (memcmp(type, "IHDR", 4) != 0 || len != 13)
                return 4;
            if (be32(d) != (uint32_t)width || be32(d + 4) != (uint32_t)height ||
                d[8] != 8 || d[9] != 2 || d[10] != 0 || d[11] != 0 || d[12] != 0)
                return 5;
        } else if (memcmp(type, "IDAT", 4) == 0) {
            idat++;
        } else if (memcmp(type, "IEND", 4) == 0) {
            if (len != 0)
                return 6;
            iend = 1;
        }
        chunks++;
        at += (size_t)len + 12;
    }
    return at == n && iend && idat > 0 ? 0 : 7;
}

static int paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return pa <= pb && pa <= pc ? a : (pb <= pc ? b : c);
}

/* unfilter h scanlines of 1 + 3w bytes into rgb; -1 on a bad filter type */
static int unfilter(const uint8_t *raw, uint8_t *rgb, int width, int height)
{
    size_t rowlen = (size_t)width * 3u, x;
    int y;
    for (y = 0; y < height; y++) {
        const uint8_t *s = raw + (size_t)y * (rowlen + 1u);
        uint8_t *cur = rgb + (size_t)y * rowlen;
        const uint8_t *up = y > 0 ? cur - rowlen : NULL;
        for (x = 0; x < rowlen; x++) {
            int a = x >= 3 ? cur[x - 3] : 0, b = up ? up[x] : 0, c = (up && x >= 3) ? up[x - 3] : 0;
            int v;
            switch (s[0]) {
            case 0: v = 0; break;
            case 1: v = a; break;
            case 2: v = b; break;
            case 3: v = (a + b) / 2; break;
            case 4: v = paeth(a, b, c); break;
            default: return -1;
            }
            cur[x] = (uint8_t)(s[1 + x] + v);
        }
    }
    return 0;
}

static uint8_t *make_image(int kind, int w, int h, t_rng_t *r)
{
    uint8_t *p = (uint8_t *)malloc((size_t)w * (size_t)h * 3u);
    int x, y, c;
    if (!p)
        return NULL;
    for (y = 0; y < h; y++) {
        for (x = 0; x < w; x++) {
            uint8_t *q = p + ((size_t)y * (size_t)w + (size_t)x) * 3u;
            for (c = 0; c < 3; c++) {
                int v;
                switch (kind) {
                case 0:     /* noise */
                    v = (int)(t_rng_u32(r) & 0xFFu);
                    break;
                case 1:     /* flat */
                    v = 40 + 60 * c;
                    break;
                case 2:     /* gradients */
                    v = (x * (c + 1) + y * (3 - c)) & 0xFF;
                    break;
                default:    /* a field: green, white lines, a goal, noise in places */
                    if ((x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2) < 900 && (x + y) % 5 == 0)
                        v = 255;
                    else if (y < h / 5)
                        v = c == 2 ? 180 : 120;                       /* background */
                    else if (abs(x - y) < 3 || y == h / 2 || (y > h / 5 && abs(x - w / 3) < 2))
                        v = 250;                                      /* lines */
                    else if (x > w - 60 && y > h / 3 && y < h / 2)
                        v = c == 0 ? 230 : (c == 1 ? 200 : 20);       /* a yellow post */
                    else if (y > h - 100)
                        v = (c == 1 ? 140 : 50) + (int)(t_rng_u32(r) % 9u); /* noisy grass */
                    else
                        v = c == 1 ? 150 : 40;                        /* grass */
                    break;
                }
                q[c] = (uint8_t)v;
            }
        }
    }
    return p;
}

static void test_roundtrip(void)
{
    static const struct { const char *name; int kind, w, h; } spec[PNG_CASES] = {
        { "one", 0, 1, 1 },
        { "one_flat", 1, 1, 1 },
        { "row", 0, 7, 1 },
        { "column", 2, 1, 9 },
        { "odd_noise", 0, 13, 7 },
        { "odd_gradient", 2, 31, 17 },
        { "odd_flat", 1, 333, 5 },
        { "field_odd", 3, 101, 77 },
        { "field", 3, 832, 592 },
        { "flat_big", 1, 832, 592 },
        { "wide_rows", 2, 11001, 3 },
        { "noise_big", 0, 160, 120 },
    };
    png_case_t cs[PNG_CASES];
    char dir[64], path[160], cmd[4096];
    size_t at;
    t_rng_t r;
    uint32_t digest = t_hash_init();
    int i, have_py, py_rc = -1;

    t_rng_seed(&r, 0x706e67u);
    snprintf(dir, sizeof dir, "/tmp/fl_png_%ld", (long)getpid());
    snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
    CHECK_EQ(system(cmd), 0);
    for (i = 0; i < PNG_CASES; i++) {
        uint8_t *file;
        size_t n = 0;
        cs[i].name = spec[i].name;
        cs[i].width = spec[i].w;
        cs[i].height = spec[i].h;
        cs[i].rgb = make_image(spec[i].kind, spec[i].w, spec[i].h, &r);
        CHECK(cs[i].rgb != NULL);
        if (!cs[i].rgb)
            return;
        snprintf(path, sizeof path, "%s/%s.png", dir, cs[i].name);
        CHECK_EQ(png_write(path, cs[i].rgb, cs[i].width, cs[i].height), 0);
        file = (uint8_t *)t_read_file(path, &n);
        CHECK(file != NULL);
        if (!file)
            continue;
        if (check_container(file, n, cs[i].width, cs[i].height) != 0)
            t_fail_msg(__FILE__, __LINE__, "%s: bad PNG container (%d)", cs[i].name,
                       check_container(file, n, cs[i].width, cs[i].height));
        digest = t_hash_bytes(digest, file, n);
        /* flat pictures compress to a small fraction of the pixels (long matches) */
        if (!strcmp(cs[i].name, "flat_big"))
            CHECK_LE(n, (size_t)cs[i].width * (size_t)cs[i].height * 3u / 100u);
        if (!strcmp(cs[i].name, "field") || !strcmp(cs[i].name, "flat_big"))
            t_info("%s %dx%d: %lu bytes (raw %lu)", cs[i].name, cs[i].width,
                   cs[i].height, (unsigned long)n, (unsigned long)((size_t)cs[i].width * (size_t)cs[i].height * 3u));
        free(file);
    }
    /* the writer is integer code: the same bytes on every target */
    t_digest("png.bytes", digest);
    /* bad arguments */
    CHECK_EQ(png_write(path, cs[0].rgb, 0, 1), -1);
    CHECK_EQ(png_write(path, NULL, 1, 1), -1);
    snprintf(path, sizeof path, "%s/no/such/dir.png", dir);
    CHECK_EQ(png_write(path, cs[0].rgb, 1, 1), -1);

    /* python3's zlib inflates every IDAT into NAME.raw (the filtered scanlines) */
    have_py = system("command -v python3 > /dev/null 2>&1") == 0;
    if (have_py) {
        at = (size_t)snprintf(cmd, sizeof cmd,
            "python3 -S -E -c 'import sys,zlib\n"
            "for p in sys.argv[1:]:\n"
            " d=open(p,\"rb\").read(); i=8; z=b\"\"\n"
            " while i<len(d):\n"
            "  n=int.from_bytes(d[i:i+4],\"big\"); t=d[i+4:i+8]\n"
            "  assert zlib.crc32(d[i+4:i+8+n])==int.from_bytes(d[i+8+n:i+12+n],\"big\"), p\n"
            "  if t==b\"IDAT\": z+=d[i+8:i+8+n]\n"
            "  i+=12+n\n"
            " o=zlib.decompressobj(); raw=o.decompress(z); assert o.eof and not o.unused_data, p\n"
            " open(p[:-4]+\".raw\",\"wb\").write(raw)\n' ");
        for (i = 0; i < PNG_CASES && at < sizeof cmd; i++)
            at += (size_t)snprintf(cmd + at, sizeof cmd - at, " %s/%s.png", dir, cs[i].name);
        py_rc = system(cmd);
        CHECK_EQ(py_rc, 0);
    } else {
        t_info("no python3, pixels not decoded");
    }
    for (i = 0; i < PNG_CASES; i++) {
        if (py_rc == 0) {
            size_t n = 0, want = ((size_t)cs[i].width * 3u + 1u) * (size_t)cs[i].height;
            uint8_t *raw, *back;
            snprintf(path, sizeof path, "%s/%s.raw", dir, cs[i].name);
            raw = (uint8_t *)t_read_file(path, &n);
            back = (uint8_t *)malloc((size_t)cs[i].width * (size_t)cs[i].height * 3u);
            CHECK(raw != NULL && back != NULL);
            if (raw && back) {
                if (n != want)
                    t_fail_msg(__FILE__, __LINE__, "%s: %lu inflated bytes, want %lu", cs[i].name,
                               (unsigned long)n, (unsigned long)want);
                else if (unfilter(raw, back, cs[i].width, cs[i].height) != 0)
                    t_fail_msg(__FILE__, __LINE__, "%s: bad filter type", cs[i].name);
                else
                    CHECK(memcmp(back, cs[i].rgb, (size_t)cs[i].width * (size_t)cs[i].height * 3u) == 0);
            }
            free(raw);
            free(back);
            remove(path);
        }
        snprintf(path, sizeof path, "%s/%s.png", dir, cs[i].name);
        remove(path);
        free(cs[i].rgb);
    }
    rmdir(dir);
}

void suite_png(void)
{
    t_run("png.roundtrip", test_roundtrip);
}

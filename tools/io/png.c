/* tools/io/png.c - PNG output in plain C, no library (no zlib, no OpenCV).
 *
 * 8-bit RGB, one IDAT chunk holding a zlib stream (header 0x78 0x01,
 * Adler-32 trailer) of DEFLATE blocks with the fixed Huffman code and a
 * greedy LZ77 (hash chains of 3-byte sequences over the 32 KiB window).
 * Each row gets the PNG filter (None, Sub or Up) with the smallest sum of
 * absolute values of its bytes taken as signed (the libpng heuristic).
 * CRC-32 table computed at run time.  Pictures of the field are mostly flat
 * areas, where runs become long matches at distance 3 or one row. */
#include "io/ppm.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PNG_WIN      32768u
#define PNG_HASH_BITS 15
#define PNG_HASH_SIZE (1u << PNG_HASH_BITS)
#define PNG_MAX_CHAIN 32
#define PNG_MIN_MATCH 3
#define PNG_MAX_MATCH 258
#define PNG_NICE      128

/* ---- growable byte buffer with a bit writer (LSB first, as DEFLATE) ---- */
typedef struct {
    uint8_t *data;
    size_t len, cap;
    uint32_t bits;      /* pending bits, LSB first */
    int nbits;
    int fail;
} png_buf_t;

static void buf_reserve(png_buf_t *b, size_t extra)
{
    size_t cap;
    uint8_t *p;
    if (b->fail || b->len + extra <= b->cap)
        return;
    cap = b->cap ? b->cap : 4096;
    while (cap < b->len + extra) {
        if (cap > SIZE_MAX / 2) {
            b->fail = 1;
            return;
        }
        cap *= 2;
    }
    p = (uint8_t *)realloc(b->data, cap);
    if (!p) {
        b->fail = 1;
        return;
    }
    b->data = p;
    b->cap = cap;
}

static void buf_byte(png_buf_t *b, uint8_t v)
{
    buf_reserve(b, 1);
    if (!b->fail)
        b->data[b->len++] = v;
}

static void buf_u32be(png_buf_t *b, uint32_t v)
{
    buf_byte(b, (uint8_t)(v >> 24));
    buf_byte(b, (uint8_t)(v >> 16));
    buf_byte(b, (uint8_t)(v >> 8));
    buf_byte(b, (uint8_t)v);
}

/* n (<= 16) bits of v, LSB first */
static void put_bits(png_buf_t *b, uint32_t v, int n)
{
    b->bits |= v << b->nbits;
    b->nbits += n;
    while (b->nbits >= 8) {
        buf_byte(b, (uint8_t)b->bits);
        b->bits >>= 8;
        b->nbits -= 8;
    }
}

static void flush_bits(png_buf_t *b)
{
    if (b->nbits > 0)
        buf_byte(b, (uint8_t)b->bits);
    b->bits = 0;
    b->nbits = 0;
}

/* Huffman codes are sent MSB first: reverse the n bits of code */
static uint32_t rev_bits(uint32_t code, int n)
{
    uint32_t r = 0;
    int i;
    for (i = 0; i < n; i++) {
        r = (r << 1) | (code & 1u);
        code >>= 1;
    }
    return r;
}

/* fixed literal/length code (RFC 1951 3.2.6) */
static void put_litlen(png_buf_t *b, unsigned sym)
{
    if (sym <= 143)
        put_bits(b, rev_bits(0x30u + sym, 8), 8);
    else if (sym <= 255)
        put_bits(b, rev_bits(0x190u + (sym - 144u), 9), 9);
    else if (sym <= 279)
        put_bits(b, rev_bits(sym - 256u, 7), 7);
    else
        put_bits(b, rev_bits(0xC0u + (sym - 280u), 8), 8);
}

static const uint16_t len_base[29] = {
    3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31,
    35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258 };
static const uint8_t len_extra[29] = {
    0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2,
    3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0 };
static const uint16_t dist_base[30] = {
    1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193,
    257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577 };
static const uint8_t dist_extra[30] = {
    0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6,
    7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13 };

static void put_match(png_buf_t *b, unsigned len, unsigned dist)
{
    int i = 28;
    while (len_base[i] > len)
        i--;
    put_litlen(b, 257u + (unsigned)i);
    if (len_extra[i])
        put_bits(b, len - len_base[i], len_extra[i]);
    i = 29;
    while (dist_base[i] > dist)
        i--;
    put_bits(b, rev_bits((uint32_t)i, 5), 5);   /* fixed distance code: 5 bits */
    if (dist_extra[i])
        put_bits(b, dist - dist_base[i], dist_extra[i]);
}

static unsigned hash3(const uint8_t *p)
{
    uint32_t v = ((uint32_t)p[0] << 16) | ((uint32_t)p[1] << 8) | p[2];
    return (unsigned)((v * 2654435761u) >> (32 - PNG_HASH_BITS));
}

/* zlib stream of src[0..n) into out: one final fixed-Huffman block */
static int deflate_fixed(png_buf_t *out, const uint8_t *src, size_t n)
{
    int32_t *head = (int32_t *)malloc(PNG_HASH_SIZE * sizeof *head);
    int32_t *prev = (int32_t *)malloc(PNG_WIN * sizeof *prev);
    uint32_t a = 1, s2 = 0;
    size_t i, k;
    if (!head || !prev) {
        free(head);
        free(prev);
        return -1;
    }
    for (k = 0; k < PNG_HASH_SIZE; k++)
        head[k] = -1;

    buf_byte(out, 0x78);
    buf_byte(out, 0x01);
    put_bits(out, 1, 1);        /* BFINAL */
    put_bits(out, 1, 2);        /* BTYPE 01: fixed Huffman */
    i = 0;
    while (i < n) {
        unsigned best_len = 0, best_dist = 0;
        if (i + PNG_MIN_MATCH <= n) {
            size_t maxlen = n - i < PNG_MAX_MATCH ? n - i : PNG_MAX_MATCH;
            unsigned h = hash3(src + i);
            int32_t cand = head[h];
            int chain = PNG_MAX_CHAIN;
            while (cand >= 0 && chain-- > 0 && i - (size_t)cand <= PNG_WIN - 262u) {
                const uint8_t *p = src + cand, *q = src + i;
                size_t l = 0;
                if (p[best_len] == q[best_len] || best_len == 0) {
                    while (l < maxlen && p[l] == q[l])
                        l++;
                    if (l > best_len) {
                        best_len = (unsigned)l;
                        best_dist = (unsigned)(i - (size_t)cand);
                        if (l >= PNG_NICE || l == maxlen)
                            break;
                    }
                }
                {
                    int32_t nx = prev[(size_t)cand & (PNG_WIN - 1)];
                    if (nx >= cand)
                        break;
                    cand = nx;
                }
            }
        }
        if (best_len >= PNG_MIN_MATCH) {
            size_t end = i + best_len;
            put_match(out, best_len, best_dist);
            /* insert every position of the match into the chains */
            for (; i < end; i++) {
                if (i + PNG_MIN_MATCH <= n) {
                    unsigned h = hash3(src + i);
                    prev[i & (PNG_WIN - 1)] = head[h];
                    head[h] = (int32_t)i;
                }
            }
        } else {
            put_litlen(out, src[i]);
            if (i + PNG_MIN_MATCH <= n) {
                unsigned h = hash3(src + i);
                prev[i & (PNG_WIN - 1)] = head[h];
                head[h] = (int32_t)i;
            }
            i++;
        }
    }
    put_litlen(out, 256);       /* end of block */
    flush_bits(out);
    free(head);
    free(prev);

    for (k = 0; k < n; k++) {   /* Adler-32 */
        a += src[k];
        if (a >= 65521u)
            a -= 65521u;
        s2 += a;
        if (s2 >= 65521u)
            s2 -= 65521u;
    }
    buf_u32be(out, (s2 << 16) | a);
    return out->fail ? -1 : 0;
}

static uint32_t crc32_update(const uint32_t *table, uint32_t crc, const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
    return crc;
}

/* one chunk: length, type, data, CRC of type and data */
static int write_chunk(FILE *f, const uint32_t *table, const char *type,
                       const uint8_t *data, size_t n)
{
    uint8_t hdr[8];
    uint8_t tail[4];
    uint32_t crc;
    hdr[0] = (uint8_t)(n >> 24);
    hdr[1] = (uint8_t)(n >> 16);
    hdr[2] = (uint8_t)(n >> 8);
    hdr[3] = (uint8_t)n;
    memcpy(hdr + 4, type, 4);
    crc = crc32_update(table, 0xFFFFFFFFu, hdr + 4, 4);
    crc = crc32_update(table, crc, data, n) ^ 0xFFFFFFFFu;
    tail[0] = (uint8_t)(crc >> 24);
    tail[1] = (uint8_t)(crc >> 16);
    tail[2] = (uint8_t)(crc >> 8);
    tail[3] = (uint8_t)crc;
    if (fwrite(hdr, 1, 8, f) != 8 || (n && fwrite(data, 1, n, f) != n) || fwrite(tail, 1, 4, f) != 4)
        return -1;
    return 0;
}

static unsigned absum(const uint8_t *p, size_t n)
{
    unsigned s = 0;
    size_t i;
    for (i = 0; i < n; i++)
        s += p[i] < 128 ? p[i] : 256u - p[i];
    return s;
}

/* filtered scanlines: per row a filter byte and 3*width bytes */
static void filter_rows(uint8_t *dst, const uint8_t *rgb, int width, int height)
{
    size_t rowlen = (size_t)width * 3u;
    int y;
    for (y = 0; y < height; y++) {
        const uint8_t *cur = rgb + (size_t)y * rowlen;
        const uint8_t *up = y > 0 ? cur - rowlen : NULL;
        uint8_t *row = dst + (size_t)y * (rowlen + 1u);
        uint8_t *sub = (uint8_t *)malloc(rowlen), *upf = (uint8_t *)malloc(rowlen);
        unsigned s_none, s_sub, s_up = ~0u;
        size_t x;
        if (!sub || !upf) {   /* out of memory: filter None */
            free(sub);
            free(upf);
            row[0] = 0;
            memcpy(row + 1, cur, rowlen);
            continue;
        }
        for (x = 0; x < rowlen; x++)
            sub[x] = (uint8_t)(cur[x] - (x >= 3 ? cur[x - 3] : 0));
        if (up)
            for (x = 0; x < rowlen; x++)
                upf[x] = (uint8_t)(cur[x] - up[x]);
        s_none = absum(cur, rowlen);
        s_sub = absum(sub, rowlen);
        if (up)
            s_up = absum(upf, rowlen);
        if (s_up <= s_sub && s_up <= s_none) {
            row[0] = 2;
            memcpy(row + 1, upf, rowlen);
        } else if (s_sub <= s_none) {
            row[0] = 1;
            memcpy(row + 1, sub, rowlen);
        } else {
            row[0] = 0;
            memcpy(row + 1, cur, rowlen);
        }
        free(sub);
        free(upf);
    }
}

int png_write(const char *path, const uint8_t *rgb, int width, int height)
{
    static const uint8_t sig[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
    uint32_t table[256];
    uint8_t ihdr[13];
    png_buf_t z;
    uint8_t *raw;
    size_t rawlen;
    FILE *f;
    uint32_t c, k;
    int j, rc;

    if (!path || !rgb || width <= 0 || height <= 0 || width > (1 << 24) || height > (1 << 24))
        return -1;
    if ((size_t)width * 3u + 1u > SIZE_MAX / (size_t)height)
        return -1;      /* the filtered scanlines would not fit in size_t */
    rawlen = ((size_t)width * 3u + 1u) * (size_t)height;
    if (rawlen > 0x7FFFFFFFu)
        return -1;      /* the LZ77 chains hold int32_t positions */
    raw = (uint8_t *)malloc(rawlen);
    if (!raw)
        return -1;
    filter_rows(raw, rgb, width, height);
    memset(&z, 0, sizeof z);
    if (deflate_fixed(&z, raw, rawlen) != 0) {
        free(raw);
        free(z.data);
        return -1;
    }
    free(raw);
    if (z.len > 0x7FFFFFFFu) {  /* a PNG chunk is at most 2^31 - 1 bytes */
        free(z.data);
        return -1;
    }

    for (k = 0; k < 256; k++) {
        c = k;
        for (j = 0; j < 8; j++)
            c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[k] = c;
    }
    ihdr[0] = (uint8_t)((uint32_t)width >> 24);
    ihdr[1] = (uint8_t)((uint32_t)width >> 16);
    ihdr[2] = (uint8_t)((uint32_t)width >> 8);
    ihdr[3] = (uint8_t)width;
    ihdr[4] = (uint8_t)((uint32_t)height >> 24);
    ihdr[5] = (uint8_t)((uint32_t)height >> 16);
    ihdr[6] = (uint8_t)((uint32_t)height >> 8);
    ihdr[7] = (uint8_t)height;
    ihdr[8] = 8;    /* bit depth */
    ihdr[9] = 2;    /* colour type RGB */
    ihdr[10] = 0;   /* deflate */
    ihdr[11] = 0;   /* adaptive filtering */
    ihdr[12] = 0;   /* no interlace */

    f = fopen(path, "wb");
    if (!f) {
        free(z.data);
        return -1;
    }
    rc = fwrite(sig, 1, 8, f) == 8 ? 0 : -1;
    if (rc == 0)
        rc = write_chunk(f, table, "IHDR", ihdr, 13);
    if (rc == 0)
        rc = write_chunk(f, table, "IDAT", z.data, z.len);
    if (rc == 0)
        rc = write_chunk(f, table, "IEND", NULL, 0);
    free(z.data);
    if (fclose(f) != 0)
        rc = -1;
    return rc;
}

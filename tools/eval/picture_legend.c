/*
 * tools/eval/picture_legend.c - legends, captions and the scanner overlay
 * of the tools' pictures (picture.h).
 *
 * Layout of the strip (width = the image's): PIC_PAD px margin, the caption
 * lines (FONT_LINE px each, wrapped at spaces), then the legend items in
 * rows of PIC_ROW px: an 11 x 11 swatch showing the mark as drawn in the
 * picture, 4 px, the label; items flow left to right and wrap.  The colors
 * of each set are those of the drawing code (det_draw, pic_belief,
 * pic_frame, scantool_picture, eval-detect, render --mask): keep them in
 * step.  On pictures 1000 px wide or more (frame | belief) everything is
 * drawn at twice the size.
 */
#include "eval/picture.h"
#include "io/font.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PIC_PAD 4
#define PIC_SW 11      /* swatch size */
#define PIC_ROW 14     /* legend row height */
#define PIC_GAP 12     /* between items */

typedef enum {
    MK_FILL, MK_BOX, MK_LINE, MK_DOTTED, MK_DOTS, MK_RING, MK_CROSS, MK_SQUARE, MK_RAMP,
    MK_TICK, MK_PART_IN, MK_PART_OUT
} pic_mark_t;

typedef struct {
    pic_mark_t mark;
    uint8_t rgb[3];
    const char *text;
} pic_item_t;

static const pic_item_t set_detect[] = {
    {MK_DOTS, {160, 160, 160}, "line point"},
    {MK_DOTS, {255, 150, 200}, "line point (luma)"},
    {MK_LINE, {40, 80, 255}, "line segment"},
    {MK_LINE, {0, 230, 230}, "circle: chord, fit, centre"},
    {MK_BOX, {255, 0, 0}, "L crossing"},
    {MK_BOX, {255, 150, 0}, "T crossing"},
    {MK_BOX, {255, 0, 255}, "X crossing"},
    {MK_BOX, {150, 60, 255}, "penalty/centre mark"},
    {MK_BOX, {0, 255, 0}, "post foot G"},
    {MK_BOX, {255, 255, 255}, "post foot unseen"},
    {MK_BOX, {200, 255, 0}, "post top U"},
    {MK_LINE, {200, 255, 0}, "post side tick (left/right)"},
};
static const pic_item_t set_model[] = {
    {MK_DOTTED, {255, 235, 0}, "field model seen from the estimate"},
};
static const pic_item_t set_belief[] = {
    {MK_FILL, {18, 62, 28}, "belief 0"},
    {MK_RAMP, {0, 0, 0}, "belief low..high"},
    {MK_TICK, {0, 0, 0}, "cell heading"},
    {MK_LINE, {235, 235, 235}, "field lines"},
    {MK_RING, {255, 40, 255}, "estimate (longer = more reliable)"},
    {MK_SQUARE, {255, 255, 255}, "observation from the estimate"},
    {MK_SQUARE, {255, 220, 0}, "post/beacon"},
};
static const pic_item_t set_particles[] = {
    {MK_FILL, {18, 62, 28}, "carpet"},
    {MK_PART_IN, {0, 0, 0}, "particle in the estimate's cluster (shade = weight, tick = heading)"},
    {MK_PART_OUT, {0, 0, 0}, "other particle"},
    {MK_DOTTED, {150, 255, 60}, "cluster spread (2 sd)"},
    {MK_LINE, {235, 235, 235}, "field lines"},
    {MK_RING, {255, 40, 255}, "estimate (longer = more reliable)"},
    {MK_SQUARE, {255, 255, 255}, "observation from the estimate"},
    {MK_SQUARE, {255, 220, 0}, "post/beacon"},
};
static const pic_item_t set_hlv[] = {
    {MK_FILL, {120, 200, 255}, "white surrounded by green (mask)"},
    {MK_FILL, {255, 0, 0}, "skeleton"},
    {MK_BOX, {255, 150, 0}, "T crossing"},
    {MK_BOX, {255, 0, 255}, "X crossing"},
    {MK_DOTS, {0, 0, 0}, "white point"},
    {MK_BOX, {0, 255, 0}, "post (foot, column range)"},
    {MK_BOX, {255, 255, 0}, "pole YBY (bands)"},
    {MK_BOX, {0, 160, 255}, "pole BYB (bands)"},
};
static const pic_item_t set_truth[] = {
    {MK_RING, {0, 230, 255}, "truth"},
};
static const pic_item_t set_classes[] = {
    {MK_FILL, {0, 170, 0}, "green cell"},
    {MK_FILL, {255, 255, 255}, "white cell"},
    {MK_FILL, {255, 220, 0}, "yellow cell"},
    {MK_FILL, {60, 0, 60}, "other cell"},
};
static const pic_item_t set_border[] = {
    {MK_LINE, {255, 0, 0}, "field border"},
    {MK_DOTTED, {255, 255, 255}, "border search start (horizon)"},
};
static const pic_item_t set_scan[] = {
    {MK_FILL, {60, 60, 60}, "above the border (dimmed)"},
    {MK_FILL, {255, 255, 255}, "white cell"},
    {MK_FILL, {255, 255, 0}, "yellow cell"},
    {MK_LINE, {255, 0, 0}, "field border"},
    {MK_CROSS, {0, 255, 255}, "post foot (yellow->green)"},
};
static const pic_item_t set_eval[] = {
    {MK_RING, {255, 255, 255}, "truth, detected"},
    {MK_RING, {255, 40, 40}, "truth, missed"},
    {MK_RING, {120, 120, 120}, "truth, not required"},
};
static const pic_item_t set_mask[] = {
    {MK_FILL, {40, 40, 40}, "background"},
    {MK_FILL, {30, 140, 50}, "carpet"},
    {MK_FILL, {255, 255, 255}, "line"},
    {MK_FILL, {240, 220, 0}, "goal"},
    {MK_FILL, {60, 90, 230}, "robot"},
    {MK_FILL, {255, 120, 0}, "ball"},
    {MK_FILL, {230, 60, 200}, "beacon"},
    {MK_DOTS, {255, 0, 0}, "carpet edge"},
};

static const struct {
    unsigned bit;
    const pic_item_t *items;
    int n;
} pic_sets[] = {
#define PIC_SET(bit, a) {bit, a, (int)(sizeof a / sizeof a[0])}
    PIC_SET(PIC_LEGEND_SCAN, set_scan),   PIC_SET(PIC_LEGEND_CLASSES, set_classes),
    PIC_SET(PIC_LEGEND_BORDER, set_border), PIC_SET(PIC_LEGEND_DETECT, set_detect),
    PIC_SET(PIC_LEGEND_EVAL, set_eval),   PIC_SET(PIC_LEGEND_MODEL, set_model),
    PIC_SET(PIC_LEGEND_BELIEF, set_belief), PIC_SET(PIC_LEGEND_PARTICLES, set_particles),
    PIC_SET(PIC_LEGEND_TRUTH, set_truth),
    PIC_SET(PIC_LEGEND_MASK, set_mask),
    PIC_SET(PIC_LEGEND_HLV, set_hlv),
#undef PIC_SET
};

static void put(host_image_t *im, int u, int v, const uint8_t *c)
{
    if (im == NULL || u < 0 || v < 0 || u >= im->width || v >= im->height)
        return;
    memcpy(im->rgb + 3 * ((size_t)v * (size_t)im->width + (size_t)u), c, 3);
}

/* Swatch pixel (i, j) of the 11 x 11 grid at (x, y), sc x sc screen pixels. */
static void sput(host_image_t *im, int x, int y, int sc, int i, int j, const uint8_t *c)
{
    int a, b;
    for (b = 0; b < sc; b++)
        for (a = 0; a < sc; a++)
            put(im, x + i * sc + a, y + j * sc + b, c);
}

static void swatch(host_image_t *im, int x, int y, int sc, const pic_item_t *it)
{
    static const uint8_t edge[3] = {100, 100, 100}, black[3] = {0, 0, 0},
                         tick_bg[3] = {250, 160, 30};
    int i, j, c = PIC_SW / 2;
    switch (it->mark) {
    case MK_FILL:
        for (j = 0; j < PIC_SW; j++)
            for (i = 0; i < PIC_SW; i++)
                sput(im, x, y, sc, i, j,
                     (i == 0 || j == 0 || i == PIC_SW - 1 || j == PIC_SW - 1) ? edge : it->rgb);
        break;
    case MK_RAMP:
        for (i = 0; i < PIC_SW; i++) {
            /* pic_belief's ramp: dark purple, red, orange, pale yellow */
            static const uint8_t stop[4][3] = {
                {40, 10, 70}, {220, 60, 40}, {250, 160, 30}, {255, 250, 170}};
            const uint8_t *col = stop[i * 4 / PIC_SW];
            for (j = 0; j < PIC_SW; j++)
                sput(im, x, y, sc, i, j, col);
        }
        break;
    case MK_TICK:
        for (j = 0; j < PIC_SW; j++)
            for (i = 0; i < PIC_SW; i++)
                sput(im, x, y, sc, i, j, tick_bg);
        for (i = c; i < PIC_SW - 1; i++)
            sput(im, x, y, sc, i, c, black);
        break;
    case MK_PART_IN:
    case MK_PART_OUT: {
        /* three particles on the carpet, light to heavy, ticks to the right */
        static const uint8_t carpet[3] = {18, 62, 28};
        static const int pu[3] = {2, 2, 6}, pv[3] = {2, 8, 5};
        static const double pw[3] = {0.1, 0.5, 1.0};
        int n;
        for (j = 0; j < PIC_SW; j++)
            for (i = 0; i < PIC_SW; i++)
                sput(im, x, y, sc, i, j, carpet);
        for (n = 0; n < 3; n++) {
            uint8_t col[3];
            pic_particle_color(pw[n], it->mark == MK_PART_IN, col);
            for (i = -1; i <= 3; i++)
                sput(im, x, y, sc, pu[n] + i, pv[n], col);
            sput(im, x, y, sc, pu[n], pv[n] - 1, col);
            sput(im, x, y, sc, pu[n], pv[n] + 1, col);
        }
        break;
    }
    case MK_BOX:
        for (i = -3; i <= 3; i++) {
            sput(im, x, y, sc, c + i, c - 3, it->rgb);
            sput(im, x, y, sc, c + i, c + 3, it->rgb);
            sput(im, x, y, sc, c - 3, c + i, it->rgb);
            sput(im, x, y, sc, c + 3, c + i, it->rgb);
        }
        break;
    case MK_LINE:
    case MK_DOTTED:
        for (i = 0; i < PIC_SW; i++)
            if (it->mark == MK_LINE || !(i & 2))
                sput(im, x, y, sc, i, c, it->rgb);
        break;
    case MK_DOTS:
        sput(im, x, y, sc, 2, c + 1, it->rgb);
        sput(im, x, y, sc, c, c - 1, it->rgb);
        sput(im, x, y, sc, PIC_SW - 3, c + 1, it->rgb);
        break;
    case MK_RING:
        for (i = 0; i < 32; i++)
            sput(im, x, y, sc, c + (int)lround(4.5 * cos(i * 0.19635)),
                 c + (int)lround(4.5 * sin(i * 0.19635)), it->rgb);
        break;
    case MK_CROSS:
        for (i = -3; i <= 3; i++) {
            sput(im, x, y, sc, c + i, c, it->rgb);
            sput(im, x, y, sc, c, c + i, it->rgb);
        }
        break;
    case MK_SQUARE:
        for (j = -3; j <= 3; j++)
            for (i = -3; i <= 3; i++)
                sput(im, x, y, sc, c + i, c + j,
                     (abs(i) == 3 || abs(j) == 3) ? black : it->rgb);
        break;
    }
}

/* Whether an identical item (mark, color, text) of the sets comes before
 * item i of set k: shown once (a grid's and a particle picture's legends
 * side by side share the lines, estimate, observations). */
static int pic_item_repeated(unsigned sets, int k, int i)
{
    const pic_item_t *it = &pic_sets[k].items[i];
    int k2, i2;
    for (k2 = 0; k2 <= k; k2++) {
        if (!(sets & pic_sets[k2].bit))
            continue;
        for (i2 = 0; i2 < (k2 == k ? i : pic_sets[k2].n); i2++) {
            const pic_item_t *o = &pic_sets[k2].items[i2];
            if (o->mark == it->mark && !memcmp(o->rgb, it->rgb, 3) && !strcmp(o->text, it->text))
                return 1;
        }
    }
    return 0;
}

/* Lay out (and, with im, draw) the strip at row y0 of an image of width W;
 * returns its height. */
static int pic_legend_layout(host_image_t *im, int W, int y0, unsigned sets,
                             const char *caption)
{
    static const uint8_t fg[3] = {PIC_LEGEND_FG, PIC_LEGEND_FG, PIC_LEGEND_FG};
    /* wide pictures (frame | belief) get the strip at twice the size */
    int cs = W >= 1000 ? 2 : 1;
    int y = y0 + PIC_PAD, x, k, i, max_chars = (W - 2 * PIC_PAD) / (FONT_ADVANCE * cs);
    char line[512];
    if (max_chars < 8)
        max_chars = 8;
    if (max_chars > (int)sizeof line - 1)
        max_chars = (int)sizeof line - 1;
    /* caption: each '\n' line wrapped at spaces to max_chars */
    if (caption != NULL && caption[0] != '\0') {
        const char *p = caption;
        while (*p) {
            const char *eol = strchr(p, '\n');
            int len = eol ? (int)(eol - p) : (int)strlen(p), take = len;
            if (take > max_chars) {
                take = max_chars;
                while (take > 0 && p[take] != ' ')
                    take--;
                if (take == 0)
                    take = max_chars;
            }
            memcpy(line, p, (size_t)take);
            line[take] = '\0';
            if (im)
                font_draw(im, PIC_PAD, y, line, fg, cs);
            y += FONT_LINE * cs;
            p += take;
            while (*p == ' ')
                p++;
            if (take == len && *p == '\n')
                p++;
        }
        y += 2;
    }
    x = PIC_PAD;
    for (k = 0; k < (int)(sizeof pic_sets / sizeof pic_sets[0]); k++) {
        if (!(sets & pic_sets[k].bit))
            continue;
        for (i = 0; i < pic_sets[k].n; i++) {
            const pic_item_t *it = &pic_sets[k].items[i];
            int w = (PIC_SW + 4) * cs + font_text_width(it->text, cs);
            if (pic_item_repeated(sets, k, i))
                continue;
            if (x > PIC_PAD && x + w > W - PIC_PAD) {
                x = PIC_PAD;
                y += PIC_ROW * cs;
            }
            if (im) {
                swatch(im, x, y, cs, it);
                font_draw(im, x + (PIC_SW + 4) * cs, y + (PIC_SW - 7) / 2 * cs, it->text, fg,
                          cs);
            }
            x += w + PIC_GAP * cs;
        }
    }
    if (x > PIC_PAD)
        y += PIC_ROW * cs;
    return y + PIC_PAD - y0;
}

int pic_legend_height(int width, unsigned sets, const char *caption)
{
    return pic_legend_layout(NULL, width, 0, sets, caption);
}

int pic_add_legend(const host_image_t *img, unsigned sets, const char *caption,
                   host_image_t *out)
{
    int H;
    memset(out, 0, sizeof *out);
    if (img == NULL || img->rgb == NULL || img->width <= 0 || img->height <= 0)
        return -1;
    H = pic_legend_height(img->width, sets, caption);
    *out = host_image_new(img->width, img->height + H, PIC_LEGEND_BG, PIC_LEGEND_BG,
                          PIC_LEGEND_BG);
    if (out->rgb == NULL)
        return -1;
    memcpy(out->rgb, img->rgb, (size_t)img->width * (size_t)img->height * 3);
    pic_legend_layout(out, img->width, img->height, sets, caption);
    return 0;
}

int pic_legend_inplace(host_image_t *img, unsigned sets, const char *caption)
{
    host_image_t out;
    if (pic_add_legend(img, sets, caption, &out) != 0)
        return -1;
    host_image_free(img);
    *img = out;
    return 0;
}

void pic_belief_caption(char *buf, size_t n, double t_s, long frame,
                        const fl_loc_estimate_t *est, double err_mm, double err_deg)
{
    size_t k = 0;
    if (n == 0)
        return;
    buf[0] = '\0';
#define PIC_CAT(...)                                                              \
    do {                                                                          \
        if (k < n) {                                                              \
            int w_ = snprintf(buf + k, n - k, __VA_ARGS__);                       \
            k += w_ > 0 ? (size_t)w_ : 0;                                         \
        }                                                                         \
    } while (0)
    if (t_s >= 0)
        PIC_CAT("t %.1f s  ", t_s);
    if (frame >= 0)
        PIC_CAT("frame %ld  ", frame);
    if (est != NULL)
        PIC_CAT("estimate %d %d mm %.0f deg  reliability %.2f", (int)est->x_mm, (int)est->y_mm,
                est->heading * (180.0 / 32768.0), est->reliability_q16 / 65536.0);
    if (err_mm >= 0)
        PIC_CAT("\nerror %.0f mm %.1f deg", err_mm, err_deg);
    else if (est != NULL)
        PIC_CAT("\nerror: unknown (no truth)");
#undef PIC_CAT
}

void pic_scan_overlay(const fl_scan_t *s, uint8_t *rgb, int w, int h, int classes,
                      int border)
{
    static const uint8_t tint[4][3] = {
        {60, 0, 60}, {0, 170, 0}, {255, 255, 255}, {255, 220, 0}};   /* by fl_color_class_t */
    int cs, rs, u, v, i, k;
    if (s == NULL || rgb == NULL || s->width != w || s->height != h || s->cols <= 0)
        return;
    cs = s->params.col_step;
    rs = s->params.row_step;
    if (classes)
        for (v = 0; v < h; v++)
            for (u = 0; u < w; u++) {
                fl_color_class_t c = fl_scan_class_at(s, u / cs, v / rs);
                uint8_t *p = rgb + 3 * ((size_t)v * (size_t)w + (size_t)u);
                for (k = 0; k < 3; k++)   /* 70 % class, 30 % image */
                    p[k] = (uint8_t)((7 * tint[c & 3][k] + 3 * p[k] + 5) / 10);
            }
    if (border) {
        static const uint8_t red[3] = {255, 0, 0}, white[3] = {255, 255, 255};
        host_image_t im;
        im.width = w;
        im.height = h;
        im.rgb = rgb;
        if (s->start_v > 0 && s->start_v < h)
            for (u = 0; u < w; u++)
                if (!(u & 2))
                    put(&im, u, s->start_v, white);
        for (i = 0; i < s->cols; i++) {
            int b = s->border_v[i], nb = i + 1 < s->cols ? s->border_v[i + 1] : b;
            if (b >= h)
                continue;
            for (u = i * cs; u < (i + 1) * cs && u < w; u++)
                put(&im, u, b, red);
            /* vertical join to the next column's border */
            if (nb < h)
                for (v = b < nb ? b : nb; v <= (b < nb ? nb : b); v++)
                    put(&im, (i + 1) * cs - 1 < w ? (i + 1) * cs - 1 : w - 1, v, red);
        }
    }
}

/*
 * tools/io/realdata.c - loader for ../shared/realdata (see realdata.h).
 *
 * Algorithm: a small CSV reader (comma separated, double-quoted fields with
 * "" escapes, '#' comment lines, CR/LF tolerant) splits each line into
 * fields; the UvA and physar parsers map the header's column names to
 * their fields, so a reordered or extended file still loads, and every
 * number is checked (strtod must consume the whole field).
 * Memory: the file text and the record arrays (malloc'd, freed by the
 * callers through rd_*_free).  Cost: linear in the file size.
 */
#include "io/realdata.h"
#include "io/textfile.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define RD_MAX_COLS 32
#define RD_LINE_MAX 4096

/* ---- the folder ---------------------------------------------------------- */

static int rd_is_dir(const char *p)
{
    struct stat st;
    return p && stat(p, &st) == 0 && S_ISDIR(st.st_mode);
}

const char *rd_dir(void)
{
    static char buf[4096];
    static const char *cands[] = {"../shared/realdata", "../../shared/realdata"};
    const char *env = getenv("FIELDLOC_REALDATA");
    size_t i;
    ssize_t n;

    if (env && *env) {
        if (!rd_is_dir(env) || strlen(env) >= sizeof buf)
            return NULL;
        strcpy(buf, env);
        return buf;
    }
    for (i = 0; i < sizeof cands / sizeof cands[0]; i++)
        if (rd_is_dir(cands[i])) {
            strcpy(buf, cands[i]);
            return buf;
        }
    /* <ancestor of the executable's folder>/../shared/realdata: the
     * executable sits in <repo>/build/ or deeper (build/h_x/...) */
    n = readlink("/proc/self/exe", buf, sizeof buf - 64);
    if (n > 0) {
        int up;
        buf[n] = '\0';
        for (up = 0; up < 4; up++) {
            char *slash = strrchr(buf, '/');
            size_t len;
            if (!slash || slash == buf)
                break;
            *slash = '\0'; /* buf = a parent folder */
            len = strlen(buf);
            strcat(buf, "/../shared/realdata");
            if (up > 0 && rd_is_dir(buf))
                return buf;
            buf[len] = '\0';
        }
    }
    return NULL;
}

const char *rd_skip_message(void)
{
    return "skipped: ../shared/realdata not found (set FIELDLOC_REALDATA to its path)";
}

int rd_path(char *buf, size_t buf_len, const char *dir, const char *file)
{
    int n;
    if (!buf || !dir || !file || buf_len == 0)
        return -1;
    n = snprintf(buf, buf_len, "%s/%s", dir, file);
    return (n < 0 || (size_t)n >= buf_len) ? -1 : 0;
}

int rd_read_ppm(const char *dir, const char *file, host_image_t *img, char *err,
                int err_len)
{
    char path[4096];
    if (!img)
        return -1;
    img->rgb = NULL;
    if (rd_path(path, sizeof path, dir, file) != 0) {
        tf_err(err, err_len, "path too long");
        return -1;
    }
    return ppm_read(path, img, err, err_len);
}

fl_status_t rd_image_view(const host_image_t *img, fl_image_t *view)
{
    if (!img || !view || !img->rgb)
        return FL_ERR_NULL;
    return fl_image_init_packed(view, FL_FMT_RGB888, img->rgb, (int32_t)img->width,
                                (int32_t)img->height, (int32_t)(3 * img->width));
}

/* ---- CSV ------------------------------------------------------------------ */

typedef struct {
    char buf[RD_LINE_MAX];          /* unquoted fields, NUL separated */
    char *col[RD_MAX_COLS];
    int n;
} rd_row_t;

/* Split the line starting at *p (ends at '\n' or NUL) into row; advance *p
 * past the line.  Returns 0, or -1 when the line is too long, has too many
 * fields or an unterminated quote. */
static int rd_csv_line(const char **p, rd_row_t *row)
{
    const char *s = *p;
    size_t o = 0;
    int in_q = 0, bad = 0;

    row->n = 0;
    row->col[row->n++] = row->buf;
    for (;; s++) {
        char c = *s;
        if (c == '\0' || (!in_q && c == '\n'))
            break;
        if (in_q && c == '\n') { /* no multi-line fields in these files */
            bad = 1;
            break;
        }
        if (c == '"') {
            if (in_q && s[1] == '"') {
                c = '"';
                s++;
            } else {
                in_q = !in_q;
                continue;
            }
        } else if (c == ',' && !in_q) {
            if (o + 1 >= sizeof row->buf || row->n >= RD_MAX_COLS) {
                bad = 1;
                break;
            }
            row->buf[o++] = '\0';
            row->col[row->n++] = row->buf + o;
            continue;
        } else if (c == '\r' && !in_q && (s[1] == '\n' || s[1] == '\0')) {
            continue;
        }
        if (o + 1 >= sizeof row->buf) {
            bad = 1;
            break;
        }
        row->buf[o++] = c;
    }
    row->buf[o] = '\0';
    while (*s && *s != '\n')
        s++;
    if (*s == '\n')
        s++;
    *p = s;
    return (bad || in_q) ? -1 : 0;
}

/* Next non-empty, non-comment line into row; 1 when found, 0 at the end,
 * -1 on a malformed line.  *line_no counts lines (1-based). */
static int rd_next_row(const char **p, rd_row_t *row, int *line_no)
{
    while (**p) {
        const char *s = *p;
        (*line_no)++;
        while (*s == ' ' || *s == '\t' || *s == '\r')
            s++;
        if (*s == '#' || *s == '\n' || *s == '\0') {
            while (**p && **p != '\n')
                (*p)++;
            if (**p == '\n')
                (*p)++;
            continue;
        }
        return rd_csv_line(p, row) == 0 ? 1 : -1;
    }
    return 0;
}

static int rd_col_index(const rd_row_t *hdr, const char *name)
{
    int i;
    for (i = 0; i < hdr->n; i++)
        if (strcmp(hdr->col[i], name) == 0)
            return i;
    return -1;
}

static int rd_num(const char *s, double *v)
{
    char *end;
    double d;
    while (*s == ' ')
        s++;
    if (!*s)
        return -1;
    errno = 0;
    d = strtod(s, &end);
    while (*end == ' ')
        end++;
    /* |d| <= 1e9: every field of these files is far smaller, and later
     * conversions to int must stay defined (found by fuzz_uva_csv) */
    if (*end || errno || !isfinite(d) || d > 1e9 || d < -1e9)
        return -1;
    *v = d;
    return 0;
}

static int rd_copy(char *dst, size_t dst_len, const char *src)
{
    size_t n = strlen(src);
    if (n >= dst_len)
        return -1;
    memcpy(dst, src, n + 1);
    return 0;
}

static char *rd_read_text(const char *path, char *err, int err_len)
{
    FILE *f;
    long n;
    char *t;
    if (!path) {
        tf_err(err, err_len, "NULL path");
        return NULL;
    }
    f = fopen(path, "rb");
    if (!f) {
        tf_err(err, err_len, "%s: %s", path, strerror(errno));
        return NULL;
    }
    if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0 ||
        n > (64L << 20)) {
        tf_err(err, err_len, "%s: cannot size the file", path);
        fclose(f);
        return NULL;
    }
    t = malloc((size_t)n + 1);
    if (!t || fread(t, 1, (size_t)n, f) != (size_t)n) {
        tf_err(err, err_len, "%s: read error", path);
        free(t);
        fclose(f);
        return NULL;
    }
    t[n] = '\0';
    fclose(f);
    return t;
}

/* ---- UvA 2013 ------------------------------------------------------------- */

/* "X:162,156 L:36,98 ..." -> features (type one of types, u - off,
 * v - off).  Count or -1. */
static int rd_features(const char *s, rd_feature_t *feat, int cap, const char *types,
                       double off)
{
    int n = 0;
    for (;;) {
        char type;
        char *end;
        double u, v;
        while (*s == ' ' || *s == '\t')
            s++;
        if (!*s)
            return n;
        type = *s++;
        if (!type || !strchr(types, type) || *s++ != ':')
            return -1;
        errno = 0;
        u = strtod(s, &end);
        if (end == s || *end != ',')
            return -1;
        s = end + 1;
        v = strtod(s, &end);
        if (end == s || errno || (*end && *end != ' ' && *end != '\t'))
            return -1;
        s = end;
        if (n >= cap)
            return -1;
        feat[n].type = type;
        feat[n].u = u - off;
        feat[n].v = v - off;
        n++;
    }
}

/* UvA: 1-based MATLAB pixels -> 0-based. */
static int rd_uva_features(const char *s, rd_feature_t *feat, int cap)
{
    return rd_features(s, feat, cap, "XLTGU", 1.0);
}

int rd_uva_parse(const char *text, rd_uva_set_t *out, char *err, int err_len)
{
    static const char *names[] = {"file", "in_realdata", "set", "index", "x_cm", "y_cm",
                                  "theta_deg", "head_pitch_rad", "head_yaw_rad",
                                  "n_features", "features"};
    enum { C_FILE, C_IN, C_SET, C_INDEX, C_X, C_Y, C_TH, C_HP, C_HY, C_NF, C_FEAT, C_N };
    rd_row_t *row, hdr;
    int ci[C_N], i, line = 0, r, cap = 0;
    const char *p = text;

    if (!out)
        return -1;
    out->rec = NULL;
    out->n = 0;
    if (!text) {
        tf_err(err, err_len, "NULL text");
        return -1;
    }
    r = rd_next_row(&p, &hdr, &line);
    if (r <= 0) {
        tf_err(err, err_len, "line %d: no header", line);
        return -1;
    }
    for (i = 0; i < C_N; i++) {
        ci[i] = rd_col_index(&hdr, names[i]);
        if (ci[i] < 0) {
            tf_err(err, err_len, "header lacks column %s", names[i]);
            return -1;
        }
    }
    row = malloc(sizeof *row);
    if (!row) {
        tf_err(err, err_len, "out of memory");
        return -1;
    }
    while ((r = rd_next_row(&p, row, &line)) == 1) {
        rd_uva_record_t *rec;
        double v[C_N];
        int k, nf;
        if (row->n != hdr.n) {
            tf_err(err, err_len, "line %d: %d fields, header has %d", line, row->n, hdr.n);
            goto fail;
        }
        if (out->n == cap) {
            int nc = cap ? 2 * cap : 32;
            rd_uva_record_t *nr = realloc(out->rec, (size_t)nc * sizeof *nr);
            if (!nr) {
                tf_err(err, err_len, "out of memory");
                goto fail;
            }
            out->rec = nr;
            cap = nc;
        }
        rec = &out->rec[out->n];
        memset(rec, 0, sizeof *rec);
        if (rd_copy(rec->file, sizeof rec->file, row->col[ci[C_FILE]]) ||
            rd_copy(rec->set, sizeof rec->set, row->col[ci[C_SET]]) ||
            rd_copy(rec->index, sizeof rec->index, row->col[ci[C_INDEX]]) || !rec->file[0]) {
            tf_err(err, err_len, "line %d: empty or too long name", line);
            goto fail;
        }
        for (k = C_IN; k <= C_NF; k++) {
            if (k == C_SET || k == C_INDEX)
                continue;
            if (rd_num(row->col[ci[k]], &v[k]) != 0) {
                tf_err(err, err_len, "line %d: bad number in column %s: '%s'", line, names[k],
                       row->col[ci[k]]);
                goto fail;
            }
        }
        rec->in_realdata = (int)v[C_IN];
        rec->x_cm = v[C_X];
        rec->y_cm = v[C_Y];
        rec->theta_deg = v[C_TH];
        rec->head_pitch_rad = v[C_HP];
        rec->head_yaw_rad = v[C_HY];
        nf = rd_uva_features(row->col[ci[C_FEAT]], rec->feat, RD_MAX_FEATURES);
        if (nf < 0) {
            tf_err(err, err_len, "line %d: bad feature list '%s'", line, row->col[ci[C_FEAT]]);
            goto fail;
        }
        if (v[C_NF] != (double)nf) {
            tf_err(err, err_len, "line %d: n_features %g but %d features listed", line, v[C_NF],
                   nf);
            goto fail;
        }
        rec->n_features = nf;
        out->n++;
    }
    if (r < 0) {
        tf_err(err, err_len, "line %d: malformed CSV line", line);
        goto fail;
    }
    free(row);
    return 0;
fail:
    free(row);
    rd_uva_free(out);
    return -1;
}

int rd_uva_load(const char *path, rd_uva_set_t *out, char *err, int err_len)
{
    char *t;
    int r;
    if (!out)
        return -1;
    out->rec = NULL;
    out->n = 0;
    t = rd_read_text(path, err, err_len);
    if (!t)
        return -1;
    r = rd_uva_parse(t, out, err, err_len);
    free(t);
    return r;
}

void rd_uva_free(rd_uva_set_t *set)
{
    if (!set)
        return;
    free(set->rec);
    set->rec = NULL;
    set->n = 0;
}

static fl_angle_t rd_angle_from_rad(double rad)
{
    double turns = rad / (2.0 * 3.14159265358979323846);
    long a = lround((turns - floor(turns + 0.5)) * 65536.0); /* [-32768, 32768] */
    if (a >= 32768)
        a -= 65536;
    return (fl_angle_t)a;
}

void rd_uva_pose(const rd_uva_record_t *r, int32_t *x_mm, int32_t *y_mm, fl_angle_t *heading)
{
    if (!r)
        return;
    if (x_mm)
        *x_mm = (int32_t)lround(r->x_cm * 10.0);
    if (y_mm)
        *y_mm = (int32_t)lround(r->y_cm * 10.0);
    if (heading)
        *heading = rd_angle_from_rad(r->theta_deg * (3.14159265358979323846 / 180.0));
}

void rd_uva_camera_pose(const rd_uva_record_t *r, const fl_camera_model_t *m,
                        fl_camera_pose_t *pose)
{
    if (!r || !m || !pose)
        return;
    memset(pose, 0, sizeof *pose);
    pose->neck_height_mm = m->default_neck_height_mm;
    pose->head_pitch = rd_angle_from_rad(r->head_pitch_rad);
    pose->head_yaw = rd_angle_from_rad(r->head_yaw_rad);
    pose->pitch_offset = m->default_pitch_offset;
}

void rd_physar_camera_pose(const rd_physar_record_t *r, const fl_camera_model_t *m,
                           fl_camera_pose_t *pose)
{
    if (!r || !m || !pose)
        return;
    memset(pose, 0, sizeof *pose);
    pose->neck_height_mm = m->default_neck_height_mm;
    pose->head_pitch = rd_angle_from_rad(r->head_pitch_rad);
    pose->head_yaw = rd_angle_from_rad(r->head_yaw_rad);
    pose->pitch_offset = m->default_pitch_offset;
    pose->torso_roll = rd_angle_from_rad(r->imu_anglex_rad);
    pose->torso_pitch = rd_angle_from_rad(r->imu_angley_rad);
}

void rd_uva_field_to_robot(const rd_uva_record_t *r, double fx_mm, double fy_mm,
                           double *rx_mm, double *ry_mm)
{
    double th, c, s, dx, dy;
    if (!r)
        return;
    th = r->theta_deg * (3.14159265358979323846 / 180.0);
    c = cos(th);
    s = sin(th);
    dx = fx_mm - r->x_cm * 10.0;
    dy = fy_mm - r->y_cm * 10.0;
    if (rx_mm)
        *rx_mm = c * dx + s * dy;
    if (ry_mm)
        *ry_mm = -s * dx + c * dy;
}

/* ---- physar 2024 ---------------------------------------------------------- */

int rd_physar_parse(const char *text, rd_physar_set_t *out, char *err, int err_len)
{
    static const char *names[] = {
        "image_top", "image_bottom", "point", "nominal_x_cm", "nominal_y_cm",
        "nominal_heading_deg", "ot_frame", "ot_field_x_cm", "ot_field_y_cm", "ot_height_m",
        "ot_rotX", "ot_rotY", "ot_rotZ", "head_pitch_rad", "head_yaw_rad", "imu_anglex_rad",
        "imu_angley_rad"};
    enum { P_TOP, P_BOT, P_POINT, P_NUM0, P_N = 17 };
    rd_row_t *row, hdr;
    int ci[P_N], i, line = 0, r, cap = 0;
    const char *p = text;

    if (!out)
        return -1;
    out->rec = NULL;
    out->n = 0;
    if (!text) {
        tf_err(err, err_len, "NULL text");
        return -1;
    }
    r = rd_next_row(&p, &hdr, &line);
    if (r <= 0) {
        tf_err(err, err_len, "line %d: no header", line);
        return -1;
    }
    for (i = 0; i < P_N; i++) {
        ci[i] = rd_col_index(&hdr, names[i]);
        if (ci[i] < 0) {
            tf_err(err, err_len, "header lacks column %s", names[i]);
            return -1;
        }
    }
    row = malloc(sizeof *row);
    if (!row) {
        tf_err(err, err_len, "out of memory");
        return -1;
    }
    while ((r = rd_next_row(&p, row, &line)) == 1) {
        rd_physar_record_t *rec;
        double v[P_N];
        int k;
        if (row->n != hdr.n) {
            tf_err(err, err_len, "line %d: %d fields, header has %d", line, row->n, hdr.n);
            goto fail;
        }
        if (out->n == cap) {
            int nc = cap ? 2 * cap : 16;
            rd_physar_record_t *nr = realloc(out->rec, (size_t)nc * sizeof *nr);
            if (!nr) {
                tf_err(err, err_len, "out of memory");
                goto fail;
            }
            out->rec = nr;
            cap = nc;
        }
        rec = &out->rec[out->n];
        memset(rec, 0, sizeof *rec);
        if (rd_copy(rec->image_top, sizeof rec->image_top, row->col[ci[P_TOP]]) ||
            rd_copy(rec->image_bottom, sizeof rec->image_bottom, row->col[ci[P_BOT]]) ||
            rd_copy(rec->point, sizeof rec->point, row->col[ci[P_POINT]])) {
            tf_err(err, err_len, "line %d: name too long", line);
            goto fail;
        }
        for (k = P_NUM0; k < P_N; k++)
            if (rd_num(row->col[ci[k]], &v[k]) != 0) {
                tf_err(err, err_len, "line %d: bad number in column %s: '%s'", line, names[k],
                       row->col[ci[k]]);
                goto fail;
            }
        rec->nominal_x_cm = v[3];
        rec->nominal_y_cm = v[4];
        rec->nominal_heading_deg = v[5];
        rec->ot_frame = (int)v[6];
        rec->ot_field_x_cm = v[7];
        rec->ot_field_y_cm = v[8];
        rec->ot_height_m = v[9];
        rec->ot_rot_deg[0] = v[10];
        rec->ot_rot_deg[1] = v[11];
        rec->ot_rot_deg[2] = v[12];
        rec->head_pitch_rad = v[13];
        rec->head_yaw_rad = v[14];
        rec->imu_anglex_rad = v[15];
        rec->imu_angley_rad = v[16];
        out->n++;
    }
    if (r < 0) {
        tf_err(err, err_len, "line %d: malformed CSV line", line);
        goto fail;
    }
    free(row);
    return 0;
fail:
    free(row);
    rd_physar_free(out);
    return -1;
}

int rd_physar_load(const char *path, rd_physar_set_t *out, char *err, int err_len)
{
    char *t;
    int r;
    if (!out)
        return -1;
    out->rec = NULL;
    out->n = 0;
    t = rd_read_text(path, err, err_len);
    if (!t)
        return -1;
    r = rd_physar_parse(t, out, err, err_len);
    free(t);
    return r;
}

void rd_physar_free(rd_physar_set_t *set)
{
    if (!set)
        return;
    free(set->rec);
    set->rec = NULL;
    set->n = 0;
}

/* ---- modern frames ---------------------------------------------------------- */

static int rd_is_file(const char *p)
{
    struct stat st;
    return p && stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

const char *rd_modern_csv(void)
{
    static char buf[4096];
    static const char *cands[] = {"tools/eval/" RD_MODERN_CSV, "../tools/eval/" RD_MODERN_CSV};
    const char *env = getenv("FIELDLOC_MODERN_CSV");
    size_t i;
    ssize_t n;

    if (env && *env) {
        if (!rd_is_file(env) || strlen(env) >= sizeof buf)
            return NULL;
        strcpy(buf, env);
        return buf;
    }
    for (i = 0; i < sizeof cands / sizeof cands[0]; i++)
        if (rd_is_file(cands[i])) {
            strcpy(buf, cands[i]);
            return buf;
        }
    /* <ancestor of the executable's folder>/tools/eval/: the executable
     * sits in <repo>/build/ or deeper, as in rd_dir */
    n = readlink("/proc/self/exe", buf, sizeof buf - 64);
    if (n > 0) {
        int up;
        buf[n] = '\0';
        for (up = 0; up < 4; up++) {
            char *slash = strrchr(buf, '/');
            size_t len;
            if (!slash || slash == buf)
                break;
            *slash = '\0';
            len = strlen(buf);
            strcat(buf, "/tools/eval/" RD_MODERN_CSV);
            if (up > 0 && rd_is_file(buf))
                return buf;
            buf[len] = '\0';
        }
    }
    return NULL;
}

static int rd_blank(const char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    return *s == '\0';
}

/* Columns first..last (inclusive, indices into names/ci) all blank -> 0,
 * all numbers -> 1 (into v), a mix or a bad number -> -1 (err set). */
static int rd_optional_group(const rd_row_t *row, const int *ci, const char *const *names,
                             int first, int last, double *v, int line, char *err, int err_len)
{
    int k, blanks = 0;
    for (k = first; k <= last; k++)
        blanks += rd_blank(row->col[ci[k]]);
    if (blanks == last - first + 1)
        return 0;
    if (blanks) {
        tf_err(err, err_len, "line %d: columns %s..%s must be all blank or all numbers", line,
               names[first], names[last]);
        return -1;
    }
    for (k = first; k <= last; k++)
        if (rd_num(row->col[ci[k]], &v[k]) != 0) {
            tf_err(err, err_len, "line %d: bad number in column %s: '%s'", line, names[k],
                   row->col[ci[k]]);
            return -1;
        }
    return 1;
}

/* One data row into rec; 0, or -1 with err set. */
static int rd_modern_row(const rd_row_t *row, const int *ci, const char *const *names,
                         rd_modern_record_t *rec, int line, char *err, int err_len)
{
    enum { C_FILE, C_IN, C_SET, C_INDEX, C_X, C_Y, C_TH, C_HP, C_HY, C_NF, C_FEAT, C_CAM };
    double v[C_CAM + 1];
    const fl_camera_model_t *m;
    int nf, i, g;

    memset(rec, 0, sizeof *rec);
    if (rd_copy(rec->file, sizeof rec->file, row->col[ci[C_FILE]]) ||
        rd_copy(rec->set, sizeof rec->set, row->col[ci[C_SET]]) ||
        rd_copy(rec->index, sizeof rec->index, row->col[ci[C_INDEX]]) ||
        rd_copy(rec->camera, sizeof rec->camera, row->col[ci[C_CAM]]) || !rec->file[0] ||
        !rec->set[0] || !rec->index[0]) {
        tf_err(err, err_len, "line %d: empty or too long name", line);
        return -1;
    }
    if (rd_num(row->col[ci[C_IN]], &v[C_IN]) != 0 || (v[C_IN] != 0 && v[C_IN] != 1)) {
        tf_err(err, err_len, "line %d: in_realdata must be 0 or 1: '%s'", line,
               row->col[ci[C_IN]]);
        return -1;
    }
    rec->in_realdata = (int)v[C_IN];
    if ((g = rd_optional_group(row, ci, names, C_X, C_TH, v, line, err, err_len)) < 0)
        return -1;
    rec->has_pose = g;
    if (g) {
        rec->x_cm = v[C_X];
        rec->y_cm = v[C_Y];
        rec->theta_deg = v[C_TH];
    }
    if ((g = rd_optional_group(row, ci, names, C_HP, C_HY, v, line, err, err_len)) < 0)
        return -1;
    rec->has_head = g;
    if (g) {
        if (fabs(v[C_HP]) > 1.6 || fabs(v[C_HY]) > 3.2) {
            tf_err(err, err_len, "line %d: head angles out of range (|pitch| <= 1.6, |yaw| <= 3.2 rad)",
                   line);
            return -1;
        }
        rec->head_pitch_rad = v[C_HP];
        rec->head_yaw_rad = v[C_HY];
    }
    m = fl_camera_model_find(rec->camera);
    if (!m) {
        tf_err(err, err_len, "line %d: unknown camera '%s'", line, rec->camera);
        return -1;
    }
    if (rd_num(row->col[ci[C_NF]], &v[C_NF]) != 0) {
        tf_err(err, err_len, "line %d: bad number in column n_features: '%s'", line,
               row->col[ci[C_NF]]);
        return -1;
    }
    nf = rd_features(row->col[ci[C_FEAT]], rec->feat, RD_MODERN_MAX_FEATURES, "XLTGUB", 0.0);
    if (nf < 0) {
        tf_err(err, err_len, "line %d: bad feature list '%s'", line, row->col[ci[C_FEAT]]);
        return -1;
    }
    if (v[C_NF] != (double)nf) {
        tf_err(err, err_len, "line %d: n_features %g but %d features listed", line, v[C_NF], nf);
        return -1;
    }
    for (i = 0; i < nf; i++) {
        const rd_feature_t *f = &rec->feat[i];
        /* pixel centres: -0.5 .. size - 0.5 covers the image */
        if (!(f->u >= -0.5 && f->v >= -0.5 && f->u <= m->width_px - 0.5 &&
              f->v <= m->height_px - 0.5)) {
            tf_err(err, err_len, "line %d: feature %c:%g,%g outside the %dx%d image of %s", line,
                   f->type, f->u, f->v, (int)m->width_px, (int)m->height_px, m->name);
            return -1;
        }
    }
    rec->n_features = nf;
    return 0;
}

int rd_modern_parse(const char *text, rd_modern_set_t *out, char *err, int err_len)
{
    static const char *const names[] = {"file", "in_realdata", "set", "index", "x_cm", "y_cm",
                                        "theta_deg", "head_pitch_rad", "head_yaw_rad",
                                        "n_features", "features", "camera"};
    enum { C_N = 12 };
    rd_row_t *row, hdr;
    int ci[C_N], i, line = 0, r, cap = 0;
    const char *p = text;

    if (!out)
        return -1;
    out->rec = NULL;
    out->n = 0;
    if (!text) {
        tf_err(err, err_len, "NULL text");
        return -1;
    }
    r = rd_next_row(&p, &hdr, &line);
    if (r <= 0) {
        tf_err(err, err_len, "line %d: no header", line);
        return -1;
    }
    for (i = 0; i < C_N; i++) {
        ci[i] = rd_col_index(&hdr, names[i]);
        if (ci[i] < 0) {
            tf_err(err, err_len, "header lacks column %s", names[i]);
            return -1;
        }
    }
    row = malloc(sizeof *row);
    if (!row) {
        tf_err(err, err_len, "out of memory");
        return -1;
    }
    while ((r = rd_next_row(&p, row, &line)) == 1) {
        if (row->n != hdr.n) {
            tf_err(err, err_len, "line %d: %d fields, header has %d", line, row->n, hdr.n);
            goto fail;
        }
        if (out->n == cap) {
            int nc = cap ? 2 * cap : 32;
            rd_modern_record_t *nr = realloc(out->rec, (size_t)nc * sizeof *nr);
            if (!nr) {
                tf_err(err, err_len, "out of memory");
                goto fail;
            }
            out->rec = nr;
            cap = nc;
        }
        if (rd_modern_row(row, ci, names, &out->rec[out->n], line, err, err_len) != 0)
            goto fail;
        for (i = 0; i < out->n; i++)
            if (strcmp(out->rec[i].file, out->rec[out->n].file) == 0) {
                tf_err(err, err_len, "line %d: file %s listed twice", line,
                       out->rec[out->n].file);
                goto fail;
            }
        out->n++;
    }
    if (r < 0) {
        tf_err(err, err_len, "line %d: malformed CSV line", line);
        goto fail;
    }
    free(row);
    return 0;
fail:
    free(row);
    rd_modern_free(out);
    return -1;
}

int rd_modern_load(const char *path, rd_modern_set_t *out, char *err, int err_len)
{
    char *t;
    int r;
    if (!out)
        return -1;
    out->rec = NULL;
    out->n = 0;
    t = rd_read_text(path, err, err_len);
    if (!t)
        return -1;
    r = rd_modern_parse(t, out, err, err_len);
    free(t);
    return r;
}

void rd_modern_free(rd_modern_set_t *set)
{
    if (!set)
        return;
    free(set->rec);
    set->rec = NULL;
    set->n = 0;
}

int rd_modern_count(const rd_modern_record_t *r, char type)
{
    int i, n = 0;
    if (!r)
        return 0;
    for (i = 0; i < r->n_features; i++)
        n += !type || r->feat[i].type == type;
    return n;
}

void rd_modern_camera_pose(const rd_modern_record_t *r, const fl_camera_model_t *m,
                           fl_camera_pose_t *pose)
{
    if (!r || !m || !pose)
        return;
    memset(pose, 0, sizeof *pose);
    pose->neck_height_mm = m->default_neck_height_mm;
    pose->head_pitch = rd_angle_from_rad(r->head_pitch_rad);
    pose->head_yaw = rd_angle_from_rad(r->head_yaw_rad);
    pose->pitch_offset = m->default_pitch_offset;
}

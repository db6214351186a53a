/*
 * tools/eval/ukf_ref.c - the double-precision UKF step (ukf_ref.h).
 */
#include "eval/ukf_ref.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define REF_TURN 65536.0
#define REF_RAD (2.0 * M_PI / REF_TURN)      /* radians per unit */

double ukf_ref_wrap(double a)
{
    a = fmod(a, REF_TURN);
    if (a > REF_TURN / 2)
        a -= REF_TURN;
    else if (a <= -REF_TURN / 2)
        a += REF_TURN;
    return a;
}

int ukf_ref_chol(double p[3][3], double l[3][3])
{
    int i, j, k;
    memset(l, 0, 9 * sizeof(double));
    for (j = 0; j < 3; j++) {
        double d = p[j][j];
        for (k = 0; k < j; k++)
            d -= l[j][k] * l[j][k];
        if (!(d > 0))
            return 0;
        l[j][j] = sqrt(d);
        for (i = j + 1; i < 3; i++) {
            double s = p[i][j];
            for (k = 0; k < j; k++)
                s -= l[i][k] * l[j][k];
            l[i][j] = s / l[j][j];
        }
    }
    return 1;
}

/* The seven sigma points' state offsets from the mean: 0, +-sqrt(3) L_j. */
static int sigma(double p[3][3], double off[7][3])
{
    double l[3][3];
    int j, k;
    if (!ukf_ref_chol(p, l))
        return 0;
    memset(off, 0, 7 * 3 * sizeof(double));
    for (j = 0; j < 3; j++)
        for (k = 0; k < 3; k++) {
            off[1 + j][k] = sqrt(3.0) * l[k][j];
            off[4 + j][k] = -sqrt(3.0) * l[k][j];
        }
    return 1;
}

static const double WM[7] = {0, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6};
static const double WC[7] = {2, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6, 1.0 / 6};

int ukf_ref_predict(ukf_ref_pose_t *m, double p[3][3], double dx, double dy, double dth,
                    double q[3][3])
{
    double off[7][3], y[7][3], mean[3] = {0, 0, 0};
    int i, a, b;
    if (!sigma(p, off))
        return 0;
    for (i = 0; i < 7; i++) {
        double x = m->x + off[i][0], yy = m->y + off[i][1], t = m->t + off[i][2];
        double c = cos(t * REF_RAD), s = sin(t * REF_RAD);
        y[i][0] = x + c * dx - s * dy;
        y[i][1] = yy + s * dx + c * dy;
        y[i][2] = t + dth;        /* unwrapped: the deviations stay about the mean */
        for (a = 0; a < 3; a++)
            mean[a] += WM[i] * y[i][a];
    }
    for (a = 0; a < 3; a++)
        for (b = 0; b < 3; b++) {
            double s = q ? q[a][b] : 0;
            for (i = 0; i < 7; i++)
                s += WC[i] * (y[i][a] - mean[a]) * (y[i][b] - mean[b]);
            p[a][b] = s;
        }
    m->x = mean[0];
    m->y = mean[1];
    m->t = ukf_ref_wrap(mean[2]);
    return 1;
}

int ukf_ref_update(ukf_ref_pose_t *m, double p[3][3], double lx, double ly, double range,
                   double bearing, double sd_r, double sd_b, double *nll_q8)
{
    double off[7][3], z[7][2], zh[2] = {0, 0}, s[2][2], pxz[3][2], k[3][2], nu[2], det;
    int i, a, b;
    if (!sigma(p, off))
        return 0;
    for (i = 0; i < 7; i++) {
        double vx = lx - (m->x + off[i][0]), vy = ly - (m->y + off[i][1]);
        z[i][0] = hypot(vx, vy);
        z[i][1] = atan2(vy, vx) / REF_RAD - (m->t + off[i][2]);
    }
    for (i = 1; i < 7; i++)        /* bearings about the central point's */
        z[i][1] = z[0][1] + ukf_ref_wrap(z[i][1] - z[0][1]);
    for (i = 0; i < 7; i++)
        for (a = 0; a < 2; a++)
            zh[a] += WM[i] * z[i][a];
    for (a = 0; a < 2; a++) {
        for (b = 0; b < 2; b++) {
            double v = 0;
            for (i = 0; i < 7; i++)
                v += WC[i] * (z[i][a] - zh[a]) * (z[i][b] - zh[b]);
            s[a][b] = v;
        }
        for (b = 0; b < 3; b++) {
            double v = 0;
            for (i = 0; i < 7; i++)
                v += WC[i] * off[i][b] * (z[i][a] - zh[a]);
            pxz[b][a] = v;
        }
    }
    s[0][0] += sd_r * sd_r;
    s[1][1] += sd_b * sd_b;
    det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
    nu[0] = range - zh[0];
    nu[1] = ukf_ref_wrap(bearing - zh[1]);
    for (a = 0; a < 3; a++) {     /* K = Pxz S^-1 */
        k[a][0] = (pxz[a][0] * s[1][1] - pxz[a][1] * s[1][0]) / det;
        k[a][1] = (pxz[a][1] * s[0][0] - pxz[a][0] * s[0][1]) / det;
    }
    if (nll_q8) {
        double q = (nu[0] * nu[0] * s[1][1] - 2 * nu[0] * nu[1] * s[0][1] +
                    nu[1] * nu[1] * s[0][0]) / det;
        *nll_q8 = 256.0 * 0.5 * (q + log(det));
    }
    m->x += k[0][0] * nu[0] + k[0][1] * nu[1];
    m->y += k[1][0] * nu[0] + k[1][1] * nu[1];
    m->t = ukf_ref_wrap(m->t + k[2][0] * nu[0] + k[2][1] * nu[1]);
    for (a = 0; a < 3; a++)       /* P - K S K' */
        for (b = 0; b < 3; b++) {
            double v = 0;
            int c, d;
            for (c = 0; c < 2; c++)
                for (d = 0; d < 2; d++)
                    v += k[a][c] * s[c][d] * k[b][d];
            p[a][b] -= v;
        }
    return 1;
}

void ukf_ref_from6(const int32_t c[6], double p[3][3])
{
    p[0][0] = c[0];
    p[0][1] = p[1][0] = c[1];
    p[0][2] = p[2][0] = c[2];
    p[1][1] = c[3];
    p[1][2] = p[2][1] = c[4];
    p[2][2] = c[5];
}

void ukf_ref_compare(const ukf_ref_pose_t *ref, double rp[3][3], int32_t x_mm,
                     int32_t y_mm, int32_t heading, const int32_t c[6], ukf_ref_err_t *e)
{
    double p[3][3], worst = 0, raw = 0;
    int a, b;
    ukf_ref_from6(c, p);
    e->mean_mm = hypot(x_mm - ref->x, y_mm - ref->y);
    e->heading_deg = fabs(ukf_ref_wrap(heading - ref->t)) * 360.0 / REF_TURN;
    for (a = 0; a < 3; a++)
        for (b = a; b < 3; b++) {
            double den = sqrt(fabs(rp[a][a] * rp[b][b]));
            /* beyond the output's rounding to integers */
            double v = fmax(0, fabs(p[a][b] - rp[a][b]) - 0.5) / (den > 0 ? den : 1);
            double w = fabs(p[a][b] - rp[a][b]) / (den > 0 ? den : 1);
            if (v > worst)
                worst = v;
            if (w > raw)
                raw = w;
        }
    e->cov_rel = worst;
    e->cov_rel_raw = raw;
}

double ukf_ref_unif(ukf_ref_rng_t *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return (double)((r->s * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

double ukf_ref_gauss(ukf_ref_rng_t *r)
{
    double u = ukf_ref_unif(r), v = ukf_ref_unif(r);
    return sqrt(-2 * log(1 - u)) * cos(2 * M_PI * v);
}

void ukf_ref_random_cov(ukf_ref_rng_t *r, double sd_lo_mm, double sd_hi_mm, double sd_lo_t,
                        double sd_hi_t, double rho_max, int32_t c[6])
{
    double a[3][3], sd[3], cr[3][3];
    int i, j, k;
    for (i = 0; i < 3; i++) {
        double n = 0;
        for (k = 0; k < 3; k++) {
            a[i][k] = ukf_ref_gauss(r);
            n += a[i][k] * a[i][k];
        }
        n = sqrt(n);
        for (k = 0; k < 3; k++)
            a[i][k] /= n;
    }
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double v = 0;
            for (k = 0; k < 3; k++)
                v += a[i][k] * a[j][k];
            cr[i][j] = i == j ? 1 : rho_max * v;
        }
    sd[0] = sd_lo_mm * pow(sd_hi_mm / sd_lo_mm, ukf_ref_unif(r));
    sd[1] = sd_lo_mm * pow(sd_hi_mm / sd_lo_mm, ukf_ref_unif(r));
    sd[2] = sd_lo_t * pow(sd_hi_t / sd_lo_t, ukf_ref_unif(r));
    c[0] = (int32_t)llround(sd[0] * sd[0]);
    c[1] = (int32_t)llround(cr[0][1] * sd[0] * sd[1]);
    c[2] = (int32_t)llround(cr[0][2] * sd[0] * sd[2]);
    c[3] = (int32_t)llround(sd[1] * sd[1]);
    c[4] = (int32_t)llround(cr[1][2] * sd[1] * sd[2]);
    c[5] = (int32_t)llround(sd[2] * sd[2]);
}

/* libFuzzer harness: arbitrary bytes as the inputs of the UKF step (ukf.h):
 * a pose, a covariance and limits from the first 32 bytes (any int32,
 * INT32 extremes included), then records of 20 bytes, each a predict (with
 * its process noise), an update (map point, range, bearing, sds) or a
 * draw / density / factor.  After every call the covariance must be valid
 * (fl_ukf_cov_valid: within the caps and floors, positive definite with
 * every pivot at least its floor) and, once a predict or update has run,
 * the mean within the box, whatever the status; a status is FL_OK or FL_ERR_RANGE; a factor that succeeds
 * has a positive diagonal.  UBSan (integer checks included) catches any
 * overflow on the way. */
#include "fieldloc/ukf.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int32_t rd32(const uint8_t *d)
{
    return (int32_t)((uint32_t)d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[2] << 16 |
                     (uint32_t)d[3] << 24);
}

static int16_t rd16(const uint8_t *d)
{
    return (int16_t)((uint16_t)d[0] | (uint16_t)(d[1] << 8));
}

/* the covariance valid; the mean in the box once a step has run on it */
static void must_hold(const fl_ukf_pose_t *m, const fl_ukf_cov_t *p, const fl_ukf_limits_t *lim,
                      int stepped)
{
    if (!fl_ukf_cov_valid(p, lim) ||
        (stepped && (m->x_mm < -FL_UKF_POS_MAX_MM || m->x_mm > FL_UKF_POS_MAX_MM ||
                     m->y_mm < -FL_UKF_POS_MAX_MM || m->y_mm > FL_UKF_POS_MAX_MM)))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fl_ukf_pose_t m, x;
    fl_ukf_cov_t p, q;
    fl_ukf_limits_t lim;
    fl_ukf_repairs_t rep = {0, 0, 0};
    fl_ukf_chol_t l;
    size_t at;
    uint32_t rng = 1u, nll;
    int stepped = 0;
    if (size < 32)
        return 0;
    m.x_mm = rd32(data);
    m.y_mm = rd32(data + 4);
    m.heading = rd16(data + 8);
    lim.var_min_mm2 = rd16(data + 10);
    lim.var_min_ang2 = rd32(data + 12);
    p.xx = rd32(data + 16);
    p.xy = rd16(data + 20) * 4096;
    p.xt = rd16(data + 22) * 4096;
    p.yy = rd32(data + 24);
    p.yt = rd16(data + 28) * 4096;
    p.tt = rd16(data + 30) * 32768;
    for (at = 32; at + 20 <= size; at += 20) {
        const uint8_t *d = data + at;
        fl_status_t st = FL_OK;
        stepped |= d[0] % 4u != 3u;
        switch (d[0] % 4u) {
        case 0:
            q.xx = rd32(d + 4);
            q.xy = rd16(d + 8);
            q.xt = rd16(d + 10);
            q.yy = rd16(d + 12) * 64;
            q.yt = rd16(d + 14);
            q.tt = rd16(d + 16) * 256;
            st = fl_ukf_predict(&m, &p, rd16(d + 1) * (d[3] & 1 ? 1 : 2), rd16(d + 18),
                                (fl_angle_t)rd16(d + 2), d[3] & 2 ? &q : NULL, &lim, &rep);
            break;
        case 1:
            st = fl_ukf_update(&m, &p, rd32(d + 1), rd32(d + 5), rd16(d + 9), rd16(d + 11),
                               rd32(d + 13), rd16(d + 17), &lim, &rep, &nll);
            break;
        case 2: {
            fl_ukf_obs_t o;
            o.lx_mm = rd16(d + 1) * 2;
            o.ly_mm = rd16(d + 3);
            o.range_mm = (int32_t)((uint16_t)rd16(d + 5) % 20001u);
            o.bearing = rd16(d + 7);
            o.sd_bearing = rd16(d + 9);
            o.sd_range_mm = rd32(d + 11);
            st = fl_ukf_update_obs(&m, &p, &o, &lim, &rep, &nll);
            break;
        }
        default:
            fl_ukf_cov_repair(&p, &lim, &rep);
            if (fl_ukf_chol3(&p, &l) == FL_OK && (l.l11 <= 0 || l.l22 <= 0 || l.l33 <= 0))
                abort();
            (void)fl_ukf_gauss_nll_q8(&m, &p, &m);
            rng ^= (uint32_t)rd32(d + 1);
            if (!fl_ukf_sample(&m, &p, &rng, &x))
                abort();                         /* a repaired covariance factors */
            if (stepped && (x.x_mm < -FL_UKF_POS_MAX_MM || x.x_mm > FL_UKF_POS_MAX_MM))
                abort();
            break;
        }
        if (st != FL_OK && st != FL_ERR_RANGE)
            abort();
        must_hold(&m, &p, &lim, stepped);
    }
    return 0;
}

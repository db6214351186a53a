/*
 * tools/bench/bench_coach_cv.cpp - the OpenCV peer of `fieldloc bench`
 * section "coach" (tools/bench/bench_coach.c): seed 003's coach chain as its
 * paper describes it (sections 3.1-3.3, OpenCV 3.1 there), single-threaded,
 * buffers kept between calls:
 *     warpPerspective (bilinear) of the frame to the top view ->
 *     cvtColor RGB2HSV -> inRange for the red jersey (two boxes: the hue
 *     wraps) and the blue one -> morphologyEx open then close on each mask
 *     (square kernels of the firmware's radii) -> connectedComponentsWithStats
 *     (4-connected) -> per region of at least min_area pixels, fitLine
 *     (DIST_L2) through its pixels -> cvtColor RGB2Lab, the a* channel,
 *     threshold with THRESH_OTSU (non-field) -> absdiff against the empty
 *     field's top view (warped once, as the firmware stores its background
 *     once), cvtColor to grey, threshold (moved) -> the foot: down the
 *     line (toward the coach) while the non-field mask holds, the lowest
 *     pixel that is non-field and moved.
 * The same chain in image space (image_space 1: no warp, the foot pixel
 * mapped by perspectiveTransform) is the OpenCV form of the firmware's own
 * order of work (fieldloc/coach.h: search the frame, map only the feet).
 * Built only with OpenCV (FL_HAVE_OPENCV).
 */
#ifdef FL_HAVE_OPENCV
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <math.h>
#include <stdint.h>
#include <vector>

struct bccv_state {
    int image_space;                 /* 1: no warp, the chain on the frame */
    cv::Mat M;                       /* image pixel -> top-view pixel */
    cv::Size top;
    cv::Mat bg_top, cur, hsv, m1, m2, mask[2], lab, a, nonfield, diff, grey, moved;
    cv::Mat labels, stats, cents, kopen, kclose;
    cv::Scalar lo[3], hi[3];
    int min_area, bg_diff;
    std::vector<cv::Point> pts;
};

extern "C" {

void *bccv_new(const double img_to_top[9], int top_w, int top_h, const uint8_t *bg_rgb, int w,
               int h, const uint8_t red[6], const uint8_t blue[6], int open_r, int close_r,
               int min_area, int bg_diff, int image_space)
{
    cv::setNumThreads(1);
    bccv_state *s = new bccv_state();
    s->image_space = image_space;
    s->M = cv::Mat(3, 3, CV_64F);
    for (int k = 0; k < 9; k++)
        s->M.at<double>(k / 3, k % 3) = img_to_top[k];
    cv::Mat bg(h, w, CV_8UC3, const_cast<uint8_t *>(bg_rgb));
    if (image_space) {
        s->top = cv::Size(w, h);
        bg.copyTo(s->bg_top);
    } else {
        s->top = cv::Size(top_w, top_h);
        cv::warpPerspective(bg, s->bg_top, s->M, s->top, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    }
    /* red wraps through hue 0: [lo..179] and [0..hi] */
    s->lo[0] = cv::Scalar(red[0], red[2], red[4]);
    s->hi[0] = cv::Scalar(179, red[3], red[5]);
    s->lo[1] = cv::Scalar(0, red[2], red[4]);
    s->hi[1] = cv::Scalar(red[1], red[3], red[5]);
    s->lo[2] = cv::Scalar(blue[0], blue[2], blue[4]);
    s->hi[2] = cv::Scalar(blue[1], blue[3], blue[5]);
    s->kopen = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * open_r + 1, 2 * open_r + 1));
    s->kclose = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * close_r + 1, 2 * close_r + 1));
    s->min_area = min_area;
    s->bg_diff = bg_diff;
    return s;
}

void bccv_free(void *s)
{
    delete static_cast<bccv_state *>(s);
}

static int on(const cv::Mat &m, int u, int v)
{
    return u >= 0 && v >= 0 && u < m.cols && v < m.rows && m.at<uint8_t>(v, u) != 0;
}

/* One frame; writes up to cap feet (top-view pixels u, v) and returns how
 * many regions gave one. */
int bccv_run(void *state, const uint8_t *rgb, int w, int h, double *feet, int cap)
{
    bccv_state *s = static_cast<bccv_state *>(state);
    cv::Mat in(h, w, CV_8UC3, const_cast<uint8_t *>(rgb));
    int n = 0;
    if (s->image_space)
        s->cur = in;
    else
        cv::warpPerspective(in, s->cur, s->M, s->top, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::cvtColor(s->cur, s->hsv, cv::COLOR_RGB2HSV);
    cv::inRange(s->hsv, s->lo[0], s->hi[0], s->m1);
    cv::inRange(s->hsv, s->lo[1], s->hi[1], s->m2);
    cv::bitwise_or(s->m1, s->m2, s->mask[0]);
    cv::inRange(s->hsv, s->lo[2], s->hi[2], s->mask[1]);
    cv::cvtColor(s->cur, s->lab, cv::COLOR_RGB2Lab);
    cv::extractChannel(s->lab, s->a, 1);
    cv::threshold(s->a, s->nonfield, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    cv::absdiff(s->cur, s->bg_top, s->diff);
    cv::cvtColor(s->diff, s->grey, cv::COLOR_RGB2GRAY);
    cv::threshold(s->grey, s->moved, s->bg_diff, 255, cv::THRESH_BINARY);
    for (int t = 0; t < 2; t++) {
        cv::morphologyEx(s->mask[t], s->mask[t], cv::MORPH_OPEN, s->kopen);
        cv::morphologyEx(s->mask[t], s->mask[t], cv::MORPH_CLOSE, s->kclose);
        int nl = cv::connectedComponentsWithStats(s->mask[t], s->labels, s->stats, s->cents, 4,
                                                  CV_32S);
        for (int i = 1; i < nl; i++) {
            const int *st = s->stats.ptr<int>(i);
            if (st[cv::CC_STAT_AREA] < s->min_area)
                continue;
            s->pts.clear();
            for (int v = st[cv::CC_STAT_TOP]; v < st[cv::CC_STAT_TOP] + st[cv::CC_STAT_HEIGHT]; v++) {
                const int *l = s->labels.ptr<int>(v);
                for (int u = st[cv::CC_STAT_LEFT]; u < st[cv::CC_STAT_LEFT] + st[cv::CC_STAT_WIDTH]; u++)
                    if (l[u] == i)
                        s->pts.push_back(cv::Point(u, v));
            }
            cv::Vec4f line;
            cv::fitLine(s->pts, line, cv::DIST_L2, 0, 0.01, 0.01);
            double dx = line[0], dy = line[1];
            if (dy < 0) {
                dx = -dx;
                dy = -dy;
            }
            /* from the region's centroid toward the coach (+v) */
            double u = s->cents.at<double>(i, 0), v = s->cents.at<double>(i, 1);
            int gap = 0, found = 0, fu = 0, fv = 0, limit = s->top.width + s->top.height;
            for (int k = 0; k < limit && gap <= 2; k++, u += dx, v += dy) {
                int iu = (int)lround(u), iv = (int)lround(v);
                if (on(s->nonfield, iu, iv)) {
                    gap = 0;
                    if (on(s->moved, iu, iv)) {
                        fu = iu;
                        fv = iv;
                        found = 1;
                    }
                } else {
                    gap++;
                }
            }
            if (found && n < cap) {
                feet[2 * n] = fu;
                feet[2 * n + 1] = fv;
                if (s->image_space) { /* the foot pixel through the homography */
                    std::vector<cv::Point2f> a(1, cv::Point2f((float)fu, (float)fv)), b;
                    cv::perspectiveTransform(a, b, s->M);
                    feet[2 * n] = b[0].x;
                    feet[2 * n + 1] = b[0].y;
                }
                n++;
            }
        }
    }
    return n;
}

} /* extern "C" */
#endif

#ifdef FL_HAVE_OPENCV
extern "C" double bccv_perspective_4pt(const float *src, const float *dst)
{
    cv::Point2f s[4], d[4];
    for (int k = 0; k < 4; k++) {
        s[k] = cv::Point2f(src[2 * k], src[2 * k + 1]);
        d[k] = cv::Point2f(dst[2 * k], dst[2 * k + 1]);
    }
    cv::Mat m = cv::getPerspectiveTransform(s, d);
    return m.at<double>(0, 0);
}
#endif

// tools/bench/cv_peer.cpp - OpenCV peers of the color and scanner code (see
// tools/bench/cv_peer.h).  Host only; built when pkg-config finds opencv4.
#include "bench/cv_peer.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

extern "C" void cvpeer_rgb2hsv(const uint8_t *rgb, uint8_t *hsv, long n)
{
    // one row of n pixels (n may exceed INT_MAX / 3 only for absurd inputs)
    const long chunk = 1L << 20;
    for (long i = 0; i < n; i += chunk) {
        int m = (int)(n - i < chunk ? n - i : chunk);
        cv::Mat src(1, m, CV_8UC3, const_cast<uint8_t *>(rgb + 3 * i));
        cv::Mat dst(1, m, CV_8UC3, hsv + 3 * i);
        cv::cvtColor(src, dst, cv::COLOR_RGB2HSV);
    }
}

extern "C" void cvpeer_set_threads(int n)
{
    cv::setNumThreads(n);
}

struct cvpeer_chain {
    cv::Mat rgb, hsv, mask[3];
};

extern "C" cvpeer_chain_t *cvpeer_chain_new(void)
{
    return new cvpeer_chain();
}

extern "C" void cvpeer_chain_free(cvpeer_chain_t *c)
{
    delete c;
}

extern "C" void cvpeer_chain_run(cvpeer_chain_t *c, const uint8_t *data, int yuyv,
                                 int w, int h, const uint8_t boxes[3][6], int run,
                                 int16_t *border)
{
    if (yuyv) {
        cv::Mat src(h, w, CV_8UC2, const_cast<uint8_t *>(data));
        cv::cvtColor(src, c->rgb, cv::COLOR_YUV2RGB_YUYV);
        cv::cvtColor(c->rgb, c->hsv, cv::COLOR_RGB2HSV);
    } else {
        cv::Mat src(h, w, CV_8UC3, const_cast<uint8_t *>(data));
        cv::cvtColor(src, c->hsv, cv::COLOR_RGB2HSV);
    }
    for (int k = 0; k < 3; k++)
        cv::inRange(c->hsv, cv::Scalar(boxes[k][0], boxes[k][2], boxes[k][4]),
                    cv::Scalar(boxes[k][1], boxes[k][3], boxes[k][5]), c->mask[k]);
    const cv::Mat &g = c->mask[0];
    for (int u = 0; u < w; u++) {
        int n = 0;
        border[u] = (int16_t)h;
        for (int v = 0; v < h; v++) {
            if (g.at<uchar>(v, u)) {
                if (++n >= run) {
                    border[u] = (int16_t)(v - run + 1);
                    break;
                }
            } else {
                n = 0;
            }
        }
    }
}

extern "C" long cvpeer_chain_count(const cvpeer_chain_t *c, int k)
{
    return k >= 0 && k < 3 && !c->mask[k].empty() ? (long)cv::countNonZero(c->mask[k]) : 0;
}

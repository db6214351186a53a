/*
 * tools/bench/bench_vision_cv.cpp - the OpenCV peer of `fieldloc bench` section
 * "vision" (tools/bench/bench_vision.c): the textbook line-feature chain on the
 * same frames, single-threaded:
 *     (cvtColor YUV2RGB_YUYV for YUYV frames) -> cvtColor RGB2HSV ->
 *     inRange for the green, white and yellow boxes (full masks) ->
 *     HoughLinesP on the white mask (rho 1 px, theta 1 deg, threshold 20,
 *     min length 10 px, max gap 3 px).
 * No crossings, posts or circle: the peer does less than fl_vision_frame,
 * so the speed ratio is a lower bound.  Built only with OpenCV
 * (FL_HAVE_OPENCV); buffers are kept between calls.
 */
#ifdef FL_HAVE_OPENCV
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <stdint.h>
#include <vector>

struct bvcv_state {
    cv::Mat rgb, hsv, green, white, yellow;
    std::vector<cv::Vec4i> lines;
};

extern "C" {

void *bvcv_new(void)
{
    cv::setNumThreads(1);
    return new bvcv_state();
}

void bvcv_free(void *s)
{
    delete static_cast<bvcv_state *>(s);
}

/* One frame; boxes[k] = h_lo, h_hi, s_lo, s_hi, v_lo, v_hi for green,
 * white, yellow.  Returns the number of Hough segments. */
int bvcv_run(void *state, const uint8_t *data, int yuyv, int w, int h,
             const uint8_t boxes[3][6])
{
    bvcv_state *s = static_cast<bvcv_state *>(state);
    cv::Mat in;
    if (yuyv) {
        cv::Mat y(h, w, CV_8UC2, const_cast<uint8_t *>(data));
        cv::cvtColor(y, s->rgb, cv::COLOR_YUV2RGB_YUYV);
        in = s->rgb;
    } else {
        in = cv::Mat(h, w, CV_8UC3, const_cast<uint8_t *>(data));
    }
    cv::cvtColor(in, s->hsv, cv::COLOR_RGB2HSV);
    cv::inRange(s->hsv, cv::Scalar(boxes[0][0], boxes[0][2], boxes[0][4]),
                cv::Scalar(boxes[0][1], boxes[0][3], boxes[0][5]), s->green);
    cv::inRange(s->hsv, cv::Scalar(boxes[1][0], boxes[1][2], boxes[1][4]),
                cv::Scalar(boxes[1][1], boxes[1][3], boxes[1][5]), s->white);
    cv::inRange(s->hsv, cv::Scalar(boxes[2][0], boxes[2][2], boxes[2][4]),
                cv::Scalar(boxes[2][1], boxes[2][3], boxes[2][5]), s->yellow);
    cv::HoughLinesP(s->white, s->lines, 1, CV_PI / 180, 20, 10, 3);
    return (int)s->lines.size();
}

} /* extern "C" */
#endif

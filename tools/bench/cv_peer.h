/*
 * tools/bench/cv_peer.h - the OpenCV side of the color and scanner comparisons
 * (tools/bench/cv_peer.cpp, built only with OpenCV: callers test FL_HAVE_OPENCV).
 */
#ifndef FL_TOOLS_CV_PEER_H
#define FL_TOOLS_CV_PEER_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* cv::cvtColor(COLOR_RGB2HSV) over n packed RGB pixels -> packed HSV. */
void cvpeer_rgb2hsv(const uint8_t *rgb, uint8_t *hsv, long n);

/* cv::setNumThreads(n) (the benchmark uses 1: both sides single-threaded). */
void cvpeer_set_threads(int n);

/* The classic chain, buffers kept between calls: input -> (cvtColor
 * YUV2RGB_YUYV when yuyv) -> cvtColor RGB2HSV -> inRange for the three
 * boxes (h_lo, h_hi, s_lo, s_hi, v_lo, v_hi each; full masks) -> per
 * column the first row of the first run of `run` green mask pixels
 * (border[u], height when none). */
typedef struct cvpeer_chain cvpeer_chain_t;
cvpeer_chain_t *cvpeer_chain_new(void);
void cvpeer_chain_free(cvpeer_chain_t *c);
void cvpeer_chain_run(cvpeer_chain_t *c, const uint8_t *data, int yuyv, int w,
                      int h, const uint8_t boxes[3][6], int run, int16_t *border);
/* Pixels set in mask k (0 green, 1 white, 2 yellow) of the last run. */
long cvpeer_chain_count(const cvpeer_chain_t *c, int k);

#ifdef __cplusplus
}
#endif

#endif

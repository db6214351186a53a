/*
 * tools/bench/bench_skeleton_cv.cpp - the OpenCV peer of `fieldloc bench`
 * section "skeleton" (tools/bench/bench_skeleton.c): cv::ximgproc::
 * thinning (Zhang-Suen) of the same 320x240 mask, single-threaded.  The
 * module is in opencv_contrib; without it (FL_HAVE_XIMGPROC unset by the
 * Makefile) the peer returns -1 and the row has no peer.
 */
#ifdef FL_HAVE_OPENCV
#include <opencv2/core.hpp>
#ifdef FL_HAVE_XIMGPROC
#include <opencv2/ximgproc.hpp>
#endif

#include <stdint.h>
#include <time.h>

extern "C" {

double bskcv_thin_ns(const uint8_t *mask, int w, int h, int n)
{
#ifdef FL_HAVE_XIMGPROC
    cv::setNumThreads(1);
    cv::Mat in(h, w, CV_8UC1), out;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            in.at<uint8_t>(y, x) = mask[y * w + x] ? 255 : 0;
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    for (int k = 0; k < n; k++)
        cv::ximgproc::thinning(in, out, cv::ximgproc::THINNING_ZHANGSUEN);
    clock_gettime(CLOCK_MONOTONIC, &b);
    return ((b.tv_sec - a.tv_sec) * 1e9 + (b.tv_nsec - a.tv_nsec)) / n;
#else
    (void)mask; (void)w; (void)h; (void)n;
    return -1;
#endif
}

}
#endif

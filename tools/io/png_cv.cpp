// tools/io/png_cv.cpp - PNG output through OpenCV (built only with FL_HAVE_OPENCV).
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include "io/ppm.h"
}

extern "C" int png_write(const char *path, const uint8_t *rgb, int width, int height)
{
    try {
        cv::Mat in(height, width, CV_8UC3, const_cast<uint8_t *>(rgb));
        cv::Mat bgr;
        cv::cvtColor(in, bgr, cv::COLOR_RGB2BGR);
        return cv::imwrite(path, bgr) ? 0 : -1;
    } catch (const cv::Exception &) {
        return -1;
    }
}

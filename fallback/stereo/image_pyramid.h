#pragma once
// The matcher's view of an image: RGB as floats (integers 0..255, 4 floats per pixel)
// and the grey-value gradient (2 floats per pixel), laid out as the kernels' buffers.
#include <opencv2/core.hpp>
#include <vector>

#include "kernels/stereo/pms_math.h"

namespace flexsight {

struct ViewImage {
  int width = 0;
  int height = 0;
  std::vector<float> color;     // r, g, b, census per pixel (pms_census_pixel)
  std::vector<float> gradient;  // gx, gy per pixel
  int pixels() const { return width * height; }
};

// The default census: the 5x5 square.
constexpr PmsCensusShape kSquareCensus = {2, 2, 2};

// From CV_8UC3 (RGB), gradient and census included.
ViewImage make_view_image(const cv::Mat& rgb8, PmsCensusShape census = kSquareCensus);

// The `color` of make_view_image (r, g, b, 0 per pixel) alone, for the OpenCL path,
// which computes the gradient on the device.
std::vector<float> view_color(const cv::Mat& rgb8);

// Coarser level: 2x2 box average with rounding (size rounds up), gradient and census
// included.
ViewImage downsample(const ViewImage& fine, PmsCensusShape census = kSquareCensus);

// Recomputes `image.gradient` and the census in `image.color` from its r, g, b.
void compute_gradient(ViewImage& image, PmsCensusShape census = kSquareCensus);

// Number of pyramid levels so that the coarsest is at most `coarsest_width` wide
// (at least 1; every level keeps at least 8 pixels in each direction).
int pyramid_level_count(int width, int height, int coarsest_width);

// Level 0 is the input; level i+1 is downsample(level i).
std::vector<ViewImage> build_pyramid(const cv::Mat& rgb8, int levels,
                                     PmsCensusShape census = kSquareCensus);

}  // namespace flexsight

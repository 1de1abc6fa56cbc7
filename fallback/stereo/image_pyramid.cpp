#include "fallback/stereo/image_pyramid.h"

#include "kernels/stereo/pms_math.h"

namespace flexsight {

std::vector<float> view_color(const cv::Mat& rgb8) {
  CV_Assert(rgb8.type() == CV_8UC3);
  std::vector<float> color(4 * static_cast<size_t>(rgb8.cols) * rgb8.rows, 0.0f);
  for (int y = 0; y < rgb8.rows; ++y) {
    const cv::Vec3b* row = rgb8.ptr<cv::Vec3b>(y);
    for (int x = 0; x < rgb8.cols; ++x) {
      float* out = &color[4 * (static_cast<size_t>(y) * rgb8.cols + x)];
      out[0] = row[x][0];
      out[1] = row[x][1];
      out[2] = row[x][2];
    }
  }
  return color;
}

ViewImage make_view_image(const cv::Mat& rgb8, PmsCensusShape census) {
  ViewImage image;
  image.width = rgb8.cols;
  image.height = rgb8.rows;
  image.color = view_color(rgb8);
  compute_gradient(image, census);
  return image;
}

void compute_gradient(ViewImage& image, PmsCensusShape census) {
  image.gradient.assign(2 * static_cast<size_t>(image.pixels()), 0.0f);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      pms_gradient_pixel(image.color.data(), image.width, image.height, x, y,
                         &image.gradient[2 * (static_cast<size_t>(y) * image.width + x)]);
      image.color[4 * (static_cast<size_t>(y) * image.width + x) + 3] =
          pms_census_pixel(image.color.data(), image.width, image.height, x, y, census);
    }
  }
}

ViewImage downsample(const ViewImage& fine, PmsCensusShape census) {
  ViewImage coarse;
  coarse.width = (fine.width + 1) / 2;
  coarse.height = (fine.height + 1) / 2;
  coarse.color.assign(4 * static_cast<size_t>(coarse.pixels()), 0.0f);
  for (int y = 0; y < coarse.height; ++y) {
    for (int x = 0; x < coarse.width; ++x) {
      pms_downsample_pixel(fine.color.data(), fine.width, fine.height, x, y,
                           &coarse.color[4 * (static_cast<size_t>(y) * coarse.width + x)]);
    }
  }
  compute_gradient(coarse, census);
  return coarse;
}

int pyramid_level_count(int width, int height, int coarsest_width) {
  int levels = 1;
  while (width > coarsest_width && (width + 1) / 2 >= 8 && (height + 1) / 2 >= 8) {
    width = (width + 1) / 2;
    height = (height + 1) / 2;
    ++levels;
  }
  return levels;
}

std::vector<ViewImage> build_pyramid(const cv::Mat& rgb8, int levels, PmsCensusShape census) {
  std::vector<ViewImage> pyramid;
  pyramid.reserve(levels);
  pyramid.push_back(make_view_image(rgb8, census));
  for (int level = 1; level < levels; ++level) pyramid.push_back(downsample(pyramid.back(), census));
  return pyramid;
}

}  // namespace flexsight

#include "host/opencl/pipeline_mirror.h"

#include <algorithm>
#include <string>

#include "host/io/input_error.h"

namespace flexsight::opencl {

void validate_inputs(const cv::Mat& left, const cv::Mat& right, const StereoParams& params) {
  params.check();
  if (left.empty() || right.empty()) throw InputError("stereo pair", "an image is empty");
  if (left.type() != CV_8UC3 || right.type() != CV_8UC3) {
    throw InputError("stereo pair", "images must be 8-bit RGB");
  }
  if (left.size() != right.size()) {
    throw InputError("stereo pair", "left and right images differ in size");
  }
  if (params.ndisp > left.cols) {
    throw InputError("parameter --ndisp", "is " + std::to_string(params.ndisp) +
                                              ", wider than the image (" +
                                              std::to_string(left.cols) + " px)");
  }
}

int level_ndisp(int ndisp, int level) {
  int n = ndisp;
  for (int i = 0; i < level; ++i) n = (n + 1) / 2;
  return std::max(n, 2);
}

std::uint32_t iteration_key(int level, int iteration) {
  return static_cast<std::uint32_t>(level * 64 + iteration);
}

std::vector<float> color_floats(const cv::Mat& rgb8) {
  CV_Assert(rgb8.type() == CV_8UC3);
  std::vector<float> color(4 * static_cast<size_t>(rgb8.cols) * rgb8.rows, 0.0f);
  for (int y = 0; y < rgb8.rows; ++y) {
    const cv::Vec3b* row = rgb8.ptr<cv::Vec3b>(y);
    float* out = &color[4 * static_cast<size_t>(y) * rgb8.cols];
    for (int x = 0; x < rgb8.cols; ++x, out += 4) {
      for (int c = 0; c < 3; ++c) out[c] = row[x][c];
    }
  }
  return color;
}

cv::Mat to_mat(const std::vector<float>& values, int width, int height, int channels) {
  cv::Mat mat(height, width, CV_32FC(channels));
  std::copy(values.begin(), values.end(), mat.ptr<float>());
  return mat;
}

cv::Mat planes_to_mat(const std::vector<float>& planes, int width, int height) {
  cv::Mat mat(height, width, CV_32FC3);
  for (int i = 0; i < width * height; ++i) {
    mat.ptr<cv::Vec3f>()[i] = cv::Vec3f(planes[4 * i], planes[4 * i + 1], planes[4 * i + 2]);
  }
  return mat;
}

}  // namespace flexsight::opencl

#include "host/stereo/opencv_stereo.h"

#include <limits>
#include <stdexcept>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

int round_up_to_16(int ndisp) { return (ndisp + 15) / 16 * 16; }

cv::Ptr<cv::StereoMatcher> make_matcher(OpenCvMatcher matcher, int ndisp) {
  const int num_disparities = round_up_to_16(ndisp);
  if (matcher == OpenCvMatcher::Sgbm) {
    const int block = 5;
    return cv::StereoSGBM::create(0, num_disparities, block, 8 * 3 * block * block,
                                  32 * 3 * block * block, 1, 63, 10, 100, 2,
                                  cv::StereoSGBM::MODE_SGBM_3WAY);
  }
  cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(num_disparities, 9);
  bm->setPreFilterCap(31);
  bm->setTextureThreshold(10);
  bm->setUniquenessRatio(15);
  bm->setSpeckleWindowSize(100);
  bm->setSpeckleRange(32);
  bm->setDisp12MaxDiff(1);
  return bm;
}

}  // namespace

bool parse_opencv_matcher(const std::string& name, OpenCvMatcher& out) {
  if (name == "sgbm") {
    out = OpenCvMatcher::Sgbm;
    return true;
  }
  if (name == "bm") {
    out = OpenCvMatcher::Bm;
    return true;
  }
  return false;
}

const char* opencv_matcher_name(OpenCvMatcher matcher) {
  return matcher == OpenCvMatcher::Sgbm ? "opencv-sgbm" : "opencv-bm";
}

std::string opencv_matcher_settings(OpenCvMatcher matcher) {
  return matcher == OpenCvMatcher::Sgbm
             ? "cv::StereoSGBM MODE_SGBM_3WAY, block 5, P1 8*3*25, P2 32*3*25, uniqueness 10, "
               "speckle 100/2, disp12MaxDiff 1, preFilterCap 63"
             : "cv::StereoBM block 9, preFilterCap 31, textureThreshold 10, uniqueness 15, "
               "speckle 100/32, disp12MaxDiff 1";
}

void check_opencv_matcher_size(OpenCvMatcher matcher, cv::Size size, int ndisp, const std::string& what) {
  const std::string got = std::to_string(size.width) + " x " + std::to_string(size.height);
  if (matcher == OpenCvMatcher::Sgbm && size.width <= round_up_to_16(ndisp)) {
    throw InputError(what, "are " + got + ": opencv-sgbm needs images wider than the disparity range rounded up to 16 (" +
                               std::to_string(round_up_to_16(ndisp)) + " px for ndisp " + std::to_string(ndisp) + ")");
  }
  if (matcher == OpenCvMatcher::Bm && (size.width < 10 || size.height < 10)) {
    throw InputError(what, "are " + got + ": opencv-bm needs images of at least 10 x 10 pixels (its 9 x 9 block)");
  }
}

cv::Mat run_opencv_matcher(OpenCvMatcher matcher, const cv::Mat& left_rgb8,
                           const cv::Mat& right_rgb8, int ndisp) {
  check_opencv_matcher_size(matcher, left_rgb8.size(), ndisp, "the images");
  cv::Mat left = left_rgb8, right = right_rgb8;
  if (matcher == OpenCvMatcher::Bm) {  // StereoBM takes 8-bit gray only
    cv::cvtColor(left_rgb8, left, cv::COLOR_RGB2GRAY);
    cv::cvtColor(right_rgb8, right, cv::COLOR_RGB2GRAY);
  }
  cv::Mat fixed_point;
  try {
    make_matcher(matcher, ndisp)->compute(left, right, fixed_point);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(std::string(opencv_matcher_name(matcher)) + " failed on " + std::to_string(left.cols) +
                             " x " + std::to_string(left.rows) + " images with ndisp " + std::to_string(ndisp) +
                             " (OpenCV: " + e.err + ")");
  }
  // 16-bit fixed point with 4 fractional bits; values below minDisparity mean "none".
  cv::Mat disparity(fixed_point.size(), CV_32FC1);
  for (int y = 0; y < fixed_point.rows; ++y) {
    const short* in = fixed_point.ptr<short>(y);
    float* out = disparity.ptr<float>(y);
    for (int x = 0; x < fixed_point.cols; ++x) {
      out[x] = in[x] < 0 ? std::numeric_limits<float>::infinity() : in[x] / 16.0f;
    }
  }
  return disparity;
}

}  // namespace flexsight

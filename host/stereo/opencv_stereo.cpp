#include "host/stereo/opencv_stereo.h"

#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

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

cv::Mat run_opencv_matcher(OpenCvMatcher matcher, const cv::Mat& left_rgb8,
                           const cv::Mat& right_rgb8, int ndisp) {
  cv::Mat left = left_rgb8, right = right_rgb8;
  if (matcher == OpenCvMatcher::Bm) {  // StereoBM takes 8-bit gray only
    cv::cvtColor(left_rgb8, left, cv::COLOR_RGB2GRAY);
    cv::cvtColor(right_rgb8, right, cv::COLOR_RGB2GRAY);
  }
  cv::Mat fixed_point;
  make_matcher(matcher, ndisp)->compute(left, right, fixed_point);
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

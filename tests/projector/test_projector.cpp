// Tests of the projector as a third view (host/projector): on a bin from `flexsight synth
// bin` (640x480, the size at which the dots are still resolved), decoding along the
// camera-projector rows finds the true disparity at pixels both cameras see, and a
// projector put in the wrong place does not; the pattern estimated from the bin's true
// disparities agrees with the bin's pattern file, and the near/far check prefers the true
// pose; the check flags a band of pixels shifted 5 px off the truth and few of the true
// ones; `flexsight projector decode` refuses a calibration without a projector.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/pfm.h"
#include "host/projector/projector_calibrate.h"
#include "host/projector/projector_check.h"
#include "host/projector/projector_decode.h"
#include "host/projector/projector_visibility.h"
#include "tests/cli/cli_test_support.h"

namespace {

using namespace flexsight;
using namespace cli_test_support;

class ProjectorBin : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_temp_dir("ProjectorBin"));
    const RunResult r = run_flexsight("synth bin --count 2 --seed 7 --size 640x480 --parts 6..6 --cad " +
                                          std::string(FLEXSIGHT_TLESS_CAD_DIR) + " -o " + (*dir_ / "bins").string(),
                                      *dir_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path bin() { return *dir_ / "bins" / "bin000"; }
  // Both bins' left views with their true disparities, every finite pixel confident.
  static std::vector<CalibrationView> ground_truth_views(const MiddleburyCalib& calib) {
    std::vector<CalibrationView> views;
    for (const char* name : {"bin000", "bin001"}) {
      const fs::path folder = *dir_ / "bins" / name;
      const cv::Mat truth = read_pfm((folder / "disp0GT.pfm").string());
      views.push_back(calibration_view(load_rgb8((folder / "im0.png").string()), truth, cv::abs(truth) < 1e6f, calib));
    }
    return views;
  }
  static fs::path* dir_;
};
fs::path* ProjectorBin::dir_ = nullptr;

// The share of the decoded pixels of a grid over the non-occluded pixels that land
// within 2 px of the truth, and how many were decoded.
struct GridScore {
  double within2 = 0;
  int decoded = 0, asked = 0;
};

GridScore decode_grid(const fs::path& bin, const ProjectorCalib& projector) {
  const MiddleburyCalib calib = read_middlebury_calib((bin / "calib.txt").string());
  const cv::Mat left = load_rgb8((bin / "im0.png").string());
  const cv::Mat truth = read_pfm((bin / "disp0GT.pfm").string());
  const cv::Mat nocc = load_rgb8((bin / "mask0nocc.png").string());
  cv::Mat asked(left.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 8; y < left.rows - 8; y += 9) {
    for (int x = 8; x < left.cols - 8; x += 9) {
      if (nocc.at<cv::Vec3b>(y, x)[0] == 255) asked.at<std::uint8_t>(y, x) = 255;
    }
  }
  const cv::Mat start(left.size(), CV_32FC1, cv::Scalar(-1000));
  const ProjectorDecodeResult result =
      decode_with_projector(left, start, asked, calib, projector, load_pattern(projector));
  GridScore score;
  score.asked = result.asked;
  score.decoded = result.decoded;
  int good = 0;
  for (int y = 0; y < left.rows; ++y) {
    for (int x = 0; x < left.cols; ++x) {
      if (result.state.at<std::uint8_t>(y, x) != 1) continue;
      good += std::abs(result.disparity.at<float>(y, x) - truth.at<float>(y, x)) <= 2.0f;
    }
  }
  score.within2 = score.decoded ? double(good) / score.decoded : 0.0;
  return score;
}

TEST_F(ProjectorBin, DecodesTheTrueDisparityAndNotWithAWrongPose) {
  const MiddleburyCalib calib = read_middlebury_calib((bin() / "calib.txt").string());
  ASSERT_TRUE(calib.projector.has_value());
  const GridScore right_pose = decode_grid(bin(), *calib.projector);
  ASSERT_GT(right_pose.asked, 1000);
  EXPECT_GT(right_pose.decoded, right_pose.asked / 3);
  EXPECT_GT(right_pose.within2, 0.9);
  ProjectorCalib moved = *calib.projector;
  moved.t[0] -= 60.0;  // 60 mm further right: every depth decodes to another disparity
  const GridScore wrong_pose = decode_grid(bin(), moved);
  EXPECT_LT(wrong_pose.within2, 0.5);
}

TEST_F(ProjectorBin, EstimatesThePatternFromKnownDisparities) {
  const MiddleburyCalib calib = read_middlebury_calib((bin() / "calib.txt").string());
  const std::vector<CalibrationView> views = ground_truth_views(calib);
  const ProjectorCalib at_middle = projector_on_baseline(calib, 35.0, 0.0, "");
  const PatternEstimate estimate = estimate_pattern(views, at_middle);
  const cv::Mat pattern = load_pattern(*calib.projector);
  ASSERT_EQ(estimate.mean.size(), pattern.size());
  const cv::Mat everywhere(pattern.size(), CV_32FC1, cv::Scalar(1));
  EXPECT_GT(pattern_agreement(estimate.mean, estimate.weight, pattern, everywhere), 0.6);
  // The pose check: the two bins (the floor at one depth, the parts elsewhere) disagree
  // at least twice as much 40 mm off as at the true place.
  const double true_pose = split_agreement(views, at_middle);
  const double off = split_agreement(views, projector_on_baseline(calib, 35.0, 40.0, ""));
  EXPECT_LT(2.0 * (1.0 - true_pose), 1.0 - off) << true_pose << " vs " << off;
}

TEST_F(ProjectorBin, CoverageGrowsWithTheScenesPooled) {
  const MiddleburyCalib calib = read_middlebury_calib((bin() / "calib.txt").string());
  const std::vector<CalibrationView> views = ground_truth_views(calib);
  const ProjectorCalib at_middle = projector_on_baseline(calib, 35.0, 0.0, "");
  const double one = pattern_coverage(estimate_pattern({views[0]}, at_middle), calib, at_middle);
  const double both = pattern_coverage(estimate_pattern(views, at_middle), calib, at_middle);
  EXPECT_GT(one, 0.2);
  EXPECT_LT(one, 1.0);
  EXPECT_GT(both, one);
}

// The true disparity with rows 200..279 shifted by 5 px: the check flags most of the
// shifted band and few of the rest, and --replace gives most flagged pixels back a value
// within 2 px of the truth.
TEST_F(ProjectorBin, CheckFlagsABandShiftedOffTheTruth) {
  const MiddleburyCalib calib = read_middlebury_calib((bin() / "calib.txt").string());
  ASSERT_TRUE(calib.projector.has_value());
  const cv::Mat left = load_rgb8((bin() / "im0.png").string());
  const cv::Mat truth = read_pfm((bin() / "disp0GT.pfm").string());
  const cv::Mat nocc = load_rgb8((bin() / "mask0nocc.png").string());
  cv::Mat disparity(truth.size(), CV_32FC1, cv::Scalar(std::numeric_limits<float>::infinity()));
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      if (nocc.at<cv::Vec3b>(y, x)[0] != 255 || !(std::abs(truth.at<float>(y, x)) < 1e6f)) continue;
      disparity.at<float>(y, x) = truth.at<float>(y, x) + ((y >= 200 && y < 280) ? 5.0f : 0.0f);
    }
  }
  ProjectorCheckParams params;
  params.replace = true;
  const ProjectorCheckResult result =
      check_with_projector(left, disparity, calib, *calib.projector, load_pattern(*calib.projector), params);
  int band = 0, band_flagged = 0, rest = 0, rest_flagged = 0, replaced_good = 0, replaced = 0;
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      if (!std::isfinite(disparity.at<float>(y, x))) continue;
      const bool flagged = result.flagged.at<std::uint8_t>(y, x) != 0;
      const bool shifted = y >= 200 && y < 280;
      (shifted ? band : rest) += 1;
      (shifted ? band_flagged : rest_flagged) += flagged;
      const float out = result.disparity.at<float>(y, x);
      if (shifted && flagged && std::isfinite(out)) {
        ++replaced;
        replaced_good += std::abs(out - truth.at<float>(y, x)) <= 2.0f;
      }
    }
  }
  ASSERT_GT(band, 10000);
  ASSERT_GT(result.checked, rest / 2);
  EXPECT_GT(band_flagged, band / 2) << band_flagged << " of " << band;
  EXPECT_LT(rest_flagged, rest / 10) << rest_flagged << " of " << rest;
  EXPECT_GT(replaced, band_flagged / 2);
  EXPECT_GT(replaced_good, replaced * 8 / 10) << replaced_good << " of " << replaced;
}

// A flat surface at disparity 40 that both views agree on: a candidate nearer the cameras
// stands in front of what the right camera sees; one farther lies in the surface's
// projector shadow; the surface itself is possible.
TEST(StereoVisibility, RulesOutFreeSpaceAndShadowOfAPlane) {
  MiddleburyCalib calib;
  calib.cam0 = {500, 0, 160, 0, 500, 120, 0, 0, 1};
  calib.cam1 = {500, 0, 160, 0, 500, 120, 0, 0, 1};
  calib.baseline_mm = 500;
  calib.width = 320;
  calib.height = 240;
  calib.ndisp = 96;
  const ProjectorCalib projector = projector_on_baseline(calib, 35.0, 0.0, "");
  const LeftCamera camera(calib);
  const cv::Mat pattern(projector.height, projector.width, CV_32FC1, cv::Scalar(0.5));
  const VirtualView view = make_virtual_view(camera, projector, pattern);
  const cv::Mat plane(240, 320, CV_32FC1, cv::Scalar(40));
  const StereoVisibility visibility(plane, plane, camera, projector, view, 2.0f);
  EXPECT_TRUE(visibility.possible(200, 100, 40.0));
  EXPECT_TRUE(visibility.in_free_space(200, 100, 50.0));
  EXPECT_FALSE(visibility.in_shadow(200, 100, 50.0));
  EXPECT_TRUE(visibility.in_shadow(200, 100, 30.0));
  EXPECT_FALSE(visibility.in_free_space(200, 100, 30.0));
}

TEST_F(ProjectorBin, DecodeRefusesACalibrationWithoutProjector) {
  const fs::path dir = *dir_ / "no_projector";
  fs::create_directories(dir);
  for (const char* name : {"im0.png", "im1.png"}) fs::copy(bin() / name, dir / name);
  std::ifstream in(bin() / "calib.txt");
  std::ofstream out(dir / "calib.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("proj", 0) != 0) out << line << "\n";
  }
  out.close();
  const cv::Mat disparity(480, 640, CV_32FC1, cv::Scalar(10));
  for (const char* suffix : {"_disp.pfm", "_raw.pfm", "_raw_right.pfm"}) {
    write_pfm((dir / (std::string("no_projector") + suffix)).string(), disparity);
  }
  const RunResult r = run_flexsight("projector decode " + dir.string() + " --stereo " + dir.string() + " -o " +
                                        (dir / "out.pfm").string(),
                                    dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("has no projector entry"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.pfm"));
}

}  // namespace

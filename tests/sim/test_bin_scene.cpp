// One simulated bin: the rig's geometry, the ground truth's consistency (the left
// passive image warped by disp0GT onto the right one), calib.txt read back by the
// project's reader, and the BOP files read back by the BOP reader.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "host/dataset/bop_reader.h"
#include "host/io/calibration.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/sim/bin_scene.h"
#include "host/sim/bin_writer.h"
#include "tests/common/test_support.h"

using namespace flexsight;
namespace fs = std::filesystem;

namespace {

BinSimSettings small_settings() {
  BinSimSettings settings;
  settings.rig.width = 320;
  settings.rig.height = 240;
  settings.min_parts = settings.max_parts = 5;
  settings.noise_sigma = 0.0;
  settings.threads = 2;
  return settings;
}

const PartLibrary& tless() {
  static const PartLibrary parts = PartLibrary::load_folder(FLEXSIGHT_TLESS_CAD_DIR);
  return parts;
}

double grey(const cv::Vec3f& c) { return (c[0] + c[1] + c[2]) / 3.0; }

}  // namespace

TEST(StereoRig, VolumeFillsBothViewsAndDisparitiesArePositive) {
  const StereoRig rig = make_stereo_rig(StereoRigSettings{});
  EXPECT_EQ(rig.left.fx, rig.right.fx);
  EXPECT_EQ(rig.left.cy, rig.right.cy);
  EXPECT_DOUBLE_EQ(rig.right.cx - rig.left.cx, rig.doffs);
  // The volume's centroid near the middle of both views.
  const Eigen::Vector3d centroid(250.0, 0.0, 1250.0);
  EXPECT_NEAR(rig.left.project(centroid).x(), 639.5, 60.0);
  EXPECT_NEAR(rig.right.project(centroid - Eigen::Vector3d(500, 0, 0)).x(), 639.5, 60.0);
  // The volume's near face at the top of the disparity range, the floor beyond it at
  // small positive disparities.
  EXPECT_GT(rig.disparity(1450.0), 0.0);
  EXPECT_LT(rig.disparity(1050.0), rig.ndisp);
  EXPECT_GT(rig.disparity(1050.0), rig.ndisp - 5);
  // World (bin frame, z up) to left camera: the floor's middle straight ahead at 1450 mm.
  EXPECT_TRUE(rig.left_point(Eigen::Vector3d::Zero()).isApprox(Eigen::Vector3d(250, 0, 1450)));
  EXPECT_TRUE(rig.left_point(Eigen::Vector3d(0, 0, 100)).isApprox(Eigen::Vector3d(250, 0, 1350)));
  // The full sensor takes the same geometry.
  StereoRigSettings full;
  full.width = 4000;
  full.height = 3000;
  const StereoRig big = make_stereo_rig(full);
  EXPECT_NEAR(big.focal() / rig.focal(), 4000.0 / 1280.0, 0.01);
  // A focal length too long for the volume is refused, naming --focal.
  full.focal_px = 20000.0;
  try {
    make_stereo_rig(full);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--focal"), std::string::npos) << e.what();
  }
}

TEST(BinScene, GroundTruthIsPhotoConsistentAndFilesReadBack) {
  const BinSimulator simulator(small_settings(), tless());
  const BinViews views = simulator.simulate(11, 0);
  const StereoRig& rig = simulator.rig();
  ASSERT_GE(views.parts.size(), 4u);
  ASSERT_EQ(views.im0.size(), cv::Size(320, 240));

  // Warp: the left passive image against the right one at x - d, on the non-occluded
  // pixels. With no noise the two views differ only by the highlights and sampling.
  cv::Mat left, right;
  views.im0_passive.convertTo(left, CV_32FC3);
  views.im1_passive.convertTo(right, CV_32FC3);
  int checked = 0, close = 0;
  for (int y = 0; y < left.rows; ++y) {
    for (int x = 0; x < left.cols; ++x) {
      if (views.nocc0.at<std::uint8_t>(y, x) == 0) continue;
      const float d = views.disp0.at<float>(y, x);
      ASSERT_TRUE(std::isfinite(d));
      const double u = x - d;
      const int u0 = int(std::floor(u));
      if (u0 < 0 || u0 + 1 >= right.cols) continue;
      const double w = u - u0;
      const double warped = (1 - w) * grey(right.at<cv::Vec3f>(y, u0)) + w * grey(right.at<cv::Vec3f>(y, u0 + 1));
      ++checked;
      close += std::abs(warped - grey(left.at<cv::Vec3f>(y, x))) <= 4.0;
    }
  }
  ASSERT_GT(checked, 320 * 240 / 2);
  EXPECT_GT(double(close) / checked, 0.9) << close << " of " << checked;
  // A disparity off by two pixels is not consistent: the test can fail.
  int shifted_close = 0;
  for (int y = 0; y < left.rows; ++y) {
    for (int x = 0; x < left.cols; ++x) {
      if (views.nocc0.at<std::uint8_t>(y, x) == 0) continue;
      const int u = int(std::lround(x - views.disp0.at<float>(y, x))) - 2;
      if (u < 0 || u >= right.cols) continue;
      shifted_close += std::abs(grey(right.at<cv::Vec3f>(y, u)) - grey(left.at<cv::Vec3f>(y, x))) <= 4.0;
    }
  }
  EXPECT_LT(shifted_close, close);

  // Disparities within 0..ndisp; the dots are in the active images only.
  double lo = 0, hi = 0;
  cv::minMaxLoc(views.disp0, &lo, &hi);
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, rig.ndisp);
  cv::Mat diff;
  cv::absdiff(views.im0, views.im0_passive, diff);
  std::vector<cv::Mat> channels;
  cv::split(diff, channels);
  // (At 320x240 a pixel spans ten dot widths: the dots blur into a faint red glow.)
  EXPECT_GT(cv::sum(channels[0])[0], 3.0 * cv::sum(channels[1])[0]);
  EXPECT_GT(cv::sum(channels[0])[0], 2.0 * 320 * 240);

  // The files.
  const fs::path dir = flexsight::testing_support::fresh_temp_dir("bin_scene") / "bin000";
  fs::create_directories(dir);
  write_bin_folder(dir.string(), rig, views);
  const MiddleburyCalib calib = read_middlebury_calib((dir / "calib.txt").string());
  EXPECT_NEAR(calib.cam0[0], rig.focal(), 1e-3);
  EXPECT_NEAR(calib.cam1[2] - calib.cam0[2], calib.doffs, 1e-3);
  EXPECT_NEAR(calib.doffs, rig.doffs, 1e-3);
  EXPECT_NEAR(calib.baseline_mm, 500.0, 1e-9);
  EXPECT_EQ(calib.width, 320);
  EXPECT_EQ(calib.height, 240);
  EXPECT_EQ(calib.ndisp, rig.ndisp);
  // The projector: at the middle of the baseline, the pattern beside calib.txt.
  ASSERT_TRUE(calib.projector.has_value());
  EXPECT_NEAR(calib.projector->t[0], -250.0, 1e-9);
  EXPECT_NEAR(calib.projector->K[0], rig.focal(), 1e-3);
  const cv::Mat pattern = cv::imread(calib.projector->pattern_path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(pattern.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(pattern, views.pattern, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::mean(pattern)[0], 5.0);  // dots, not an empty image
  const cv::Mat disp = read_pfm((dir / "disp0GT.pfm").string());
  EXPECT_EQ(cv::norm(disp, views.disp0, cv::NORM_INF), 0.0);
  const BopReader reader(dir.string());
  ASSERT_EQ(reader.size(), 1u);
  const AnnotatedImage bop = reader.load(0);
  ASSERT_EQ(bop.parts.size(), views.parts.size());
  for (std::size_t i = 0; i < bop.parts.size(); ++i) {
    const Pose pose = rig.to_left(views.parts[i].world);
    EXPECT_LT((bop.parts[i].cam_t_m2c - pose.t).norm(), 1e-3);
    EXPECT_EQ(bop.parts[i].obj_id, views.parts[i].obj_id);
  }
  // Depth: Z = f B / (d + doffs) at every pixel, within the PNG's 0.1 mm.
  for (int y = 0; y < 240; y += 7) {
    for (int x = 0; x < 320; x += 7) {
      const double z = rig.focal() * 500.0 / (views.disp0.at<float>(y, x) + rig.doffs);
      EXPECT_NEAR(bop.depth.at<float>(y, x), z, 0.1);
    }
  }
}

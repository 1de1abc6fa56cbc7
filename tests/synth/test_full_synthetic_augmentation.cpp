// The post-processing against the same image without it: a flip mirrors every pixel,
// mask and box and reflects the poses; the in-plane rotation turns the poses by a
// rotation about the optical axis and the masks with them; the corners it uncovers show
// background, not black.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/synth/full_synthetic.h"
#include "tests/render/render_test_support.h"
#include "tests/synth/synth_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

AnnotatedImage render(const FullSyntheticSettings& settings, std::int64_t index) {
  return render_full_synthetic(settings, tless_parts(), real_backgrounds(), 21, index);
}

// Intersection over union of two masks.
double iou(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat both, either;
  cv::bitwise_and(a, b, both);
  cv::bitwise_or(a, b, either);
  return double(cv::countNonZero(both)) / std::max(1, cv::countNonZero(either));
}

// Mean absolute difference between `turned`'s background and `plain`'s background
// sampled (bilinear) where `to_plain` maps each pixel, over the pixels that see
// background in both pictures, away from parts and borders; `count` gets their number.
double background_difference(const AnnotatedImage& plain, const AnnotatedImage& turned,
                             const cv::Matx23d& to_plain, int& count) {
  double sum = 0.0;
  count = 0;
  for (int y = 0; y < turned.rgb.rows; ++y) {
    for (int x = 0; x < turned.rgb.cols; ++x) {
      if (turned.depth.at<float>(y, x) > 0.0f) continue;
      const double u = to_plain(0, 0) * x + to_plain(0, 1) * y + to_plain(0, 2);
      const double v = to_plain(1, 0) * x + to_plain(1, 1) * y + to_plain(1, 2);
      const int u0 = int(std::floor(u)), v0 = int(std::floor(v));
      if (u0 < 1 || v0 < 1 || u0 + 2 >= plain.rgb.cols || v0 + 2 >= plain.rgb.rows) continue;
      bool part = false;
      for (int dv = -1; dv <= 2; ++dv)
        for (int du = -1; du <= 2; ++du) part |= plain.depth.at<float>(v0 + dv, u0 + du) > 0.0f;
      if (part) continue;
      const double a = u - u0, b = v - v0;
      for (int c = 0; c < 3; ++c) {
        const auto at = [&](int vv, int uu) { return double(plain.rgb.at<cv::Vec3b>(vv, uu)[c]); };
        const double sample = (1 - b) * ((1 - a) * at(v0, u0) + a * at(v0, u0 + 1)) +
                              b * ((1 - a) * at(v0 + 1, u0) + a * at(v0 + 1, u0 + 1));
        sum += std::abs(sample - turned.rgb.at<cv::Vec3b>(y, x)[c]);
      }
      ++count;
    }
  }
  return sum / (3.0 * std::max(count, 1));
}

}  // namespace

// The same image unflipped, flipped left-right, upside down and both: the random draws
// are the same, so the flipped images are the unflipped one's pixels mirrored.
TEST(SynthFullSyntheticAugmentation, FlipsMirrorPixelsMasksBoxesAndPoses) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  settings.width = 241;  // odd: the centre column maps onto itself
  settings.height = 180;
  for (int index = 0; index < 3; ++index) {
    settings.horizontal_flip_probability = settings.vertical_flip_probability = 0.0;
    const AnnotatedImage plain = render(settings, index);
    ASSERT_FALSE(plain.mirrored());
    for (const auto& [h, v] : {std::pair{1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}}) {
      SCOPED_TRACE("image " + std::to_string(index) + " flips " + std::to_string(h) + " " +
                   std::to_string(v));
      settings.horizontal_flip_probability = h;
      settings.vertical_flip_probability = v;
      const AnnotatedImage flipped = render(settings, index);
      EXPECT_EQ(flipped.flipped_horizontally, h == 1.0);
      EXPECT_EQ(flipped.flipped_vertically, v == 1.0);
      EXPECT_EQ(flipped.mirrored(), h != v);
      const int code = h == 1.0 && v == 1.0 ? -1 : (h == 1.0 ? 1 : 0);
      cv::Mat expected;
      cv::flip(plain.rgb, expected, code);
      EXPECT_TRUE(same_mat_bytes(flipped.rgb, expected));
      cv::flip(plain.depth, expected, code);
      EXPECT_TRUE(same_mat_bytes(flipped.depth, expected));
      const Eigen::Matrix3d F = flip_matrix(flipped);
      ASSERT_EQ(flipped.parts.size(), plain.parts.size());
      for (size_t i = 0; i < plain.parts.size(); ++i) {
        const PartAnnotation& a = plain.parts[i];
        const PartAnnotation& b = flipped.parts[i];
        EXPECT_EQ(b.obj_id, a.obj_id);
        EXPECT_EQ(b.cam_R_m2c, F * a.cam_R_m2c);
        EXPECT_EQ(b.cam_t_m2c, F * a.cam_t_m2c);
        cv::flip(a.mask, expected, code);
        EXPECT_TRUE(same_mat_bytes(b.mask, expected));
        cv::flip(a.mask_visib, expected, code);
        EXPECT_TRUE(same_mat_bytes(b.mask_visib, expected));
        const int x = h == 1.0 ? settings.width - a.bbox_obj.x - a.bbox_obj.width : a.bbox_obj.x;
        const int y = v == 1.0 ? settings.height - a.bbox_obj.y - a.bbox_obj.height : a.bbox_obj.y;
        EXPECT_EQ(b.bbox_obj, (BopBox{x, y, a.bbox_obj.width, a.bbox_obj.height}));
        EXPECT_EQ(b.px_count_all, a.px_count_all);
        EXPECT_EQ(b.px_count_visib, a.px_count_visib);
        EXPECT_EQ(b.visib_fract, a.visib_fract);
      }
    }
  }
}

// The same draws with and without the in-plane rotation (no cap, no flips, so that the
// same parts are kept; no noise or blur, so that backgrounds compare): every part's pose
// turns by one rotation Q about the optical axis within the range, and its mask and the
// background turn with it about the principal point, the same way.
TEST(SynthFullSyntheticAugmentation, InPlaneRotationTurnsPosesMasksAndBackground) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  settings.horizontal_flip_probability = settings.vertical_flip_probability = 0.0;
  settings.max_noise_sigma = 0.0;
  settings.blur_probability = 0.0;
  settings.min_visible_fraction = 0.0;
  settings.min_parts = settings.max_parts = 3;
  settings.min_part_size = 0.2;
  int compared = 0;
  double right_turn = 0.0, wrong_turn = 0.0;
  for (int index = 0; index < 6; ++index) {
    SCOPED_TRACE("image " + std::to_string(index));
    settings.max_rotation_degrees = 0.0;
    const AnnotatedImage plain = render(settings, index);
    settings.max_rotation_degrees = 15.0;
    const AnnotatedImage turned = render(settings, index);
    if (turned.parts.size() != plain.parts.size()) continue;  // a part rotated out of view
    const Eigen::Matrix3d Q = turned.parts[0].cam_R_m2c * plain.parts[0].cam_R_m2c.transpose();
    const double angle = std::atan2(Q(1, 0), Q(0, 0));
    EXPECT_LE(std::abs(angle), 15.0 * M_PI / 180.0);
    EXPECT_GT(std::abs(angle), 1e-6);
    const Eigen::Matrix3d Rz =
        Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    // Poses (x_cam' = Q x_cam) and the pixel rotation that goes with it (fx == fy).
    const double cx = turned.camera.K(0, 2), cy = turned.camera.K(1, 2);
    const cv::Matx23d to_plain(Rz(0, 0), Rz(1, 0), cx - Rz(0, 0) * cx - Rz(1, 0) * cy, Rz(0, 1),
                               Rz(1, 1), cy - Rz(0, 1) * cx - Rz(1, 1) * cy);
    // The background: resampled twice, so not to the byte, but far closer than when
    // turned the other way.
    const cv::Matx23d wrong_way(Rz(0, 0), Rz(0, 1), cx - Rz(0, 0) * cx - Rz(0, 1) * cy, Rz(1, 0),
                                Rz(1, 1), cy - Rz(1, 0) * cx - Rz(1, 1) * cy);
    int pixels = 0;
    const double right = background_difference(plain, turned, to_plain, pixels);
    EXPECT_GT(pixels, 10000);
    EXPECT_LT(right, 4.0);
    right_turn += right;
    wrong_turn += background_difference(plain, turned, wrong_way, pixels);
    for (size_t i = 0; i < plain.parts.size(); ++i) {
      const PartAnnotation& a = plain.parts[i];
      const PartAnnotation& b = turned.parts[i];
      ASSERT_EQ(b.obj_id, a.obj_id);
      EXPECT_LT((b.cam_R_m2c - Rz * a.cam_R_m2c).norm(), 1e-9);
      EXPECT_LT((b.cam_t_m2c - Rz * a.cam_t_m2c).norm(), 1e-9 * a.cam_t_m2c.norm());
      // The plain mask turned (nearest pixel) against the turned image's mask, for parts
      // well inside both pictures.
      const auto inside = [&](const BopBox& box) {
        return box.x > 0 && box.y > 0 && box.x + box.width < settings.width &&
               box.y + box.height < settings.height;
      };
      if (a.px_count_all < 300 || !inside(a.bbox_obj) || !inside(b.bbox_obj)) continue;
      cv::Mat warped;
      cv::warpAffine(a.mask, warped, to_plain, a.mask.size(),
                     cv::INTER_NEAREST | cv::WARP_INVERSE_MAP);
      EXPECT_GT(iou(warped, b.mask), 0.9);
      ++compared;
    }
  }
  EXPECT_GE(compared, 4);
  EXPECT_GT(wrong_turn, 10.0 * right_turn);
}

// A background of one colour, turned by up to 15 degrees, without noise or blur: every
// pixel no part covers is that colour, the uncovered corners included.
TEST(SynthFullSyntheticAugmentation, RotatedCornersShowBackgroundNotBlack) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  TempFolder folder;
  cv::imwrite(folder / "plain.png", cv::Mat(120, 200, CV_8UC3, cv::Scalar(50, 100, 200)));
  const BackgroundLibrary backgrounds(folder.str());
  FullSyntheticSettings settings;
  settings.max_rotation_degrees = 15.0;
  settings.max_noise_sigma = 0.0;
  settings.blur_probability = 0.0;
  for (int index = 0; index < 4; ++index) {
    const AnnotatedImage image =
        render_full_synthetic(settings, tless_parts(), backgrounds, 2, index);
    int wrong = 0;
    for (int y = 0; y < image.rgb.rows; ++y) {
      for (int x = 0; x < image.rgb.cols; ++x) {
        if (image.depth.at<float>(y, x) > 0.0f) continue;
        if (image.rgb.at<cv::Vec3b>(y, x) != cv::Vec3b(200, 100, 50)) ++wrong;
      }
    }
    EXPECT_EQ(wrong, 0) << "image " << index;
  }
}

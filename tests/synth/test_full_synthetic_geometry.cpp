// What every full-synthetic image must satisfy, checked on real T-LESS parts and
// backgrounds: the occlusion cap, parts' sizes in range, boxes and counts equal to those
// of the masks, visible within amodal, and poses consistent with the pixels (the model's
// vertices project onto the box, a re-cast of the posed model gives the stored depth),
// after in-plane rotations and flips too.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "host/render/raycaster.h"
#include "host/synth/full_synthetic.h"
#include "tests/synth/synth_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

PinholeCamera camera_of(const AnnotatedImage& image) {
  PinholeCamera camera;
  camera.width = image.rgb.cols;
  camera.height = image.rgb.rows;
  camera.fx = image.camera.K(0, 0);
  camera.fy = image.camera.K(1, 1);
  camera.cx = image.camera.K(0, 2);
  camera.cy = image.camera.K(1, 2);
  return camera;
}

// The box of the model's vertices projected with the stored pose, in pixel coordinates.
cv::Rect2d projected_vertex_box(const Mesh& mesh, const PartAnnotation& part,
                                const PinholeCamera& camera) {
  double lo_u = INFINITY, lo_v = INFINITY, hi_u = -INFINITY, hi_v = -INFINITY;
  for (const Eigen::Vector3f& vertex : mesh.positions) {
    const Eigen::Vector2d uv =
        camera.project(part.cam_R_m2c * vertex.cast<double>() + part.cam_t_m2c);
    lo_u = std::min(lo_u, uv.x()), hi_u = std::max(hi_u, uv.x());
    lo_v = std::min(lo_v, uv.y()), hi_v = std::max(hi_v, uv.y());
  }
  return {lo_u, lo_v, hi_u - lo_u, hi_v - lo_v};
}

// The depth of the part alone, ray cast anew at the pose the renderer used (the stored
// one unreflected) and flipped as the picture was.
cv::Mat recast_depth(const Mesh& mesh, const PartAnnotation& part, const AnnotatedImage& image) {
  const Eigen::Matrix3d F = flip_matrix(image);
  RenderScene scene;
  Pose pose;
  pose.R = F * part.cam_R_m2c;
  pose.t = F * part.cam_t_m2c;
  scene.add_instance(scene.add_mesh(std::make_shared<const Mesh>(mesh)), pose);
  scene.commit();
  cv::Mat depth = raycast(scene, camera_of(image)).depth;
  if (image.flipped_horizontally || image.flipped_vertically) {
    cv::flip(depth, depth,
             image.flipped_horizontally && image.flipped_vertically
                 ? -1
                 : (image.flipped_horizontally ? 1 : 0));
  }
  return depth;
}

// Every invariant of one image; `recast` adds the (slower) depth comparison. Adds to
// `in_view` the parts whose whole box was compared with their projected vertices.
void check_image(const AnnotatedImage& image, const FullSyntheticSettings& settings, bool recast,
                 int& in_view_parts) {
  const PartLibrary& library = tless_parts();
  const PinholeCamera camera = camera_of(image);
  ASSERT_EQ(image.rgb.size(), cv::Size(settings.width, settings.height));
  ASSERT_EQ(image.depth.size(), image.rgb.size());
  ASSERT_FALSE(image.parts.empty());
  ASSERT_LE(int(image.parts.size()), settings.max_parts);
  int visible_total = 0;
  for (size_t i = 0; i < image.parts.size(); ++i) {
    SCOPED_TRACE("part " + std::to_string(i));
    const PartAnnotation& part = image.parts[i];
    const int index = library.index_of(part.obj_id);
    ASSERT_GE(index, 0);
    const Mesh& mesh = *library.part(index).mesh;

    // The occlusion cap, and the numbers from the masks.
    EXPECT_GE(part.visib_fract, settings.min_visible_fraction);
    EXPECT_EQ(part.bbox_obj, mask_box(part.mask));
    EXPECT_EQ(part.bbox_visib, mask_box(part.mask_visib));
    EXPECT_EQ(part.px_count_all, cv::countNonZero(part.mask));
    EXPECT_EQ(part.px_count_visib, cv::countNonZero(part.mask_visib));
    EXPECT_EQ(part.px_count_valid, part.px_count_all);  // a part is a surface everywhere
    EXPECT_DOUBLE_EQ(part.visib_fract, double(part.px_count_visib) / part.px_count_all);
    cv::Mat outside;
    cv::bitwise_and(part.mask_visib, ~part.mask, outside);
    EXPECT_EQ(cv::countNonZero(outside), 0) << "visible pixels outside the amodal mask";
    visible_total += part.px_count_visib;

    // A reflected pose after one flip, a rotation otherwise.
    EXPECT_NEAR(part.cam_R_m2c.determinant(), image.mirrored() ? -1.0 : 1.0, 1e-9);
    // Projected diameter in range: f d / z of the box centre (flips and the in-plane
    // rotation leave z alone).
    const double z = (part.cam_R_m2c * mesh.bounds.center().cast<double>() + part.cam_t_m2c).z();
    const double size = camera.fx * mesh.diameter / z / settings.width;
    EXPECT_GE(size, settings.min_part_size * (1 - 1e-9));
    EXPECT_LE(size, settings.max_part_size * (1 + 1e-9));

    // The vertices project around the amodal box: it reaches no more than a pixel past
    // them; where the whole part is in view, it spans them to two pixels (a pixel counts
    // when its centre is on the part, and a thin extreme, a pin or a sharp corner, can
    // miss the centres of its last column: up to 1.2 pixels seen).
    const cv::Rect2d vertices = projected_vertex_box(mesh, part, camera);
    const BopBox& box = part.bbox_obj;
    EXPECT_GE(box.x, vertices.x - 1.0);
    EXPECT_GE(box.y, vertices.y - 1.0);
    EXPECT_LE(box.x + box.width - 1, vertices.br().x + 1.0);
    EXPECT_LE(box.y + box.height - 1, vertices.br().y + 1.0);
    const bool in_view = vertices.x > 1 && vertices.y > 1 && vertices.br().x < camera.width - 2 &&
                         vertices.br().y < camera.height - 2;
    if (in_view) {
      ++in_view_parts;
      const double slack = 2.0;
      EXPECT_LE(box.x, vertices.x + slack);
      EXPECT_LE(box.y, vertices.y + slack);
      EXPECT_GE(box.x + box.width - 1, vertices.br().x - slack);
      EXPECT_GE(box.y + box.height - 1, vertices.br().y - slack);
      if (part.visib_fract == 1.0) {
        EXPECT_EQ(part.bbox_visib, part.bbox_obj);
      }
    }

    // The stored depth is the posed model's surface where the part is visible.
    if (recast) {
      const cv::Mat alone = recast_depth(mesh, part, image);
      int mismatches = 0;
      for (int y = 0; y < camera.height; ++y) {
        for (int x = 0; x < camera.width; ++x) {
          if (part.mask_visib.at<std::uint8_t>(y, x) == 0) continue;
          const float expected = alone.at<float>(y, x);
          if (!(expected > 0.0f) ||
              std::abs(image.depth.at<float>(y, x) - expected) > 1e-4f * expected) {
            ++mismatches;
          }
        }
      }
      EXPECT_EQ(mismatches, 0);
    }
  }
  // The visible masks share out the pixels where a part is.
  cv::Mat covered;
  cv::compare(image.depth, 0.0, covered, cv::CMP_GT);
  EXPECT_EQ(visible_total, cv::countNonZero(covered));
}

}  // namespace

// Defaults (random flips and rotation) at 300x300, and an awkward odd size with many
// parts, so the cap has work.
TEST(SynthFullSyntheticGeometry, EveryImageKeepsItsInvariants) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  int in_view = 0;
  for (int index = 0; index < 12; ++index) {
    SCOPED_TRACE("300x300, image " + std::to_string(index));
    check_image(render_full_synthetic(settings, tless_parts(), real_backgrounds(), 11, index),
                settings, index < 6, in_view);
  }
  settings.width = 317;
  settings.height = 229;
  settings.min_parts = 4;
  settings.max_parts = 8;
  for (int index = 0; index < 6; ++index) {
    SCOPED_TRACE("317x229, image " + std::to_string(index));
    check_image(render_full_synthetic(settings, tless_parts(), real_backgrounds(), 5, index),
                settings, true, in_view);
  }
  EXPECT_GE(in_view, 20);
}

// Large parts, six of them: poses are drawn again and parts dropped, and the cap holds
// at 0.5 and at 0.9.
TEST(SynthFullSyntheticGeometry, OcclusionCapResamplesAndDropsButHolds) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  settings.min_parts = settings.max_parts = 6;
  settings.min_part_size = 0.35;
  for (double cap : {0.5, 0.9}) {
    settings.min_visible_fraction = cap;
    int resampled = 0, dropped = 0;
    for (int index = 0; index < 8; ++index) {
      SCOPED_TRACE("cap " + std::to_string(cap) + ", image " + std::to_string(index));
      FullSyntheticStats stats;
      const AnnotatedImage image =
          render_full_synthetic(settings, tless_parts(), real_backgrounds(), 3, index, &stats);
      int in_view = 0;
      check_image(image, settings, false, in_view);
      EXPECT_EQ(int(image.parts.size()) + stats.parts_dropped, 6);
      resampled += stats.pose_attempts > 6 ? 1 : 0;
      dropped += stats.parts_dropped;
    }
    EXPECT_GT(resampled, 0);
    EXPECT_GT(dropped, 0);
  }
}

#include "host/render/part_row.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "host/render/shading.h"

namespace flexsight {

PartRow compose_part_row(const std::vector<std::shared_ptr<const Mesh>>& meshes, const PinholeCamera& camera,
                         const PartRowLayout& layout, std::uint32_t seed) {
  float spacing = 0.0f;
  for (const std::shared_ptr<const Mesh>& mesh : meshes) spacing = std::max(spacing, 1.1f * mesh->diameter);
  const double row = spacing * meshes.size();
  const double distance =
      layout.distance > 0.0 ? layout.distance : camera.fx * row / (0.6 * camera.width);
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(layout.rotation_degrees[2] * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(layout.rotation_degrees[1] * M_PI / 180.0, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(layout.rotation_degrees[0] * M_PI / 180.0, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();

  PartRow row_scene;
  row_scene.distance = distance;
  RenderScene& scene = row_scene.scene;
  for (size_t i = 0; i < meshes.size(); ++i) {
    Pose pose;
    pose.R = R;
    // The part's box centre on the row, the row centred on the optical axis.
    const Eigen::Vector3d slot((i + 0.5) * spacing - row / 2.0, 0.0, distance);
    pose.t = slot - R * meshes[i]->bounds.center().cast<double>();
    Material material;
    material.albedo = tinted_grey(seed, static_cast<int>(i));
    scene.add_instance(scene.add_mesh(meshes[i]), pose, material);
  }
  if (layout.floor) {
    // A matte floor just behind the deepest part, wide enough to fill the view.
    const double floor_z = distance + spacing / 2.0;
    const float half =
        static_cast<float>(floor_z * std::max(camera.width / camera.fx, camera.height / camera.fy));
    auto square = std::make_shared<const Mesh>(
        make_mesh("floor", {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}},
                  {{0, 1, 2}, {0, 2, 3}}));
    Pose pose;
    pose.t = {0.0, 0.0, floor_z};
    Material material;
    material.albedo = {0.35f, 0.35f, 0.37f};
    material.specular = 0.05f;
    scene.add_instance(scene.add_mesh(square), pose, material);
  }
  scene.commit();
  // The light above and to the left of the camera, a distance's height above the parts.
  row_scene.light = {static_cast<float>(-0.4 * distance), static_cast<float>(-0.8 * distance), 0.0f};
  return row_scene;
}

cv::Mat part_mask(const cv::Mat& instance, int parts) {
  cv::Mat mask(instance.size(), CV_8UC1);
  for (int y = 0; y < mask.rows; ++y) {
    for (int x = 0; x < mask.cols; ++x) {
      const int id = instance.at<std::int32_t>(y, x);
      mask.at<std::uint8_t>(y, x) = id >= 0 && id < parts ? std::uint8_t(id + 1) : 0;
    }
  }
  return mask;
}

}  // namespace flexsight

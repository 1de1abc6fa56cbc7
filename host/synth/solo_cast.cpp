#include "host/synth/solo_cast.h"

#include <algorithm>
#include <cmath>

#include "host/render/primary_rays.h"

namespace flexsight {

CameraRayTable::CameraRayTable(const PinholeCamera& camera) : dx(camera.width), dy(camera.height) {
  // The expressions of the ray caster's CameraRays (host/render/raycaster.cpp): the same
  // doubles rounded to the same floats.
  for (int u = 0; u < camera.width; ++u) dx[u] = static_cast<float>((u - camera.cx) / camera.fx);
  for (int v = 0; v < camera.height; ++v) dy[v] = static_cast<float>((v - camera.cy) / camera.fy);
}

cv::Rect projected_area(const Mesh& mesh, const Pose& pose, const PinholeCamera& camera) {
  const cv::Rect image(0, 0, camera.width, camera.height);
  double lo_u = INFINITY, lo_v = INFINITY, hi_u = -INFINITY, hi_v = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p =
        pose.R * mesh.bounds.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner))
                     .cast<double>() +
        pose.t;
    if (!(p.z() > 1e-6)) return image;
    const Eigen::Vector2d uv = camera.project(p);
    lo_u = std::min(lo_u, uv.x());
    hi_u = std::max(hi_u, uv.x());
    lo_v = std::min(lo_v, uv.y());
    hi_v = std::max(hi_v, uv.y());
  }
  const double x0 = std::max(std::floor(lo_u) - 1.0, 0.0);
  const double y0 = std::max(std::floor(lo_v) - 1.0, 0.0);
  const double x1 = std::min(std::ceil(hi_u) + 2.0, double(camera.width));
  const double y1 = std::min(std::ceil(hi_v) + 2.0, double(camera.height));
  if (x1 <= x0 || y1 <= y0) return {};
  return cv::Rect(int(x0), int(y0), int(x1 - x0), int(y1 - y0)) & image;
}

AmodalPatch cast_alone(const RenderScene& scene, int instance, const PinholeCamera& camera,
                       const CameraRayTable& rays) {
  AmodalPatch patch;
  const Instance& placed = scene.instance(instance);
  patch.area = projected_area(scene.mesh(placed.mesh), placed.pose, camera);
  patch.depth = cv::Mat::zeros(patch.area.size(), CV_32FC1);
  if (patch.area.empty()) return patch;
  const RTCScene solo = scene.embree_instance_scene(instance);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[16];
  const int x0 = patch.area.x, y0 = patch.area.y;
  const int x1 = patch.area.br().x, y1 = patch.area.br().y;
  // 4x4 packets, as the ray caster's; a ray's result does not depend on its lane.
  for (int by = y0; by < y1; by += 4) {
    for (int bx = x0; bx < x1; bx += 4) {
      for (int k = 0; k < 16; ++k) {
        const int x = bx + (k & 3), y = by + (k >> 2);
        const bool inside = x < x1 && y < y1;
        valid[k] = inside ? -1 : 0;
        set_primary_ray(packet, k, inside ? rays.dx[x] : 0.0f, inside ? rays.dy[y] : 0.0f);
      }
      rtcIntersect16(valid, solo, &context, &packet);
      for (int k = 0; k < 16; ++k) {
        if (valid[k] == 0 || packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
        patch.depth.at<float>(by + (k >> 2) - y0, bx + (k & 3) - x0) = packet.ray.tfar[k];
        ++patch.pixels;
      }
    }
  }
  return patch;
}

}  // namespace flexsight

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

#pragma once
// One instance's amodal depth: its rays cast through the one-instance Embree scene that
// RenderScene keeps for it (embree_instance_scene), within the projection of its
// bounding box only. The rays are the ray caster's (same directions, same packets of
// rtcIntersect16, same instance transform), so a pixel where raycast() sees the part
// has the same depth here, to the bit: the occlusion cap computed from these patches
// holds for the final image, and every visible pixel lies in the amodal mask.
#include <opencv2/core.hpp>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight {

// Ray direction of pixel (u, v): (dx[u], dy[v], 1), computed as the ray caster does.
struct CameraRayTable {
  explicit CameraRayTable(const PinholeCamera& camera);
  std::vector<float> dx, dy;
};

struct AmodalPatch {
  cv::Rect area;   // the pixels cast, within the image (empty when the part is out of view)
  cv::Mat depth;   // CV_32FC1 over `area`: z of the part alone in mm, 0 where it is missed
  int pixels = 0;  // pixels where the part is hit
};

// `scene` must be committed.
AmodalPatch cast_alone(const RenderScene& scene, int instance, const PinholeCamera& camera,
                       const CameraRayTable& rays);

}  // namespace flexsight

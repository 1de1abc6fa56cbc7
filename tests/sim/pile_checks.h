#pragma once
// Physical checks of a settled pile, independent of Bullet's shapes: whether parts lie
// inside one another, by ray parity against each part's own mesh with Embree.
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"
#include "host/sim/bin_physics.h"

namespace pile_checks {

using namespace flexsight;

// Whether model point `p` (in the mesh's own frame) is inside the closed mesh: the
// number of surfaces a ray along +z crosses is odd.
inline bool inside(RTCScene mesh_scene, const Eigen::Vector3f& p) {
  int crossings = 0;
  float tnear = 0.0f;
  for (int guard = 0; guard < 64; ++guard) {
    RTCRayHit hit;
    hit.ray.org_x = p.x();
    hit.ray.org_y = p.y();
    hit.ray.org_z = p.z();
    hit.ray.dir_x = 0.0123f;  // off-axis: no ray along a facet edge of an axis-aligned part
    hit.ray.dir_y = 0.0171f;
    hit.ray.dir_z = 1.0f;
    hit.ray.tnear = tnear;
    hit.ray.tfar = INFINITY;
    hit.ray.time = 0.0f;
    hit.ray.mask = 0xFFFFFFFF;
    hit.ray.id = 0;
    hit.ray.flags = 0;
    hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(mesh_scene, &context, &hit);
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    ++crossings;
    tnear = hit.ray.tfar + 1e-3f;
  }
  return crossings % 2 == 1;
}

// Of each part's vertices (about 150 a part), how many lie inside another part;
// `tested` gets how many were tested. A vertex touching a neighbour's surface may count
// either way, so a sound pile has almost none, not none.
inline int vertices_inside_other_parts(const std::vector<std::shared_ptr<const Mesh>>& meshes,
                                       const std::vector<RestingPart>& parts, int& tested) {
  RenderScene scene;
  for (const auto& mesh : meshes) scene.add_mesh(mesh);
  int inside_count = 0;
  tested = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const RestingPart& a = parts[i];
    for (std::size_t j = 0; j < parts.size(); ++j) {
      if (i == j) continue;
      const RestingPart& b = parts[j];
      const RTCScene b_scene = scene.embree_mesh_scene(b.part);
      const auto& positions = meshes[a.part]->positions;
      for (std::size_t k = 0; k < positions.size(); k += std::max<std::size_t>(1, positions.size() / 150)) {
        const Eigen::Vector3d w = a.world.R * positions[k].cast<double>() + a.world.t;
        const Eigen::Vector3d in_b = b.world.R.transpose() * (w - b.world.t);
        ++tested;
        // Quick reject by b's box.
        if (!meshes[b.part]->bounds.cast<double>().contains(in_b)) continue;
        if (inside(b_scene, in_b.cast<float>())) ++inside_count;
      }
    }
  }
  return inside_count;
}

}  // namespace pile_checks

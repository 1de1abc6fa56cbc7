// Parts dropped into the bin come to rest inside it: above the floor, within the walls,
// and not inside one another (checked with Embree, independently of Bullet's shapes).
#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <cmath>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"
#include "host/sim/bin_physics.h"

using namespace flexsight;

namespace {

std::vector<std::shared_ptr<const Mesh>> some_tless_parts() {
  std::vector<std::shared_ptr<const Mesh>> meshes;
  // Small and large, round and boxy.
  for (const char* name : {"obj_02.stl", "obj_05.stl", "obj_11.stl", "obj_19.stl", "obj_26.stl"}) {
    const std::string path = std::string(FLEXSIGHT_TLESS_CAD_DIR) + "/" + name;
    meshes.push_back(std::make_shared<const Mesh>(load_mesh(path)));
  }
  return meshes;
}

// Whether model point `p` (in the mesh's own frame) is inside the closed mesh: the
// number of surfaces a ray along +z crosses is odd.
bool inside(RTCScene mesh_scene, const Eigen::Vector3f& p) {
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

}  // namespace

TEST(BinPhysics, HullIsSmallAndAroundTheCentreOfMass) {
  const Mesh mesh = load_mesh(std::string(FLEXSIGHT_TLESS_CAD_DIR) + "/obj_05.stl");
  const PartHull hull = make_part_hull(mesh);
  EXPECT_GE(hull.points.size(), 8u);
  EXPECT_LE(hull.points.size(), 256u);
  EXPECT_GT(hull.volume_mm3, 0.0);
  EXPECT_LT(hull.volume_mm3, (mesh.bounds.max() - mesh.bounds.min()).cast<double>().prod());
  // The centre of mass is inside the part's box, and the hull reaches its far corner.
  EXPECT_TRUE(mesh.bounds.cast<double>().contains(hull.centre_of_mass));
  EXPECT_NEAR(2.0 * hull.radius_mm, mesh.diameter, 0.35 * mesh.diameter);
}

TEST(BinPhysics, PartsComeToRestInsideTheBinWithoutInterpenetrating) {
  const auto meshes = some_tless_parts();
  std::vector<PartHull> hulls;
  for (const auto& mesh : meshes) hulls.push_back(make_part_hull(*mesh));
  BinGeometry bin;
  bin.length_mm = 200.0;  // a small bin, so that the parts pile up
  bin.width_mm = 150.0;
  bin.wall_height_mm = 100.0;
  std::vector<int> order;
  for (int i = 0; i < 12; ++i) order.push_back(i % int(hulls.size()));
  const PhysicsResult result =
      drop_parts(hulls, order, bin, PhysicsSettings{}, synth_detail::SynthRandom(7, 0, 1));
  EXPECT_TRUE(result.at_rest) << result.steps << " steps";
  EXPECT_EQ(result.dropped, 12);
  ASSERT_GE(result.parts.size(), 10u) << result.removed << " removed";

  // Every vertex above the floor and within the walls (1.5 mm: Bullet's margins).
  RenderScene scene;
  for (const auto& mesh : meshes) scene.add_mesh(mesh);
  double highest = 0.0;
  for (const RestingPart& part : result.parts) {
    for (const Eigen::Vector3f& p : meshes[part.part]->positions) {
      const Eigen::Vector3d w = part.world.R * p.cast<double>() + part.world.t;
      ASSERT_GE(w.z(), -1.5);
      ASSERT_LE(std::abs(w.x()), 0.5 * bin.length_mm + 1.5);
      ASSERT_LE(std::abs(w.y()), 0.5 * bin.width_mm + 1.5);
      highest = std::max(highest, w.z());
    }
  }
  // A pile, not a single layer: 12 parts on 200 x 150 mm stack up.
  EXPECT_GT(highest, 35.0);

  // No part inside another: of each part's vertices, almost none lie inside any other
  // part (a vertex touching a neighbour's surface may count either way).
  int inside_count = 0, tested = 0;
  for (std::size_t i = 0; i < result.parts.size(); ++i) {
    const RestingPart& a = result.parts[i];
    for (std::size_t j = 0; j < result.parts.size(); ++j) {
      if (i == j) continue;
      const RestingPart& b = result.parts[j];
      const RTCScene b_scene = scene.embree_mesh_scene(b.part);
      const auto& positions = meshes[a.part]->positions;
      for (std::size_t k = 0; k < positions.size(); k += std::max<std::size_t>(1, positions.size() / 150)) {
        const Eigen::Vector3d w = a.world.R * positions[k].cast<double>() + a.world.t;
        const Eigen::Vector3d in_b = b.world.R.transpose() * (w - b.world.t);
        // Quick reject by b's box.
        if (!meshes[b.part]->bounds.cast<double>().contains(in_b)) {
          ++tested;
          continue;
        }
        ++tested;
        if (inside(b_scene, in_b.cast<float>())) ++inside_count;
      }
    }
  }
  EXPECT_LT(inside_count, std::max(3, tested / 500)) << inside_count << " of " << tested;
}

TEST(BinPhysics, SameSeedSamePoses) {
  const auto meshes = some_tless_parts();
  std::vector<PartHull> hulls;
  for (const auto& mesh : meshes) hulls.push_back(make_part_hull(*mesh));
  const std::vector<int> order{0, 1, 2, 3, 0};
  const PhysicsResult a = drop_parts(hulls, order, BinGeometry{}, PhysicsSettings{},
                                     synth_detail::SynthRandom(3, 1, 1));
  const PhysicsResult b = drop_parts(hulls, order, BinGeometry{}, PhysicsSettings{},
                                     synth_detail::SynthRandom(3, 1, 1));
  const PhysicsResult c = drop_parts(hulls, order, BinGeometry{}, PhysicsSettings{},
                                     synth_detail::SynthRandom(4, 1, 1));
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i) {
    EXPECT_EQ(a.parts[i].world.t, b.parts[i].world.t);
    EXPECT_EQ(a.parts[i].world.R, b.parts[i].world.R);
  }
  EXPECT_NE(a.parts[0].world.t, c.parts[0].world.t);
}

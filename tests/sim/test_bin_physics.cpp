// Parts dropped into the bin come to rest inside it: above the floor, within the walls,
// and not inside one another (checked with Embree, independently of Bullet's shapes).
#include <gtest/gtest.h>

#include <cmath>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"
#include "host/sim/bin_physics.h"
#include "tests/sim/pile_checks.h"

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

  // No part inside another (pile_checks.h).
  int tested = 0;
  const int inside_count = pile_checks::vertices_inside_other_parts(meshes, result.parts, tested);
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

#pragma once
// Parts dropped into a bin with rigid-body physics (Bullet): piles a real bin could hold,
// parts resting on the floor, on the walls and on each other, never floating or inside
// one another, which random placement cannot give.
//
// Each part collides as the convex hull of its mesh: the T-LESS parts are mostly convex
// (boxes, cylinders, plugs), a hull keeps the contact solver fast and stable (a concave
// triangle mesh is not supported for moving bodies, and a convex decomposition would
// cost a library and seconds per part for little change in how parts lie), and it can
// only leave a gap where the part has a hollow, never an overlap. The hull's vertices are
// thinned to at most 256 (farthest-point order): a cylinder's hull keeps hundreds of
// rim vertices that change its shape by less than a millimetre but the cost of every
// contact query in proportion.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"
#include "host/synth/synth_random.h"

namespace flexsight {

// The bin, in mm: inner floor length (x) and width (y), wall height above the floor, wall
// and floor thickness. Its frame: origin at the middle of the floor's top face, z up.
struct BinGeometry {
  double length_mm = 500.0, width_mm = 340.0;
  double wall_height_mm = 120.0;
  double wall_thickness_mm = 10.0, floor_thickness_mm = 10.0;
};

struct PhysicsSettings {
  // Fixed step (s) and solver iterations: the same steps on every run, so the same seed
  // gives the same piles. 1/360 s keeps a part falling at 2.5 m/s to 7 mm per step,
  // below the thinnest part's thickness.
  double time_step_s = 1.0 / 360.0;
  int solver_iterations = 20;
  // Simulated time after each drop before the next part falls (s): enough for it to land,
  // not to come to rest, so the pile settles while it grows.
  double drop_interval_s = 0.3;
  // Dense piles fall in waves: after every wave_size parts the pile settles (at most
  // wave_settle_s of simulated time) before the next wave, so that the next parts land
  // on a pile at rest rather than on parts still sliding (0: one wave, the sparse pile).
  int wave_size = 0;
  double wave_settle_s = 1.5;
  // A wave's parts fall around one point of the bin (Gaussian, this sigma in mm), as
  // parts tipped from a box or a conveyor heap up; 0: anywhere over the bin.
  double heap_sigma_mm = 0.0;
  // At rest: every part slower than these for rest_steps steps in a row; or max_settle_s
  // of simulated time after the last drop.
  double rest_linear_mm_s = 5.0, rest_angular_rad_s = 0.05;
  int rest_steps = 30;
  double max_settle_s = 8.0;
  // Moulded plastic on plastic and on the bin; rolling friction as Bullet has it, a lever
  // arm (mm), so that round parts stop rolling.
  double friction = 0.5, restitution = 0.1;
  double rolling_friction_mm = 1.0;
  double density_kg_mm3 = 1.2e-6;
};

// A part's collision shape: hull vertices (mm) relative to its centre of mass, in the
// model's axes, and what the body needs.
struct PartHull {
  std::vector<Eigen::Vector3f> points;
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();  // model frame, mm
  double volume_mm3 = 0.0;  // of the mesh (closed) or its box (otherwise)
  double radius_mm = 0.0;   // largest distance of a hull point from the centre of mass
  // Bullet's margin around the thinned hull: a quarter millimetre plus how far the
  // vertices thinning dropped stick out of the thinned hull, so the shape holds the part.
  double margin_mm = 0.0;
};

PartHull make_part_hull(const Mesh& mesh);

struct RestingPart {
  int part = 0;     // index into the hulls given to drop_parts
  Pose world;       // model -> bin frame, mm
};

struct PhysicsResult {
  std::vector<RestingPart> parts;  // those at rest inside the bin, in drop order
  int dropped = 0;
  // Parts that ended outside the bin (centre of mass outside the walls, or hanging over
  // a wall's top): taken out, and the rest settled again.
  int removed = 0;
  int steps = 0;
  bool at_rest = false;  // false: the last settling stopped at max_settle_s
};

// Drops parts `order[0]`, `order[1]`, ... (indices into `hulls`) one after another, each
// from a random orientation and a random point above the bin (drawn from `random`),
// simulates until all are at rest, and returns the parts inside the bin. Single-threaded
// and deterministic.
PhysicsResult drop_parts(const std::vector<PartHull>& hulls, const std::vector<int>& order,
                         const BinGeometry& bin, const PhysicsSettings& settings,
                         synth_detail::SynthRandom random);

}  // namespace flexsight

#include "host/sim/bin_physics.h"

#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

namespace flexsight {
namespace {

// Bullet's own tolerances (contact breaking distance, sleeping and split-impulse
// thresholds) are tuned for bodies of about 0.05 to 10 units. In metres the T-LESS parts
// (20 to 100 mm) sit at the bottom of that range and piles of them never came to rest
// (parts shivering at 0.3 m/s after 8 s); in centimetres, 2 to 10 units, they settle
// within a second. So Bullet's unit here is the centimetre (gravity 981 units/s^2).
constexpr double kMetresPerMm = 0.1;  // Bullet units per mm (the name: its usual metre)
constexpr int kMaxHullPoints = 256;
// Bullet's collision margin around each hull (mm): contacts are found this far out, which
// keeps resting contacts stable; a quarter millimetre is below what the images resolve.
// The thinned hull's own error is added (make_part_hull).
constexpr double kHullMarginMm = 0.25;
// The static boxes are thicker than the bin's walls and floor (mm), outward only, so a
// fast part cannot pass through them within one step; nothing outside the bin shows it.
constexpr double kStaticReserveMm = 60.0;

btVector3 to_bt(const Eigen::Vector3d& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }

// Farthest-point order from the point farthest from the centre: the first k points are
// spread over the whole hull.
std::vector<Eigen::Vector3f> thin_points(const std::vector<Eigen::Vector3f>& points, int keep) {
  if (static_cast<int>(points.size()) <= keep) return points;
  std::vector<float> distance(points.size(), INFINITY);
  std::vector<Eigen::Vector3f> kept;
  std::size_t next = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (points[i].squaredNorm() > points[next].squaredNorm()) next = i;
  }
  while (static_cast<int>(kept.size()) < keep) {
    kept.push_back(points[next]);
    std::size_t best = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      distance[i] = std::min(distance[i], (points[i] - kept.back()).squaredNorm());
      if (distance[i] > distance[best]) best = i;
    }
    next = best;
  }
  return kept;
}

Eigen::Quaterniond random_rotation(synth_detail::SynthRandom& random) {
  // Shoemake's uniform quaternion.
  const double u1 = random.uniform(), u2 = random.uniform(), u3 = random.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(2 * M_PI * u3), a * std::sin(2 * M_PI * u2),
                            a * std::cos(2 * M_PI * u2), b * std::sin(2 * M_PI * u3));
}

// The Bullet world of one bin: the floor and walls as static bodies, then the dropped
// parts' bodies in drop order (body first_part_body_ + drop index).
class BinWorld {
 public:
  BinWorld(const std::vector<PartHull>& hulls, const BinGeometry& bin, const PhysicsSettings& settings)
      : hulls_(hulls),
        bin_(bin),
        settings_(settings),
        dispatcher_(&configuration_),
        world_(&dispatcher_, &broadphase_, &solver_, &configuration_),
        part_shapes_(hulls.size(), nullptr) {
    world_.setGravity(btVector3(0, 0, btScalar(-9810.0 * kMetresPerMm)));
    world_.getSolverInfo().m_numIterations = settings.solver_iterations;
    add_bin();
    first_part_body_ = bodies_.size();
  }

  // Drops `part` above the walls and the pile, clear of both by a margin, at a random
  // point and orientation.
  void drop(int part, synth_detail::SynthRandom& random, const Eigen::Vector2d& heap = Eigen::Vector2d::Zero()) {
    const PartHull& hull = hulls_[part];
    const double L = bin_.length_mm, W = bin_.width_mm;
    double top = bin_.wall_height_mm;
    for (std::size_t b = first_part_body_; b < bodies_.size(); ++b) {
      btVector3 lo, hi;
      bodies_[b]->getAabb(lo, hi);
      top = std::max(top, double(hi.z()) / kMetresPerMm);
    }
    const double rx = std::max(0.0, 0.5 * L - hull.radius_mm);
    const double ry = std::max(0.0, 0.5 * W - hull.radius_mm);
    Eigen::Vector3d position;
    if (settings_.heap_sigma_mm > 0.0) {
      // Box-Muller around the heap's point, kept over the bin.
      const double r = settings_.heap_sigma_mm * std::sqrt(-2.0 * std::log(1.0 - random.uniform()));
      const double phi = 2.0 * M_PI * random.uniform();
      position = {std::clamp(heap.x() + r * std::cos(phi), -rx, rx),
                  std::clamp(heap.y() + r * std::sin(phi), -ry, ry), top + hull.radius_mm + 20.0};
    } else {
      // The constructor's arguments, as the sparse piles have always been drawn (their
      // order of evaluation is the compiler's; braces would fix it and change the piles).
      position = Eigen::Vector3d(random.uniform(-rx, rx), random.uniform(-ry, ry), top + hull.radius_mm + 20.0);
    }
    const Eigen::Quaterniond rotation = random_rotation(random);
    btTransform transform;
    transform.setOrigin(to_bt(kMetresPerMm * position));
    transform.setRotation(btQuaternion(btScalar(rotation.x()), btScalar(rotation.y()),
                                       btScalar(rotation.z()), btScalar(rotation.w())));
    const double mass = settings_.density_kg_mm3 * hull.volume_mm3;
    btRigidBody* body = add_body(shape_of(part), mass, transform);
    // Continuous collision for fast, thin parts: a swept sphere inside the part.
    body->setCcdMotionThreshold(btScalar(0.25 * hull.radius_mm * kMetresPerMm));
    body->setCcdSweptSphereRadius(btScalar(0.2 * hull.radius_mm * kMetresPerMm));
  }

  void step() {
    // One fixed step, no sub-stepping left to Bullet's clock.
    world_.stepSimulation(btScalar(settings_.time_step_s), 0);
    ++steps_;
  }

  // Steps until every part is at rest or `max_steps` have passed; true: at rest.
  bool settle(int max_steps) {
    int calm_steps = 0;
    bool at_rest = false;
    for (int s = 0; s < max_steps && !at_rest; ++s) {
      step();
      at_rest = rest_check(calm_steps);
    }
    return at_rest;
  }

  // The pose of the part dropped `i`-th, `part` its index into the hulls.
  Pose pose_of(std::size_t i, int part) const {
    const btTransform& transform = bodies_[first_part_body_ + i]->getWorldTransform();
    const btQuaternion q = transform.getRotation();
    const btVector3 origin = transform.getOrigin();
    Pose pose;
    pose.R = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
    // The body's origin is the centre of mass: model point x sits at R (x - com) + centre.
    pose.t = Eigen::Vector3d(origin.x(), origin.y(), origin.z()) / kMetresPerMm -
             pose.R * hulls_[part].centre_of_mass;
    return pose;
  }

  // Out of the bin: the centre of mass outside the walls or below the floor, or the part
  // hanging over a wall's top by more than half the wall.
  bool left_bin(std::size_t i, int part) const {
    const double L = bin_.length_mm, W = bin_.width_mm;
    const Pose pose = pose_of(i, part);
    const PartHull& hull = hulls_[part];
    const Eigen::Vector3d centre = pose.R * hull.centre_of_mass + pose.t;
    if (std::abs(centre.x()) > 0.5 * L || std::abs(centre.y()) > 0.5 * W || centre.z() < 0.0) return true;
    const double reach = 0.5 * bin_.wall_thickness_mm;
    for (const Eigen::Vector3f& p : hull.points) {
      const Eigen::Vector3d w = centre + pose.R * p.cast<double>();
      if (std::abs(w.x()) > 0.5 * L + reach || std::abs(w.y()) > 0.5 * W + reach) return true;
    }
    return false;
  }

  void remove_part(std::size_t i) { world_.removeRigidBody(bodies_[first_part_body_ + i].get()); }

  // Takes the bin's bodies and the parts `in_world` (by drop index) out of the world.
  void remove_all(const std::vector<bool>& in_world) {
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      if (b < first_part_body_ || in_world[b - first_part_body_]) world_.removeRigidBody(bodies_[b].get());
    }
  }

  int steps() const { return steps_; }

 private:
  btRigidBody* add_body(btCollisionShape* shape, double mass, const btTransform& transform) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shape, inertia);
    info.m_startWorldTransform = transform;
    info.m_friction = btScalar(settings_.friction);
    info.m_restitution = btScalar(settings_.restitution);
    info.m_linearDamping = 0.05f;
    info.m_angularDamping = 0.1f;
    // Bullet's rolling friction is a lever arm (a length): without it a cylinder rolls on
    // for ever.
    info.m_rollingFriction = btScalar(settings_.rolling_friction_mm * kMetresPerMm);
    info.m_spinningFriction = btScalar(settings_.rolling_friction_mm * kMetresPerMm);
    bodies_.push_back(std::make_unique<btRigidBody>(info));
    world_.addRigidBody(bodies_.back().get());
    return bodies_.back().get();
  }

  void add_box(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& size_mm) {
    shapes_.push_back(std::make_unique<btBoxShape>(to_bt(0.5 * kMetresPerMm * size_mm)));
    btTransform transform;
    transform.setIdentity();
    transform.setOrigin(to_bt(kMetresPerMm * centre_mm));
    add_body(shapes_.back().get(), 0.0, transform);
  }

  // The bin: floor and four walls as static boxes (inner faces where the bin's are).
  void add_bin() {
    const double L = bin_.length_mm, W = bin_.width_mm, H = bin_.wall_height_mm;
    const double T = bin_.wall_thickness_mm + kStaticReserveMm;
    const double F = bin_.floor_thickness_mm + kStaticReserveMm;
    add_box({0, 0, -0.5 * F}, {L + 2 * T, W + 2 * T, F});
    add_box({0.5 * (L + T), 0, 0.5 * H}, {T, W + 2 * T, H});
    add_box({-0.5 * (L + T), 0, 0.5 * H}, {T, W + 2 * T, H});
    add_box({0, 0.5 * (W + T), 0.5 * H}, {L, T, H});
    add_box({0, -0.5 * (W + T), 0.5 * H}, {L, T, H});
  }

  // One shape per part model, shared by its copies.
  btConvexHullShape* shape_of(int part) {
    if (part_shapes_[part] == nullptr) {
      auto shape = std::make_unique<btConvexHullShape>();
      for (const Eigen::Vector3f& p : hulls_[part].points) {
        shape->addPoint(to_bt(kMetresPerMm * p.cast<double>()), false);
      }
      shape->recalcLocalAabb();
      shape->setMargin(btScalar(hulls_[part].margin_mm * kMetresPerMm));
      part_shapes_[part] = shape.get();
      shapes_.push_back(std::move(shape));
    }
    return part_shapes_[part];
  }

  // Counts the steps in a row with every part slower than the rest thresholds.
  bool rest_check(int& calm_steps) const {
    bool calm = true;
    for (std::size_t b = first_part_body_; b < bodies_.size() && calm; ++b) {
      if (!bodies_[b]->isInWorld()) continue;
      calm = bodies_[b]->getLinearVelocity().length() < settings_.rest_linear_mm_s * kMetresPerMm &&
             bodies_[b]->getAngularVelocity().length() < settings_.rest_angular_rad_s;
    }
    calm_steps = calm ? calm_steps + 1 : 0;
    return calm_steps >= settings_.rest_steps;
  }

  const std::vector<PartHull>& hulls_;
  const BinGeometry& bin_;
  const PhysicsSettings& settings_;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<btConvexHullShape*> part_shapes_;
  std::size_t first_part_body_ = 0;
  int steps_ = 0;
};

}  // namespace

PartHull make_part_hull(const Mesh& mesh) {
  PartHull hull;
  // Volume and centre of mass of the closed mesh: signed tetrahedra from the origin.
  double volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions[t[2]].cast<double>();
    const double v = a.dot(b.cross(c)) / 6.0;
    volume += v;
    moment += v * (a + b + c) / 4.0;
  }
  const Eigen::Vector3d box = (mesh.bounds.max() - mesh.bounds.min()).cast<double>();
  if (volume > 1e-3 * box.prod()) {
    hull.volume_mm3 = volume;
    hull.centre_of_mass = moment / volume;
  } else {  // open or inside-out mesh: its box stands in
    hull.volume_mm3 = box.prod();
    hull.centre_of_mass = mesh.bounds.center().cast<double>();
  }

  std::vector<float> coords;
  for (const Eigen::Vector3f& p : mesh.positions) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  btConvexHullComputer computer;
  computer.compute(coords.data(), 3 * sizeof(float), static_cast<int>(mesh.positions.size()), 0, 0);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < computer.vertices.size(); ++i) {
    const btVector3& v = computer.vertices[i];
    points.push_back(Eigen::Vector3f(float(v.x()), float(v.y()), float(v.z())) -
                     hull.centre_of_mass.cast<float>());
  }
  hull.points = thin_points(points, kMaxHullPoints);
  for (const Eigen::Vector3f& p : hull.points) hull.radius_mm = std::max(hull.radius_mm, double(p.norm()));
  // How far the dropped hull vertices stick out of the thinned hull: the margin covers
  // it, so the collision shape still holds the whole part and parts never overlap.
  double outside = 0.0;
  if (hull.points.size() < points.size()) {
    std::vector<float> kept;
    for (const Eigen::Vector3f& p : hull.points) kept.insert(kept.end(), {p.x(), p.y(), p.z()});
    btConvexHullComputer thin;
    thin.compute(kept.data(), 3 * sizeof(float), static_cast<int>(hull.points.size()), 0, 0);
    std::vector<std::pair<Eigen::Vector3d, double>> planes;  // outward normal, offset
    for (int f = 0; f < thin.faces.size(); ++f) {
      const btConvexHullComputer::Edge* edge = &thin.edges[thin.faces[f]];
      const auto vertex = [&](int i) {
        const btVector3& v = thin.vertices[i];
        return Eigen::Vector3d(v.x(), v.y(), v.z());
      };
      const Eigen::Vector3d a = vertex(edge->getSourceVertex());
      const Eigen::Vector3d b = vertex(edge->getTargetVertex());
      const Eigen::Vector3d c = vertex(edge->getNextEdgeOfFace()->getTargetVertex());
      Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() < 1e-12) continue;
      n.normalize();
      planes.emplace_back(n, n.dot(a));
    }
    for (const Eigen::Vector3f& p : points) {
      double distance = -INFINITY;
      for (const auto& [n, d] : planes) distance = std::max(distance, n.dot(p.cast<double>()) - d);
      outside = std::max(outside, distance);
    }
  }
  hull.margin_mm = kHullMarginMm + outside;
  return hull;
}

PhysicsResult drop_parts(const std::vector<PartHull>& hulls, const std::vector<int>& order,
                         const BinGeometry& bin, const PhysicsSettings& settings,
                         synth_detail::SynthRandom random) {
  // A fresh world per bin: no state (solver seed, caches, pair order) carries over.
  BinWorld world(hulls, bin, settings);
  PhysicsResult result;
  const int drop_steps = std::max(1, int(std::lround(settings.drop_interval_s / settings.time_step_s)));
  const int wave_steps = int(std::lround(settings.wave_settle_s / settings.time_step_s));
  Eigen::Vector2d heap = Eigen::Vector2d::Zero();
  for (int part : order) {
    const bool wave_starts = settings.wave_size > 0 && result.dropped % settings.wave_size == 0;
    if (wave_starts && settings.heap_sigma_mm > 0.0) {
      heap = {random.uniform(-0.3, 0.3) * bin.length_mm, random.uniform(-0.3, 0.3) * bin.width_mm};
    }
    world.drop(part, random, heap);
    ++result.dropped;
    for (int s = 0; s < drop_steps; ++s) world.step();
    const bool wave_done = settings.wave_size > 0 && result.dropped % settings.wave_size == 0;
    if (wave_done && result.dropped < int(order.size())) world.settle(wave_steps);
  }
  // The parts still in the world, by drop index (a removed part's body is taken out).
  std::vector<bool> in_world(order.size(), true);
  // Settle; take out the parts that left the bin; settle again what leaned on them.
  const int max_steps = int(std::lround(settings.max_settle_s / settings.time_step_s));
  for (int round = 0; round < 3; ++round) {
    result.at_rest = world.settle(max_steps);
    bool removed = false;
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (!in_world[i] || !world.left_bin(i, order[i])) continue;
      world.remove_part(i);
      in_world[i] = false;
      ++result.removed;
      removed = true;
    }
    if (!removed) break;
  }

  for (std::size_t i = 0; i < order.size(); ++i) {
    if (in_world[i]) result.parts.push_back({order[i], world.pose_of(i, order[i])});
  }
  result.steps = world.steps();
  world.remove_all(in_world);
  return result;
}

}  // namespace flexsight

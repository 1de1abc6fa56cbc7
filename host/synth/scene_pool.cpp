#include "host/synth/scene_pool.h"

#include <chrono>
#include <stdexcept>
#include <string>

namespace flexsight {
namespace {

// 1 km behind the camera: see scene_pool.h.
Pose parked_pose() {
  Pose pose;
  pose.t = {0.0, 0.0, -1e6};
  return pose;
}

}  // namespace

PooledScene::PooledScene(const std::vector<std::shared_ptr<const Mesh>>* meshes)
    : meshes_(meshes), mesh_of_part_(meshes->size(), -1), instances_of_part_(meshes->size()) {}

int PooledScene::place(int part, const Pose& pose, const Material& material) {
  if (part < 0 || part >= static_cast<int>(meshes_->size())) {
    throw std::out_of_range("PooledScene::place: no part " + std::to_string(part));
  }
  for (int instance : instances_of_part_[part]) {
    if (in_use_[instance]) continue;
    in_use_[instance] = true;
    scene_.set_pose(instance, pose);
    scene_.set_material(instance, material);
    return instance;
  }
  if (mesh_of_part_[part] < 0) {
    const auto start = std::chrono::steady_clock::now();
    mesh_of_part_[part] = scene_.add_mesh((*meshes_)[part]);
    setup_ms_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  const int instance = scene_.add_instance(mesh_of_part_[part], pose, material);
  instance_part_.push_back(part);
  in_use_.push_back(true);
  instances_of_part_[part].push_back(instance);
  return instance;
}

void PooledScene::park(int instance) {
  if (!in_use_.at(instance)) return;
  scene_.set_pose(instance, parked_pose());
  in_use_[instance] = false;
}

void PooledScene::park_all() {
  for (int instance = 0; instance < static_cast<int>(in_use_.size()); ++instance) park(instance);
}

double PooledScene::take_setup_ms() {
  const double ms = setup_ms_;
  setup_ms_ = 0.0;
  return ms;
}

ScenePool::ScenePool(std::vector<std::shared_ptr<const Mesh>> meshes)
    : meshes_(std::move(meshes)) {}

ScenePool::Lease::Lease(const ScenePool* pool, std::unique_ptr<PooledScene> scene)
    : pool_(pool), scene_(std::move(scene)) {}

ScenePool::Lease::~Lease() {
  if (scene_ == nullptr) return;
  // Never throws: a scene that cannot go back (no memory for the list) is dropped.
  try {
    const std::lock_guard<std::mutex> lock(pool_->mutex_);
    pool_->idle_.push_back(std::move(scene_));
  } catch (...) {
  }
}

ScenePool::Lease ScenePool::acquire() const {
  std::unique_ptr<PooledScene> scene;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!idle_.empty()) {
      scene = std::move(idle_.back());
      idle_.pop_back();
    }
  }
  if (scene == nullptr) scene = std::make_unique<PooledScene>(&meshes_);
  scene->park_all();
  return Lease(this, std::move(scene));
}

}  // namespace flexsight

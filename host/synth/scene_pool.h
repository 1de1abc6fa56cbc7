#pragma once
// Render scenes of a part library, kept from one image to the next. RenderScene builds
// a mesh's Embree hierarchy when the mesh is added (high quality, 1-40 ms per T-LESS
// part, 137 ms for all 23): per image that would cost more than the image itself. A
// pooled scene adds each mesh once, on its first use, and keeps its instances: an
// image takes the instances it needs and parks the others out of sight.
//
// Parked means posed 1e6 mm behind the camera. Camera rays (z > 0 all along) never reach
// it, nor do shadow rays, whose segments end at lights within metres of the parts. So a
// parked instance changes no pixel, and an image's bytes do not depend on which pooled
// scene rendered it or what that scene rendered before (tested).
#include <memory>
#include <mutex>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight {

class PooledScene {
 public:
  explicit PooledScene(const std::vector<std::shared_ptr<const Mesh>>* meshes);

  RenderScene& scene() { return scene_; }
  const RenderScene& scene() const { return scene_; }
  // An instance of part `part` at `pose`: a parked instance of that part if there is
  // one, a new one otherwise (adding the part's mesh on its first use). Needs commit().
  int place(int part, const Pose& pose, const Material& material);
  // Parks `instance`, freeing it for a later place(). Needs commit().
  void park(int instance);
  // Parks every instance in use (an image's first step).
  void park_all();
  // The library part that `instance` shows.
  int part_of(int instance) const { return instance_part_[instance]; }
  // Milliseconds spent building hierarchies of meshes added since the last call.
  double take_setup_ms();

 private:
  const std::vector<std::shared_ptr<const Mesh>>* meshes_;
  RenderScene scene_;
  std::vector<int> mesh_of_part_;   // RenderScene mesh index per part, -1 until used
  std::vector<int> instance_part_;  // per instance
  std::vector<bool> in_use_;        // per instance
  std::vector<std::vector<int>> instances_of_part_;
  double setup_ms_ = 0.0;
};

// Thread-safe: each thread rendering an image holds one scene; the pool grows to the
// number of images rendered at once.
class ScenePool {
 public:
  explicit ScenePool(std::vector<std::shared_ptr<const Mesh>> meshes);

  // A scene with every instance parked, returned to the pool when the lease ends.
  class Lease {
   public:
    Lease(const ScenePool* pool, std::unique_ptr<PooledScene> scene);
    ~Lease();
    Lease(Lease&&) noexcept = default;
    Lease& operator=(Lease&&) = delete;
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    PooledScene& operator*() const { return *scene_; }
    PooledScene* operator->() const { return scene_.get(); }

   private:
    const ScenePool* pool_;
    std::unique_ptr<PooledScene> scene_;
  };
  Lease acquire() const;

 private:
  std::vector<std::shared_ptr<const Mesh>> meshes_;
  mutable std::mutex mutex_;
  mutable std::vector<std::unique_ptr<PooledScene>> idle_;
};

}  // namespace flexsight

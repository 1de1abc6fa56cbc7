#include "host/render/raycaster.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "host/io/input_error.h"
#include "host/render/embree_device.h"
#include "host/render/primary_rays.h"
#include "host/render/tiles.h"

namespace flexsight {

using render_detail::check_embree;
using render_detail::embree_device;

// ---------------------------------------------------------------- scene

struct RenderScene::Impl {
  std::vector<std::shared_ptr<const Mesh>> meshes;
  std::vector<RTCScene> mesh_scenes;
  std::vector<Instance> instances;
  std::vector<RTCGeometry> instance_geometries;  // Embree geometry id = instance id
  RTCScene top = nullptr;
  // Each instance alone in a scene of its own, with the same transform, for the amodal
  // masks: the ray meets the part through the same float arithmetic as in `top`, so a
  // pixel where the part is visible is always in its amodal mask.
  std::vector<RTCScene> solo_scenes;
  std::vector<RTCGeometry> solo_geometries;
  bool dirty = true;

  Impl() {
    top = rtcNewScene(embree_device());
    check_embree("creating the scene");
    // Robust traversal: rays through a shared edge or vertex of two triangles hit one of
    // them, never slip between (a plane of two triangles has no diagonal crack).
    rtcSetSceneFlags(top, RTC_SCENE_FLAG_ROBUST);
  }
  ~Impl() {
    for (RTCGeometry g : instance_geometries) rtcReleaseGeometry(g);
    for (RTCGeometry g : solo_geometries) rtcReleaseGeometry(g);
    for (RTCScene s : solo_scenes) rtcReleaseScene(s);
    if (top != nullptr) rtcReleaseScene(top);
    for (RTCScene s : mesh_scenes) rtcReleaseScene(s);
  }

  void set_transform(int id) {
    const Pose& pose = instances[id].pose;
    // Column-major 3x4: the three columns of R, then t.
    float m[12];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) m[3 * c + r] = static_cast<float>(pose.R(r, c));
    for (int r = 0; r < 3; ++r) m[9 + r] = static_cast<float>(pose.t[r]);
    for (RTCGeometry g : {instance_geometries[id], solo_geometries[id]}) {
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, m);
      rtcCommitGeometry(g);
    }
    check_embree("setting an instance's pose");
    dirty = true;
  }
};

RenderScene::RenderScene() : impl_(std::make_unique<Impl>()) {}
RenderScene::~RenderScene() = default;
RenderScene::RenderScene(RenderScene&&) noexcept = default;
RenderScene& RenderScene::operator=(RenderScene&&) noexcept = default;

int RenderScene::add_mesh(std::shared_ptr<const Mesh> mesh) {
  if (mesh == nullptr || mesh->triangles.empty()) {
    throw std::invalid_argument("RenderScene::add_mesh: a mesh with triangles is needed");
  }
  const RTCDevice device = embree_device();
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  // A part's hierarchy is built once and traced for every image: the slower, better
  // build pays for itself.
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               mesh->positions.size()));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh->triangles.size()));
  if (vertices == nullptr || indices == nullptr) {
    rtcReleaseGeometry(geometry);
    rtcReleaseScene(scene);
    check_embree("allocating a mesh's buffers");
    throw std::runtime_error("Embree: allocating a mesh's buffers failed");
  }
  for (size_t i = 0; i < mesh->positions.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = mesh->positions[i][k];
  for (size_t t = 0; t < mesh->triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = mesh->triangles[t][k];
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  try {
    check_embree(("building the hierarchy of " + mesh->source).c_str());
  } catch (...) {
    rtcReleaseScene(scene);
    throw;
  }
  impl_->meshes.push_back(std::move(mesh));
  impl_->mesh_scenes.push_back(scene);
  return static_cast<int>(impl_->meshes.size()) - 1;
}

int RenderScene::add_instance(int mesh, const Pose& pose, const Material& material) {
  if (mesh < 0 || mesh >= mesh_count()) {
    throw std::out_of_range("RenderScene::add_instance: no mesh " + std::to_string(mesh));
  }
  const int id = instance_count();
  const RTCDevice device = embree_device();
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(geometry, impl_->mesh_scenes[mesh]);
  rtcAttachGeometryByID(impl_->top, geometry, static_cast<unsigned>(id));
  RTCScene solo = rtcNewScene(device);
  rtcSetSceneFlags(solo, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry solo_geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(solo_geometry, impl_->mesh_scenes[mesh]);
  rtcAttachGeometryByID(solo, solo_geometry, static_cast<unsigned>(id));
  impl_->instances.push_back({mesh, pose, material});
  impl_->instance_geometries.push_back(geometry);
  impl_->solo_scenes.push_back(solo);
  impl_->solo_geometries.push_back(solo_geometry);
  check_embree("adding an instance");
  impl_->set_transform(id);
  return id;
}

void RenderScene::set_pose(int instance, const Pose& pose) {
  if (instance < 0 || instance >= instance_count()) {
    throw std::out_of_range("RenderScene::set_pose: no instance " + std::to_string(instance));
  }
  impl_->instances[instance].pose = pose;
  impl_->set_transform(instance);
}

void RenderScene::set_material(int instance, const Material& material) {
  if (instance < 0 || instance >= instance_count()) {
    throw std::out_of_range("RenderScene::set_material: no instance " + std::to_string(instance));
  }
  impl_->instances[instance].material = material;
}

void RenderScene::commit() {
  rtcCommitScene(impl_->top);
  for (RTCScene solo : impl_->solo_scenes) rtcCommitScene(solo);
  check_embree("building the scene's hierarchy");
  impl_->dirty = false;
}

bool RenderScene::committed() const { return !impl_->dirty; }
int RenderScene::mesh_count() const { return static_cast<int>(impl_->meshes.size()); }
int RenderScene::instance_count() const { return static_cast<int>(impl_->instances.size()); }
const Mesh& RenderScene::mesh(int index) const { return *impl_->meshes.at(index); }
const Instance& RenderScene::instance(int id) const { return impl_->instances.at(id); }
RTCScene RenderScene::embree_scene() const { return impl_->top; }
RTCScene RenderScene::embree_mesh_scene(int mesh) const { return impl_->mesh_scenes.at(mesh); }
RTCScene RenderScene::embree_instance_scene(int instance) const {
  return impl_->solo_scenes.at(instance);
}

// ---------------------------------------------------------------- casting

namespace {

// Ray direction of pixel (u, v): (dx[u], dy[v], 1), so that the hit parameter t is the
// depth z itself.
struct CameraRays {
  explicit CameraRays(const PinholeCamera& camera) {
    camera.check();
    dx.resize(camera.width);
    dy.resize(camera.height);
    for (int u = 0; u < camera.width; ++u) dx[u] = static_cast<float>((u - camera.cx) / camera.fx);
    for (int v = 0; v < camera.height; ++v) dy[v] = static_cast<float>((v - camera.cy) / camera.fy);
  }
  std::vector<float> dx, dy;
};

void require_committed(const RenderScene& scene) {
  if (!scene.committed()) {
    throw std::logic_error("ray casting needs RenderScene::commit() after the last change");
  }
}

// Per instance, what a hit needs: its mesh and its rotation in float.
struct SceneView {
  struct Entry {
    const Mesh* mesh;
    Eigen::Matrix3f R;
  };
  explicit SceneView(const RenderScene& scene) {
    require_committed(scene);
    instances.reserve(scene.instance_count());
    for (int i = 0; i < scene.instance_count(); ++i) {
      const Instance& instance = scene.instance(i);
      instances.push_back({&scene.mesh(instance.mesh), instance.pose.R.cast<float>()});
    }
  }
  std::vector<Entry> instances;
};

cv::Mat zeros_like_image(const PinholeCamera& camera, int type) {
  return cv::Mat::zeros(camera.height, camera.width, type);
}

// Fills pixel (x, y) of the images from a hit of instance `id` on its triangle `prim`
// at barycentric (u, v) and parameter t along the camera ray `direction` (z = 1).
void write_hit(const SceneView& view, RaycastImages& images, int x, int y, unsigned id,
               unsigned prim, float u, float v, float t, const Eigen::Vector3f& direction) {
  const SceneView::Entry& entry = view.instances[id];
  const Mesh& mesh = *entry.mesh;
  const Eigen::Vector3f* corner = &mesh.corner_normals[3 * size_t(prim)];
  Eigen::Vector3f shading = entry.R * ((1.0f - u - v) * corner[0] + u * corner[1] + v * corner[2]);
  Eigen::Vector3f geometric = entry.R * mesh.face_normals[prim];
  const float shading_length = shading.norm();
  shading = shading_length > 0.0f ? Eigen::Vector3f(shading / shading_length) : geometric;
  if (geometric.dot(direction) > 0.0f) {  // the back of the triangle: two-sided surfaces
    geometric = -geometric;
    shading = -shading;
  }
  const Eigen::Vector3f point = t * direction;
  images.depth.at<float>(y, x) = point.z();
  images.instance.at<std::int32_t>(y, x) = static_cast<std::int32_t>(id);
  images.normal.at<cv::Vec3f>(y, x) = {shading.x(), shading.y(), shading.z()};
  images.geometric_normal.at<cv::Vec3f>(y, x) = {geometric.x(), geometric.y(), geometric.z()};
  images.point.at<cv::Vec3f>(y, x) = {point.x(), point.y(), point.z()};
}

// Every pixel of a tile.
struct WholeTile {
  bool operator()(int, int) const { return true; }
};

// Casts the camera rays of pixels [x0, x1) x [y0, y1) through `scene` as 4x4 packets
// (rtcIntersect16: on coherent primary rays about three times the rays per second of
// rtcIntersect1, bench/render) and calls on_hit(x, y, instance, triangle, u, v, t) for
// each pixel that meets a surface and for which wanted(x, y) holds. A pixel's packet
// and lane depend on where it lies in its tile, never on the threads. A packet with no
// wanted pixel is not cast; one with some is cast whole, as without `wanted`: Embree's
// traversal depends on which lanes of a packet are active (it turns to single rays when
// few are), and with it which of two triangles at exactly the same distance a ray
// reports, so only whole packets give the same bytes for sure.
template <class OnHit, class Wanted = WholeTile>
void cast_packets(RTCScene scene, const CameraRays& rays, int x0, int y0, int x1, int y1,
                  const OnHit& on_hit, const Wanted& wanted = {}) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[16];
  bool keep[16];
  for (int by = y0; by < y1; by += 4) {
    for (int bx = x0; bx < x1; bx += 4) {
      bool any = false;
      for (int k = 0; k < 16; ++k) {
        const int x = bx + (k & 3), y = by + (k >> 2);
        const bool inside = x < x1 && y < y1;
        keep[k] = inside && wanted(x, y);
        any = any || keep[k];
        valid[k] = inside ? -1 : 0;
        set_primary_ray(packet, k, inside ? rays.dx[x] : 0.0f, inside ? rays.dy[y] : 0.0f);
      }
      if (!any) continue;
      rtcIntersect16(valid, scene, &context, &packet);
      for (int k = 0; k < 16; ++k) {
        if (!keep[k] || packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
        on_hit(bx + (k & 3), by + (k >> 2), packet.hit.instID[0][k], packet.hit.primID[k],
               packet.hit.u[k], packet.hit.v[k], packet.ray.tfar[k]);
      }
    }
  }
}

}  // namespace

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


RaycastImages raycast(const RenderScene& scene, const PinholeCamera& camera,
                      const RaycastOptions& options) {
  const CameraRays rays(camera);
  const SceneView view(scene);
  RaycastImages images;
  images.depth = zeros_like_image(camera, CV_32FC1);
  images.instance = cv::Mat(camera.height, camera.width, CV_32SC1, cv::Scalar(-1));
  images.normal = zeros_like_image(camera, CV_32FC3);
  images.geometric_normal = zeros_like_image(camera, CV_32FC3);
  images.point = zeros_like_image(camera, CV_32FC3);
  const RTCScene top = scene.embree_scene();
  const auto on_hit = [&](int x, int y, unsigned id, unsigned prim, float u, float v, float t) {
    write_hit(view, images, x, y, id, prim, u, v, t, Eigen::Vector3f(rays.dx[x], rays.dy[y], 1.0f));
  };

  render_detail::for_each_tile(
      cv::Rect(0, 0, camera.width, camera.height), options.threads,
      [&](int x0, int y0, int x1, int y1) {
        if (options.areas.empty()) return cast_packets(top, rays, x0, y0, x1, y1, on_hit);
        // The same tiles and packets as without areas; those that meet no area are not
        // cast, and only the pixels in an area are written.
        const cv::Rect tile(x0, y0, x1 - x0, y1 - y0);
        std::vector<cv::Rect> parts;
        for (const cv::Rect& area : options.areas) {
          const cv::Rect part = area & tile;
          if (!part.empty()) parts.push_back(part);
        }
        if (parts.empty()) return;
        cast_packets(top, rays, x0, y0, x1, y1, on_hit, [&](int x, int y) {
          for (const cv::Rect& part : parts) {
            if (part.contains({x, y})) return true;
          }
          return false;
        });
      });
  return images;
}

std::vector<cv::Mat> amodal_masks(const RenderScene& scene, const PinholeCamera& camera,
                                  const RaycastOptions& options) {
  const CameraRays rays(camera);
  require_committed(scene);
  std::vector<cv::Mat> masks;
  std::vector<cv::Rect> areas;
  for (int id = 0; id < scene.instance_count(); ++id) {
    const Instance& instance = scene.instance(id);
    masks.push_back(zeros_like_image(camera, CV_8UC1));
    areas.push_back(projected_area(scene.mesh(instance.mesh), instance.pose, camera));
  }
  render_detail::for_each_tile(areas, options.threads, [&](int id, int x0, int y0, int x1, int y1) {
    cv::Mat& mask = masks[id];
    cast_packets(scene.embree_instance_scene(id), rays, x0, y0, x1, y1,
                 [&](int x, int y, unsigned, unsigned, float, float, float) {
                   mask.at<std::uint8_t>(y, x) = 255;
                 });
  });
  return masks;
}

cv::Mat visible_mask(const RaycastImages& images, int instance) {
  cv::Mat mask;
  cv::compare(images.instance, cv::Scalar(instance), mask, cv::CMP_EQ);
  return mask;
}

}  // namespace flexsight

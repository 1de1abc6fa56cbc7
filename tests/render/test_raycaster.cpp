// Ray casting against analytic answers: the depth of a plane and of a box at known
// poses, per pixel; the box of a part's mask against its projected vertices; visible
// and amodal masks behind a known occluder; the same bytes for any thread count; and
// casts limited to areas.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"
#include "host/render/raycaster.h"
#include "host/render/shading.h"
#include "tests/render/render_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

// An awkward camera: odd sizes, fx != fy, principal point off centre.
PinholeCamera awkward_camera() {
  PinholeCamera camera;
  camera.width = 131;
  camera.height = 97;
  camera.fx = 150.0;
  camera.fy = 160.0;
  camera.cx = 64.3;
  camera.cy = 47.8;
  return camera;
}

Eigen::Vector3d at(const cv::Mat& image, int u, int v) {
  const cv::Vec3f& p = image.at<cv::Vec3f>(v, u);
  return {p[0], p[1], p[2]};
}

// Depth, normal and point match the double-precision answer to float tolerance.
void expect_hit(const RaycastImages& images, int u, int v, int id, const Eigen::Vector3d& ray,
                double depth, const Eigen::Vector3d& facing_normal) {
  SCOPED_TRACE("pixel (" + std::to_string(u) + ", " + std::to_string(v) + ")");
  ASSERT_EQ(images.instance.at<std::int32_t>(v, u), id);
  EXPECT_NEAR(images.depth.at<float>(v, u), depth, 2e-6 * depth);
  EXPECT_LT((at(images.point, u, v) - depth * ray).norm(), 2e-6 * depth);
  EXPECT_LT((at(images.geometric_normal, u, v) - facing_normal).norm(), 1e-5);
  EXPECT_LT((at(images.normal, u, v) - facing_normal).norm(), 1e-5);
}

void expect_miss(const RaycastImages& images, int u, int v) {
  EXPECT_EQ(images.instance.at<std::int32_t>(v, u), -1) << u << ", " << v;
  EXPECT_EQ(images.depth.at<float>(v, u), 0.0f) << u << ", " << v;
  EXPECT_EQ(at(images.normal, u, v), Eigen::Vector3d::Zero()) << u << ", " << v;
}

}  // namespace

// A square of two triangles, tilted, off-axis: every pixel's depth is where its ray
// meets the plane, inside the square; no pixel is hit outside it (and none is lost on
// the shared diagonal).
TEST(RaycastDepth, PlaneOfTwoTrianglesAtAKnownPose) {
  const PinholeCamera camera = awkward_camera();
  const float half = 100.0f;
  const Pose pose = make_pose(35.0, {1.0, 0.6, 0.2}, {10.0, -20.0, 800.0});
  RenderScene scene;
  scene.add_instance(scene.add_mesh(square_mesh(half)), pose);
  scene.commit();
  const RaycastImages images = raycast(scene, camera);

  const Eigen::Vector3d n = pose.R.col(2);
  int hits = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = pixel_ray(camera, u, v);
      const double depth = n.dot(pose.t) / n.dot(ray);
      const Eigen::Vector3d local = pose.R.transpose() * (depth * ray - pose.t);
      const double inside = half - local.head<2>().cwiseAbs().maxCoeff();
      if (inside > 1e-3) {
        expect_hit(images, u, v, 0, ray, depth, n.dot(ray) < 0 ? n : Eigen::Vector3d(-n));
        ++hits;
      } else if (inside < -1e-3) {
        expect_miss(images, u, v);
      }
    }
  }
  EXPECT_GT(hits, 1000);
}

// A box turned about a skew axis: the depth is where the ray enters the box (slab
// method in double), the normal that of the face it enters through.
TEST(RaycastDepth, BoxAtAKnownPose) {
  const PinholeCamera camera = awkward_camera();
  const Eigen::Vector3d h(30.0, 20.0, 25.0);
  const Pose pose = make_pose(40.0, {1.0, 2.0, 3.0}, {5.0, 10.0, 300.0});
  RenderScene scene;
  scene.add_instance(scene.add_mesh(box_mesh(h.cast<float>())), pose);
  scene.commit();
  const RaycastImages images = raycast(scene, camera);

  const Eigen::Vector3d origin = -pose.R.transpose() * pose.t;
  int hits = 0, misses = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = pixel_ray(camera, u, v);
      const Eigen::Vector3d d = pose.R.transpose() * ray;
      double enter = -INFINITY, leave = INFINITY, second = -INFINITY;
      int axis = 0;
      for (int i = 0; i < 3; ++i) {
        const double t1 = (-h[i] - origin[i]) / d[i], t2 = (h[i] - origin[i]) / d[i];
        const double near = std::min(t1, t2);
        if (near > enter) {
          second = enter;
          enter = near;
          axis = i;
        } else {
          second = std::max(second, near);
        }
        leave = std::min(leave, std::max(t1, t2));
      }
      // Leave pixels whose ray grazes an edge (float may go either way) aside.
      if (leave - enter > 1e-3 && enter - second > 1e-3) {
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        normal[axis] = d[axis] > 0 ? -1.0 : 1.0;
        expect_hit(images, u, v, 0, ray, enter, pose.R * normal);
        ++hits;
      } else if (enter - leave > 1e-3) {
        expect_miss(images, u, v);
        ++misses;
      }
    }
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 5000);
}

// The mask of a T-LESS part spans the box of its projected vertices: the extreme
// vertices lie on the silhouette, so the outermost pixel centres the part covers are
// next to them.
TEST(RaycastMasks, ProjectedBoxOfATlessPartIsTheBoxOfItsMask) {
  ASSERT_TRUE(file_present(tless_cad_path("05")));
  const auto mesh = std::make_shared<const Mesh>(load_mesh(tless_cad_path("05").string()));
  PinholeCamera camera;
  camera.width = 400;
  camera.height = 300;
  camera.fx = camera.fy = 1075.0;
  camera.cx = 196.3;
  camera.cy = 151.7;
  for (const Pose& pose : {make_pose(0.0, {0, 0, 1}, {0, 0, 600}),
                           make_pose(70.0, {0.3, -1.0, 0.5}, {-12.0, 8.0, 450.0}),
                           make_pose(150.0, {1.0, 1.0, 0.0}, {20.0, -15.0, 700.0})}) {
    RenderScene scene;
    scene.add_instance(scene.add_mesh(mesh), pose);
    scene.commit();
    const RaycastImages images = raycast(scene, camera);
    const cv::Rect mask_box = cv::boundingRect(visible_mask(images, 0));
    double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
    for (const Eigen::Vector3f& p : mesh->positions) {
      const Eigen::Vector2d uv = camera.project(pose.R * p.cast<double>() + pose.t);
      lo_u = std::min(lo_u, uv.x());
      hi_u = std::max(hi_u, uv.x());
      lo_v = std::min(lo_v, uv.y());
      hi_v = std::max(hi_v, uv.y());
    }
    ASSERT_GT(lo_u, 0.0);
    ASSERT_LT(hi_u, camera.width - 1.0);
    ASSERT_GT(lo_v, 0.0);
    ASSERT_LT(hi_v, camera.height - 1.0);
    // Inside the projected box (a hit pixel centre lies within the silhouette), and
    // less than a pixel and a half from it: the silhouette narrows to a point at an
    // extreme vertex, so the last pixel centre it covers may be one column short.
    const double left = mask_box.x, right = mask_box.x + mask_box.width - 1;
    const double top = mask_box.y, bottom = mask_box.y + mask_box.height - 1;
    EXPECT_GE(left, lo_u - 1e-3);
    EXPECT_LE(right, hi_u + 1e-3);
    EXPECT_GE(top, lo_v - 1e-3);
    EXPECT_LE(bottom, hi_v + 1e-3);
    EXPECT_LT(left - lo_u, 1.5);
    EXPECT_LT(hi_u - right, 1.5);
    EXPECT_LT(top - lo_v, 1.5);
    EXPECT_LT(hi_v - bottom, 1.5);
    // Alone in the scene, the part's amodal mask is its visible mask.
    const std::vector<cv::Mat> amodal = amodal_masks(scene, camera);
    ASSERT_EQ(amodal.size(), 1u);
    EXPECT_TRUE(same_mat_bytes(amodal[0], visible_mask(images, 0)));
  }
}

// A square at 1 m behind a second square at 0.5 m that covers its left half (and more):
// pixel centres fall 0.5 pixel from every edge, so the counts are exact. The visible
// fraction of the back square is a half; its amodal mask is the whole square.
TEST(RaycastMasks, VisibleFractionBehindAKnownOccluder) {
  PinholeCamera camera;
  camera.width = camera.height = 200;
  camera.fx = camera.fy = 1000.0;
  camera.cx = camera.cy = 99.5;
  RenderScene scene;
  const int square = scene.add_mesh(square_mesh(50.0f));
  // Back: |x|, |y| <= 50 at z = 1000: columns and rows 50..149 (100 x 100).
  const int back = scene.add_instance(square, make_pose(0, {0, 0, 1}, {0, 0, 1000}));
  // Front: x in [-100, 0], |y| <= 50 at z = 500: x / z in [-0.2, 0], columns 0..99, all
  // rows (|y / z| <= 0.1 reaches past the image).
  const int front = scene.add_instance(square, make_pose(0, {0, 0, 1}, {-50, 0, 500}));
  scene.commit();
  const RaycastImages images = raycast(scene, camera);
  const std::vector<cv::Mat> amodal = amodal_masks(scene, camera);
  ASSERT_EQ(amodal.size(), 2u);
  const cv::Mat back_visible = visible_mask(images, back);
  const cv::Mat front_visible = visible_mask(images, front);
  EXPECT_EQ(cv::countNonZero(amodal[back]), 100 * 100);
  EXPECT_EQ(cv::countNonZero(back_visible), 50 * 100);
  EXPECT_EQ(cv::countNonZero(amodal[front]), 100 * 200);
  EXPECT_EQ(cv::countNonZero(front_visible), 100 * 200);
  EXPECT_EQ(double(cv::countNonZero(back_visible)) / cv::countNonZero(amodal[back]), 0.5);
  EXPECT_EQ(cv::countNonZero(amodal[back](cv::Rect(50, 50, 100, 100))), 100 * 100);
  EXPECT_EQ(cv::countNonZero(back_visible(cv::Rect(100, 50, 50, 100))), 50 * 100);
  // Visible is always within amodal.
  cv::Mat outside;
  cv::bitwise_and(back_visible, ~amodal[back], outside);
  EXPECT_EQ(cv::countNonZero(outside), 0);
  EXPECT_EQ(images.depth.at<float>(100, 120), 1000.0f);
  EXPECT_EQ(images.depth.at<float>(100, 80), 500.0f);
  EXPECT_EQ(images.depth.at<float>(10, 180), 0.0f);
}

// Moving an instance and committing again moves its pixels; a changed scene must be
// committed before rays are cast.
TEST(RaycastDepth, PosesCanChangeBetweenImages) {
  PinholeCamera camera;
  camera.width = camera.height = 64;
  camera.fx = camera.fy = 100.0;
  camera.cx = camera.cy = 31.5;
  RenderScene scene;
  const int id =
      scene.add_instance(scene.add_mesh(square_mesh(10.0f)), make_pose(0, {0, 0, 1}, {0, 0, 400}));
  scene.commit();
  EXPECT_EQ(raycast(scene, camera).depth.at<float>(32, 32), 400.0f);
  scene.set_pose(id, make_pose(0, {0, 0, 1}, {0, 0, 250}));
  EXPECT_FALSE(scene.committed());
  EXPECT_THROW(raycast(scene, camera), std::logic_error);
  scene.commit();
  EXPECT_EQ(raycast(scene, camera).depth.at<float>(32, 32), 250.0f);
}

TEST(RaycastDepth, RejectsAnImpossibleCamera) {
  RenderScene scene;
  scene.add_instance(scene.add_mesh(square_mesh(10.0f)), make_pose(0, {0, 0, 1}, {0, 0, 400}));
  scene.commit();
  for (const auto& edit : std::vector<std::function<void(PinholeCamera&)>>{
           [](PinholeCamera& c) { c.fx = 0; }, [](PinholeCamera& c) { c.fy = -5; },
           [](PinholeCamera& c) { c.width = 0; }, [](PinholeCamera& c) { c.cx = NAN; }}) {
    PinholeCamera camera;
    edit(camera);
    try {
      raycast(scene, camera);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()).rfind("camera: ", 0), 0u) << error.what();
    }
  }
}

// A bin-like scene of T-LESS parts, ray cast and shaded with soft shadows: every
// output is the same bytes with 1, 2 and 5 threads.
TEST(RaycastDeterminism, SameBytesWithOneAndManyThreads) {
  RenderScene scene;
  const char* objects[] = {"02", "05", "11", "19", "26"};
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(file_present(tless_cad_path(objects[i])));
    const int mesh = scene.add_mesh(
        std::make_shared<const Mesh>(load_mesh(tless_cad_path(objects[i]).string())));
    Material material;
    material.albedo = tinted_grey(3, i);
    scene.add_instance(mesh,
                       make_pose(37.0 * i, {1.0, i - 2.0, 0.5},
                                 {-60.0 + 30.0 * i, 10.0 * (i % 2), 500.0 + 15 * i}),
                       material);
  }
  const int floor = scene.add_mesh(square_mesh(400.0f));
  scene.add_instance(floor, make_pose(0, {0, 0, 1}, {0, 0, 560}));
  scene.commit();
  PinholeCamera camera = awkward_camera();
  camera.fx = camera.fy = 120.0;
  ShadingOptions shading;
  shading.lights[0].radius = 40.0f;
  shading.shadow_samples = 4;
  shading.camera_light = true;

  const auto run = [&](int threads) {
    RaycastOptions options;
    options.threads = threads;
    shading.threads = threads;
    RaycastImages images = raycast(scene, camera, options);
    std::vector<cv::Mat> outputs = {images.depth,  images.instance,
                                    images.normal, images.geometric_normal,
                                    images.point,  shade(scene, images, shading)};
    for (const cv::Mat& mask : amodal_masks(scene, camera, options)) outputs.push_back(mask);
    return outputs;
  };
  const std::vector<cv::Mat> one = run(1);
  for (int threads : {2, 5}) {
    const std::vector<cv::Mat> many = run(threads);
    ASSERT_EQ(many.size(), one.size());
    for (size_t i = 0; i < one.size(); ++i) {
      EXPECT_TRUE(same_mat_bytes(one[i], many[i]))
          << "output " << i << ", " << threads << " threads";
    }
  }
  // Every part and the floor are in the picture, each visible pixel within its amodal
  // mask, and the parts that hide each other show less than their amodal masks.
  int hidden = 0;
  for (int id = 0; id < 6; ++id) {
    const cv::Mat visible = one[1] == id;
    const cv::Mat& amodal = one[6 + id];
    EXPECT_GT(cv::countNonZero(visible), 20) << "instance " << id;
    EXPECT_EQ(cv::countNonZero(visible & ~amodal), 0) << "instance " << id;
    hidden += cv::countNonZero(amodal) - cv::countNonZero(visible);
  }
  EXPECT_GT(hidden, 100);
}

// Areas: the pixels of two overlapping rectangles that straddle tiles and packets are
// the same bytes as in the full cast, every other pixel is empty; the projected boxes of
// all the instances give the full cast's bytes everywhere.
TEST(RaycastDepth, AreasCastTheirPixelsOnlyWithTheSameBytes) {
  RenderScene scene;
  const char* objects[] = {"05", "19", "30"};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(file_present(tless_cad_path(objects[i])));
    const int mesh = scene.add_mesh(
        std::make_shared<const Mesh>(load_mesh(tless_cad_path(objects[i]).string())));
    scene.add_instance(mesh, make_pose(60.0 * i + 10.0, {1.0, 0.5, i - 1.0},
                                       {-45.0 + 45.0 * i, 8.0 * i - 8.0, 420.0 + 30 * i}));
  }
  scene.commit();
  PinholeCamera camera = awkward_camera();
  camera.fx = camera.fy = 260.0;
  const RaycastImages full = raycast(scene, camera);

  RaycastOptions options;
  options.areas = {cv::Rect(5, 7, 40, 33), cv::Rect(30, 21, 61, 50)};
  const RaycastImages some = raycast(scene, camera, options);
  cv::Mat inside = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
  for (const cv::Rect& area : options.areas) inside(area).setTo(255);
  const std::vector<std::pair<cv::Mat, cv::Mat>> outputs = {
      {full.depth, some.depth},
      {full.instance, some.instance},
      {full.normal, some.normal},
      {full.geometric_normal, some.geometric_normal},
      {full.point, some.point}};
  int hits_inside = 0, hits_outside = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const bool hit = full.instance.at<std::int32_t>(v, u) >= 0;
      if (inside.at<std::uint8_t>(v, u) == 0) {
        hits_outside += hit;
        expect_miss(some, u, v);
        continue;
      }
      hits_inside += hit;
      for (const auto& [a, b] : outputs) {
        ASSERT_EQ(std::memcmp(a.ptr(v, u), b.ptr(v, u), a.elemSize()), 0) << u << ", " << v;
      }
    }
  }
  EXPECT_GT(hits_inside, 300);
  EXPECT_GT(hits_outside, 300);

  // Each part's pixels lie within the box of its amodal mask.
  options.areas.clear();
  for (const cv::Mat& amodal : amodal_masks(scene, camera)) {
    options.areas.push_back(cv::boundingRect(amodal));
  }
  const RaycastImages boxed = raycast(scene, camera, options);
  for (const auto& [a, b] : std::vector<std::pair<cv::Mat, cv::Mat>>{
           {full.depth, boxed.depth},
           {full.instance, boxed.instance},
           {full.normal, boxed.normal},
           {full.geometric_normal, boxed.geometric_normal},
           {full.point, boxed.point}}) {
    EXPECT_TRUE(same_mat_bytes(a, b));
  }
}

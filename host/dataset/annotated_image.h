#pragma once
// One image of a training or test set with what is known about every part in it: the
// in-memory form the synthetic-data generators produce, the BOP and COCO writers store
// and their readers give back. Field names follow BOP's (docs/bop_datasets_format.md of
// the BOP toolkit), so a reader of either format fills the same struct.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <vector>

namespace flexsight {

// BOP's scene_camera.json entry: intrinsics, and the scale that turns the 16-bit depth
// PNG's values into millimetres (depth_mm = value * depth_scale).
struct DatasetCamera {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  double depth_scale = 0.1;
  // Further keys of the image's scene_camera.json entry, kept as they are: a JSON object
  // (or null for none). The readers put here what they do not interpret (T-LESS's
  // cam_R_w2c, cam_t_w2c, elev, mode); a generator adds what a user of its images needs
  // to know (e.g. {"flip": "horizontal"}). The writer copies it beside cam_K and
  // depth_scale, which it may not name.
  nlohmann::json extra;
};

// BOP's box: x, y of the top-left pixel, width and height; (-1, -1, -1, -1) when the
// part has no pixel (scene_gt_info's convention for a part out of view). Our boxes
// (gt_info.h) count pixels: width = x_max - x_min + 1, as COCO's and pycocotools' are.
// The BOP toolkit's calc_2d_bbox gives x_max - x_min, one less; boxes read from a real
// BOP file are kept as written.
struct BopBox {
  int x = -1, y = -1, width = -1, height = -1;
  bool empty() const { return width <= 0 || height <= 0; }
  bool operator==(const BopBox& other) const {
    return x == other.x && y == other.y && width == other.width && height == other.height;
  }
};

// One part in one image: scene_gt.json (pose, model) and scene_gt_info.json (boxes,
// pixel counts), and its masks.
struct PartAnnotation {
  int obj_id = 0;  // the model's id: obj_000001.ply is 1 (BOP), obj_01.stl is 1 here
  // Pose of the model in the camera frame: x_cam = R x_model + t, t in mm.
  Eigen::Matrix3d cam_R_m2c = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_t_m2c = Eigen::Vector3d::Zero();
  BopBox bbox_obj;    // box of the amodal (full) mask, clipped to the image
  BopBox bbox_visib;  // box of the visible mask
  int px_count_all = 0;    // pixels of the amodal mask inside the image
  int px_count_valid = 0;  // of those, pixels with a valid depth
  int px_count_visib = 0;  // pixels of the visible mask
  double visib_fract = 0.0;  // px_count_visib / px_count_all (0 when out of view)
  // CV_8UC1, 255 on the part, 0 elsewhere, the image's size; empty when not stored
  // (--no-masks, or a COCO file, which has the visible mask only).
  cv::Mat mask;        // amodal: the part as if it were alone
  cv::Mat mask_visib;  // where the part is the closest surface
};

struct AnnotatedImage {
  int scene_id = 0;
  int im_id = 0;
  cv::Mat rgb;    // CV_8UC3, RGB channel order (as load_rgb8 returns)
  cv::Mat depth;  // CV_32FC1 in mm, 0 where no surface; empty when not stored
  DatasetCamera camera;
  std::vector<PartAnnotation> parts;  // in gt_id order (BOP's per-image index)
  // Flips of the whole picture made after rendering (host/synth's augmentation). A flip
  // is a reflection, which no rigid pose describes: the poses are stored reflected,
  // cam_R_m2c = F R and cam_t_m2c = F t with F = diag(-1, 1, 1) for a horizontal flip and
  // diag(1, -1, 1) for a vertical one, so that they project the model onto the flipped
  // pixels (the principal point being the image centre), but det(cam_R_m2c) = -1 after
  // one flip. Both flips together are a turn by 180 degrees about the optical axis, a
  // proper pose. Writers keep the two flags (BOP: extra keys of the image's
  // scene_camera.json entry) so that pose evaluators can skip mirrored images.
  bool flipped_horizontally = false;
  bool flipped_vertically = false;
  // Exactly one flip: the poses are reflections, no rigid motion of the model.
  bool mirrored() const { return flipped_horizontally != flipped_vertically; }
};

}  // namespace flexsight

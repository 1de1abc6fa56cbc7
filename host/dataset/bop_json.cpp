#include "host/dataset/bop_json.h"

#include "host/dataset/bop_layout.h"
#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"
#include "host/io/physical_checks.h"

namespace flexsight {
namespace {

using dataset_files::Json;
using dataset_files::require_key;

// ------------------------------------------------------------------------- writing --

Json matrix_json(const Eigen::Matrix3d& m) {
  Json values = Json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) values.push_back(m(r, c));  // row-major, as BOP
  }
  return values;
}

Json box_json(const BopBox& box) { return Json::array({box.x, box.y, box.width, box.height}); }

Json camera_entry(const DatasetCamera& camera) {
  Json entry = camera.extra.is_object() ? camera.extra : Json::object();
  entry["cam_K"] = matrix_json(camera.K);
  entry["depth_scale"] = camera.depth_scale;
  return entry;
}

Json gt_entry(const PartAnnotation& part) {
  return Json{
      {"cam_R_m2c", matrix_json(part.cam_R_m2c)},
      {"cam_t_m2c", Json::array({part.cam_t_m2c.x(), part.cam_t_m2c.y(), part.cam_t_m2c.z()})},
      {"obj_id", part.obj_id}};
}

Json gt_info_entry(const PartAnnotation& part) {
  return Json{{"bbox_obj", box_json(part.bbox_obj)},   {"bbox_visib", box_json(part.bbox_visib)},
              {"px_count_all", part.px_count_all},     {"px_count_valid", part.px_count_valid},
              {"px_count_visib", part.px_count_visib}, {"visib_fract", part.visib_fract}};
}

// {"<im_id>": entry, ...} in numeric order, one line per image, as the BOP toolkit's
// save_json; a list entry gets one line per part (the toolkit puts the whole list on the
// image's line), which keeps lines short in images of many parts.
std::string im_id_object_text(const std::map<int, Json>& entries) {
  if (entries.empty()) return "{}\n";
  std::string text = "{\n";
  bool first = true;
  for (const auto& [im_id, entry] : entries) {
    if (!first) text += ",\n";
    first = false;
    text += "  \"" + std::to_string(im_id) + "\": ";
    if (entry.is_array() && !entry.empty()) {
      text += "[\n";
      for (std::size_t i = 0; i < entry.size(); ++i) {
        text += "    " + entry[i].dump() + (i + 1 < entry.size() ? ",\n" : "\n");
      }
      text += "  ]";
    } else {
      text += entry.dump();
    }
  }
  return text + "\n}\n";
}

// ------------------------------------------------------------------------- reading --

std::string image_where(int im_id) { return "image " + std::to_string(im_id); }

Eigen::Matrix3d matrix_of(const Json& value, const std::string& file, const std::string& where) {
  const std::vector<double> v = dataset_files::to_doubles(value, 9, file, where);
  Eigen::Matrix3d m;
  m << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  return m;
}

BopBox box_of(const Json& value, const std::string& file, const std::string& where,
              bool visible) {
  if (!value.is_array() || value.size() != 4) {
    throw InputError(
        file, where + ": expected an array of 4 integers [x, y, w, h], found " + value.dump());
  }
  const BopBox box{dataset_files::to_int(value[0], file, where + "[0]"),
                   dataset_files::to_int(value[1], file, where + "[1]"),
                   dataset_files::to_int(value[2], file, where + "[2]"),
                   dataset_files::to_int(value[3], file, where + "[3]")};
  // (-1, -1, -1, -1) marks a part without pixels; any other box has a size (0 for one
  // pixel in the BOP toolkit's x_max - x_min). bbox_obj may start left of or above the
  // image (the toolkit measures the whole silhouette), bbox_visib may not.
  if (box == BopBox{}) return box;
  if (box.width < 0 || box.height < 0) {
    throw InputError(file, where + ": " + value.dump() +
                               " has a negative width or height (a part without pixels is "
                               "[-1, -1, -1, -1])");
  }
  if (visible && (box.x < 0 || box.y < 0)) {
    throw InputError(file, where + ": " + value.dump() + " starts outside the image");
  }
  return box;
}

// The file's top-level object by im_id.
std::map<int, Json> read_im_id_object(const std::string& path) {
  const Json root = dataset_files::read_json(path);
  if (!root.is_object()) {
    throw InputError(
        path, "expected an object keyed by image id, found " + std::string(root.type_name()));
  }
  std::map<int, Json> entries;
  for (const auto& [key, value] : root.items()) {
    entries[dataset_files::parse_im_id(key, path)] = value;
  }
  return entries;
}

// `entries` (from `path`) lists exactly the images of scene_camera.json.
void require_same_images(const std::map<int, Json>& entries, const std::string& path,
                         const BopSceneRecords& images) {
  for (const auto& [im_id, record] : images) {
    if (entries.count(im_id) == 0) {
      throw InputError(path, "has no entry for image " + std::to_string(im_id) + " (" +
                                 bop_layout::kSceneCamera + " has one)");
    }
  }
  for (const auto& [im_id, entry] : entries) {
    if (images.count(im_id) == 0) {
      throw InputError(path, "has an entry for image " + std::to_string(im_id) + " that " +
                                 bop_layout::kSceneCamera + " lacks");
    }
  }
}

const Json& list_of(const Json& entry, const std::string& path, const std::string& where) {
  if (!entry.is_array()) {
    throw InputError(path, where + ": expected a list of parts, found " + entry.type_name());
  }
  return entry;
}

DatasetCamera camera_of(const Json& entry, const std::string& path, int im_id,
                        bool require_depth_scale) {
  const std::string where = image_where(im_id);
  DatasetCamera camera;
  camera.K = matrix_of(require_key(entry, "cam_K", path, where), path, where + ": cam_K");
  const std::string k_problem = physical_checks::intrinsics_problem(camera.K);
  if (!k_problem.empty()) throw InputError(path, where + ": cam_K: " + k_problem);
  if (require_depth_scale || entry.contains("depth_scale")) {
    camera.depth_scale = dataset_files::to_double(require_key(entry, "depth_scale", path, where),
                                                  path, where + ": depth_scale");
    const std::string problem = physical_checks::depth_scale_problem(camera.depth_scale);
    if (!problem.empty()) throw InputError(path, where + ": depth_scale " + problem);
  }
  for (const auto& [key, value] : entry.items()) {
    if (key != "cam_K" && key != "depth_scale") camera.extra[key] = value;
  }
  return camera;
}

bool extra_flag(const DatasetCamera& camera, const char* key) {
  if (!camera.extra.is_object()) return false;
  const auto found = camera.extra.find(key);
  return found != camera.extra.end() && found->is_boolean() && found->get<bool>();
}

// What the image's scene_camera.json entry says of its poses: an image flipped once
// (host/synth's augmentation) stores reflections; a pasted one (synth semi) stores
// placeholders (identity, origin) under "pose_unknown".
struct PoseKind {
  bool mirrored = false;
  bool unknown = false;
};

PoseKind pose_kind(const DatasetCamera& camera) {
  return {extra_flag(camera, "flip_horizontal") != extra_flag(camera, "flip_vertical"),
          extra_flag(camera, "pose_unknown")};
}

void read_gt(const Json& entry, const std::string& path, const std::string& where,
             const PoseKind& kind, PartAnnotation& part) {
  part.cam_R_m2c =
      matrix_of(require_key(entry, "cam_R_m2c", path, where), path, where + ": cam_R_m2c");
  const std::string r_problem = physical_checks::rotation_problem(part.cam_R_m2c, kind.mirrored);
  if (!r_problem.empty()) throw InputError(path, where + ": cam_R_m2c " + r_problem);
  const std::vector<double> t = dataset_files::to_doubles(
      require_key(entry, "cam_t_m2c", path, where), 3, path, where + ": cam_t_m2c");
  part.cam_t_m2c = Eigen::Vector3d(t[0], t[1], t[2]);
  const std::string t_problem =
      physical_checks::translation_problem(part.cam_t_m2c, !kind.unknown);
  if (!t_problem.empty()) throw InputError(path, where + ": cam_t_m2c " + t_problem);
  part.obj_id =
      dataset_files::to_int(require_key(entry, "obj_id", path, where), path, where + ": obj_id");
}

void read_gt_info(const Json& entry, const std::string& path, const std::string& where,
                  PartAnnotation& part) {
  auto integer = [&](const char* key) {
    return dataset_files::to_int(require_key(entry, key, path, where), path, where + ": " + key);
  };
  part.bbox_obj =
      box_of(require_key(entry, "bbox_obj", path, where), path, where + ": bbox_obj", false);
  part.bbox_visib =
      box_of(require_key(entry, "bbox_visib", path, where), path, where + ": bbox_visib", true);
  part.px_count_all = integer("px_count_all");
  part.px_count_valid = integer("px_count_valid");
  part.px_count_visib = integer("px_count_visib");
  part.visib_fract = dataset_files::to_double(require_key(entry, "visib_fract", path, where), path,
                                              where + ": visib_fract");
}

}  // namespace

void write_bop_scene_json(const std::string& scene_dir, const BopSceneRecords& records) {
  std::map<int, Json> cameras, gts, gt_infos;
  for (const auto& [im_id, record] : records) {
    cameras[im_id] = camera_entry(record.camera);
    Json gt = Json::array(), gt_info = Json::array();
    for (const PartAnnotation& part : record.parts) {
      gt.push_back(gt_entry(part));
      gt_info.push_back(gt_info_entry(part));
    }
    gts[im_id] = gt;
    gt_infos[im_id] = gt_info;
  }
  dataset_files::write_text(scene_dir + "/" + bop_layout::kSceneCamera, im_id_object_text(cameras));
  dataset_files::write_text(scene_dir + "/" + bop_layout::kSceneGt, im_id_object_text(gts));
  dataset_files::write_text(scene_dir + "/" + bop_layout::kSceneGtInfo,
                            im_id_object_text(gt_infos));
}

BopSceneJson read_bop_scene_json(const std::string& scene_dir, bool require_depth_scale) {
  BopSceneJson scene;
  const std::string camera_path = scene_dir + "/" + bop_layout::kSceneCamera;
  for (const auto& [im_id, entry] : read_im_id_object(camera_path)) {
    scene.images[im_id].camera = camera_of(entry, camera_path, im_id, require_depth_scale);
  }

  const std::string gt_path = scene_dir + "/" + bop_layout::kSceneGt;
  const std::map<int, Json> gts = read_im_id_object(gt_path);
  require_same_images(gts, gt_path, scene.images);
  for (const auto& [im_id, entry] : gts) {
    const Json& list = list_of(entry, gt_path, image_where(im_id));
    std::vector<PartAnnotation>& parts = scene.images[im_id].parts;
    parts.resize(list.size());
    for (std::size_t gt_id = 0; gt_id < list.size(); ++gt_id) {
      read_gt(list[gt_id], gt_path, image_where(im_id) + ", gt " + std::to_string(gt_id),
              pose_kind(scene.images[im_id].camera), parts[gt_id]);
    }
  }

  const std::string info_path = scene_dir + "/" + bop_layout::kSceneGtInfo;
  scene.has_gt_info = dataset_files::is_file(info_path);
  if (!scene.has_gt_info) return scene;
  const std::map<int, Json> infos = read_im_id_object(info_path);
  require_same_images(infos, info_path, scene.images);
  for (const auto& [im_id, entry] : infos) {
    const Json& list = list_of(entry, info_path, image_where(im_id));
    std::vector<PartAnnotation>& parts = scene.images[im_id].parts;
    if (list.size() != parts.size()) {
      throw InputError(info_path, image_where(im_id) + ": lists " + std::to_string(list.size()) +
                                      " parts but " + bop_layout::kSceneGt + " lists " +
                                      std::to_string(parts.size()));
    }
    for (std::size_t gt_id = 0; gt_id < list.size(); ++gt_id) {
      read_gt_info(list[gt_id], info_path, image_where(im_id) + ", gt " + std::to_string(gt_id),
                   parts[gt_id]);
    }
  }
  return scene;
}

}  // namespace flexsight

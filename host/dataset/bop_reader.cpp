#include "host/dataset/bop_reader.h"

#include <algorithm>
#include <filesystem>

#include "host/dataset/bop_layout.h"
#include "host/dataset/dataset_files.h"
#include "host/io/image_header.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

// The folder name as a scene id: "000001" is 1; 0 for a name that is not a number.
int scene_id_of(const std::string& dir) {
  const std::string name = fs::path(dir).filename().string();
  const bool digits = !name.empty() && name.size() <= 9 &&
                      name.find_first_not_of("0123456789") == std::string::npos;
  return digits ? std::stoi(name) : 0;
}

// BOP stores color images in rgb/ and, for gray-only sensors (ITODD), in gray/; the
// format differs between data sets (T-LESS png, the PBR sets jpg). Empty when none is there.
std::string existing_rgb(const std::string& scene_dir, int im_id) {
  for (const char* folder : {"rgb", "gray"}) {
    for (const char* extension : {".png", ".jpg", ".jpeg", ".tif"}) {
      const std::string path =
          scene_dir + "/" + folder + "/" + bop_layout::six_digits(im_id) + extension;
      if (dataset_files::is_file(path)) return path;
    }
  }
  return {};
}

std::string find_rgb(const std::string& scene_dir, int im_id) {
  const std::string path = existing_rgb(scene_dir, im_id);
  if (!path.empty()) return path;
  throw InputError(scene_dir + "/rgb/" + bop_layout::six_digits(im_id) + ".png",
                   "does not exist (nor does a .jpg, .jpeg or .tif, in rgb/ or gray/)");
}

void require_size(const cv::Mat& image, const cv::Size& size, const std::string& path) {
  if (image.size() != size) {
    throw InputError(path, "is " + io_detail::size_text(image.size()) + " but the rgb image is " +
                               io_detail::size_text(size));
  }
}

cv::Mat read_depth_mm(const std::string& path, double depth_scale, const cv::Size& size) {
  const cv::Mat encoded = io_detail::imread_unchanged(path);
  if (encoded.type() != CV_16UC1) {
    throw InputError(path, "is " + io_detail::describe(encoded) + ", expected a 16-bit gray depth");
  }
  require_size(encoded, size, path);
  cv::Mat depth(size, CV_32FC1);
  for (int y = 0; y < size.height; ++y) {
    const auto* src = encoded.ptr<std::uint16_t>(y);
    float* dst = depth.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) dst[x] = static_cast<float>(src[x] * depth_scale);
  }
  return depth;
}

cv::Mat read_mask(const std::string& path, const cv::Size& size) {
  const cv::Mat image = io_detail::imread_unchanged(path);
  if (image.depth() != CV_8U) {
    throw InputError(path, "is " + io_detail::describe(image) + ", expected an 8-bit mask");
  }
  const cv::Mat mask = io_detail::single_channel_of_gray(image, path);
  require_size(mask, size, path);
  return mask != 0;
}

// The visible box lies in the image (the reader of scene_gt_info.json checked the rest
// of it, without the image's size).
void require_inside(const BopBox& box, const cv::Size& size, const std::string& scene_dir,
                    int im_id, int gt_id) {
  const long long right = static_cast<long long>(box.x) + box.width;
  const long long bottom = static_cast<long long>(box.y) + box.height;
  if (box.empty() || (right <= size.width && bottom <= size.height)) {
    return;
  }
  throw InputError(scene_dir + "/" + bop_layout::kSceneGtInfo,
                   "image " + std::to_string(im_id) + ", gt " + std::to_string(gt_id) +
                       ": bbox_visib [" + std::to_string(box.x) + ", " + std::to_string(box.y) +
                       ", " + std::to_string(box.width) + ", " + std::to_string(box.height) +
                       "] reaches beyond the " + io_detail::size_text(size) + " image");
}

}  // namespace

BopReader::BopReader(const std::string& path) {
  if (dataset_files::is_file(path + "/" + bop_layout::kSceneCamera)) {
    add_scene(path);
  } else if (dataset_files::is_directory(path)) {
    std::vector<std::string> dirs;
    for (const auto& entry : fs::directory_iterator(path)) {
      const std::string dir = entry.path().string();
      if (entry.is_directory() && dataset_files::is_file(dir + "/" + bop_layout::kSceneCamera)) {
        dirs.push_back(dir);
      }
    }
    std::sort(dirs.begin(), dirs.end());
    for (const std::string& dir : dirs) add_scene(dir);
    if (scenes_.empty()) {
      throw InputError(path, std::string("is neither a BOP scene folder (it has no ") +
                                 bop_layout::kSceneCamera +
                                 ") nor a split folder (no subfolder has one)");
    }
  } else {
    throw InputError(path, "does not exist (expected a BOP scene or split folder)");
  }
  std::stable_sort(scenes_.begin(), scenes_.end(),
                   [](const Scene& a, const Scene& b) { return a.scene_id < b.scene_id; });
  for (std::size_t s = 0; s < scenes_.size(); ++s) {
    for (const auto& [im_id, record] : scenes_[s].json.images) index_.push_back({s, im_id});
  }
}

void BopReader::add_scene(const std::string& dir) {
  Scene scene;
  scene.dir = dir;
  scene.scene_id = scene_id_of(dir);
  scene.has_depth = dataset_files::is_directory(dir + "/depth");
  scene.has_mask = dataset_files::is_directory(dir + "/mask");
  scene.has_mask_visib = dataset_files::is_directory(dir + "/mask_visib");
  // Depth PNGs mean nothing without their scale.
  scene.json = read_bop_scene_json(dir, scene.has_depth);
  scenes_.push_back(std::move(scene));
}

BopImageRef BopReader::ref(std::size_t i) const {
  const Entry& entry = index_.at(i);
  return {scenes_[entry.scene].scene_id, entry.im_id};
}

const BopImageRecord& BopReader::record(std::size_t i) const {
  const Entry& entry = index_.at(i);
  return scenes_[entry.scene].json.images.at(entry.im_id);
}

const std::string& BopReader::scene_dir(std::size_t i) const {
  return scenes_[index_.at(i).scene].dir;
}

bool BopReader::has_gt_info(std::size_t i) const {
  return scenes_[index_.at(i).scene].json.has_gt_info;
}

AnnotatedImage BopReader::load(std::size_t i) const {
  const Entry& entry = index_.at(i);
  const Scene& scene = scenes_[entry.scene];
  const BopImageRecord& record = scene.json.images.at(entry.im_id);
  AnnotatedImage image;
  image.scene_id = scene.scene_id;
  image.im_id = entry.im_id;
  image.camera = record.camera;
  if (record.camera.extra.is_object()) {
    image.flipped_horizontally = record.camera.extra.value("flip_horizontal", false);
    image.flipped_vertically = record.camera.extra.value("flip_vertical", false);
  }
  image.parts = record.parts;
  image.rgb = load_rgb8(find_rgb(scene.dir, entry.im_id));
  const cv::Size size = image.rgb.size();
  if (scene.has_depth) {
    image.depth = read_depth_mm(scene.dir + "/" + bop_layout::depth_in_scene(entry.im_id),
                                record.camera.depth_scale, size);
  }
  for (std::size_t gt_id = 0; gt_id < image.parts.size(); ++gt_id) {
    PartAnnotation& part = image.parts[gt_id];
    const int gt = static_cast<int>(gt_id);
    if (scene.json.has_gt_info) require_inside(part.bbox_visib, size, scene.dir, entry.im_id, gt);
    if (scene.has_mask) {
      part.mask =
          read_mask(scene.dir + "/" + bop_layout::mask_in_scene(entry.im_id, gt, false), size);
    }
    if (scene.has_mask_visib) {
      part.mask_visib =
          read_mask(scene.dir + "/" + bop_layout::mask_in_scene(entry.im_id, gt, true), size);
    }
  }
  return image;
}

cv::Size BopReader::check_boxes_inside_image(std::size_t i, bool require_image) const {
  const Entry& entry = index_.at(i);
  const Scene& scene = scenes_[entry.scene];
  if (!scene.json.has_gt_info) return {};
  const std::string rgb = require_image ? find_rgb(scene.dir, entry.im_id) : existing_rgb(scene.dir, entry.im_id);
  if (rgb.empty()) return {};
  const cv::Size size = image_size_from_header(rgb);
  const std::vector<PartAnnotation>& parts = scene.json.images.at(entry.im_id).parts;
  for (std::size_t gt = 0; gt < parts.size(); ++gt) {
    require_inside(parts[gt].bbox_visib, size, scene.dir, entry.im_id, static_cast<int>(gt));
  }
  return size;
}

}  // namespace flexsight

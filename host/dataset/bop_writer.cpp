#include "host/dataset/bop_writer.h"

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "host/dataset/bop_layout.h"
#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

// PNG compression fixed here, not left to OpenCV's default, so the files' bytes do not
// change with the OpenCV version. Level 1: the generator should not wait on zlib (at
// 1280x960 the masks were a third of an image's time at level 3). Masks, long runs of
// 0 and 255, use zlib's run-length strategy: as small as level 3's files, far faster.
const std::vector<int> kPngParams{cv::IMWRITE_PNG_COMPRESSION, 1};
const std::vector<int> kMaskPngParams{cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY,
                                      cv::IMWRITE_PNG_STRATEGY_RLE, cv::IMWRITE_PNG_BILEVEL, 1};

// The 16-bit depth PNG's values: round(depth_mm / depth_scale), 0 where depth is 0.
cv::Mat encode_depth(const cv::Mat& depth, double depth_scale, const cv::Size& size,
                     const std::string& path) {
  if (depth.type() != CV_32FC1 || depth.size() != size) {
    throw InputError(
        path, "depth is " + (depth.empty() ? std::string("missing") : io_detail::describe(depth)) +
                  ", expected 32F 1-channel " + io_detail::size_text(size) +
                  " (or set write_depth off)");
  }
  cv::Mat encoded(size, CV_16UC1);
  for (int y = 0; y < size.height; ++y) {
    const float* src = depth.ptr<float>(y);
    auto* dst = encoded.ptr<std::uint16_t>(y);
    for (int x = 0; x < size.width; ++x) {
      const double value = std::round(src[x] / depth_scale);
      if (!(value >= 0 && value <= 65535)) {  // also catches NaN
        throw InputError(path, "depth " + std::to_string(src[x]) + " mm at pixel (" +
                                   std::to_string(x) + ", " + std::to_string(y) +
                                   ") cannot be stored with depth_scale " +
                                   std::to_string(depth_scale) + " (16-bit PNG: 0 to " +
                                   std::to_string(65535 * depth_scale) + " mm); raise depth_scale");
      }
      dst[x] = static_cast<std::uint16_t>(value);
    }
  }
  return encoded;
}

cv::Mat mask_to_write(const cv::Mat& mask, const cv::Size& size, const std::string& path) {
  if (mask.type() != CV_8UC1 || mask.size() != size) {
    throw InputError(path, "mask is " +
                               (mask.empty() ? std::string("missing") : io_detail::describe(mask)) +
                               ", expected 8U 1-channel " + io_detail::size_text(size) +
                               " (or set write_masks off)");
  }
  return mask != 0;  // 255 on the part, 0 elsewhere, whatever non-zero value it held
}

void check_camera_and_poses(const AnnotatedImage& image, const std::string& path) {
  const DatasetCamera& camera = image.camera;
  if (!camera.K.allFinite() || !std::isfinite(camera.depth_scale) || camera.depth_scale <= 0) {
    throw InputError(path, "camera K is not finite or depth_scale is not positive");
  }
  if (!camera.extra.is_null() && !camera.extra.is_object()) {
    throw InputError(
        path, "camera extra must be a JSON object, not " + std::string(camera.extra.type_name()));
  }
  if (camera.extra.contains("cam_K") || camera.extra.contains("depth_scale")) {
    throw InputError(path, "camera extra may not name cam_K or depth_scale");
  }
  for (std::size_t gt_id = 0; gt_id < image.parts.size(); ++gt_id) {
    const PartAnnotation& part = image.parts[gt_id];
    if (!part.cam_R_m2c.allFinite() || !part.cam_t_m2c.allFinite()) {
      throw InputError(path, "pose of gt " + std::to_string(gt_id) + " is not finite");
    }
  }
}

}  // namespace

void BopWriterOptions::check() const {
  if (jpg_quality < 1 || jpg_quality > 100) {
    throw InputError("bop options",
                     "jpg_quality " + std::to_string(jpg_quality) + " is outside 1..100");
  }
}

std::string BopWriterOptions::rgb_extension() const {
  return rgb_format == RgbFormat::jpg ? "jpg" : "png";
}

std::vector<std::string> BopWriterOptions::scene_folders() const {
  std::vector<std::string> folders{"rgb"};
  if (write_depth) folders.push_back("depth");
  if (write_masks) folders.insert(folders.end(), {"mask", "mask_visib"});
  return folders;
}

BopWriter::BopWriter(std::string root, BopWriterOptions options)
    : root_(std::move(root)), options_(options) {
  options_.check();
  std::error_code ec;
  std::filesystem::create_directories(root_, ec);
  if (ec) throw InputError(root_, "cannot be created (" + ec.message() + ")");
}

void BopWriter::write(const AnnotatedImage& image) {
  const int s = image.scene_id, i = image.im_id;
  const std::string rgb_path = root_ + "/" + bop_layout::rgb_file(s, i, options_.rgb_extension());
  if (s < 0 || i < 0) throw InputError(rgb_path, "scene_id and im_id must not be negative");
  check_camera_and_poses(image, rgb_path);

  // Every file of the image, prepared (and so checked) before the first is written:
  // path and the image in cv::imwrite's channel order.
  std::vector<std::pair<std::string, cv::Mat>> files;
  if (image.rgb.type() == CV_8UC3) {
    cv::Mat bgr;
    cv::cvtColor(image.rgb, bgr, cv::COLOR_RGB2BGR);
    files.emplace_back(rgb_path, bgr);
  } else if (image.rgb.type() == CV_8UC1) {
    files.emplace_back(rgb_path, image.rgb);
  } else {
    throw InputError(rgb_path,
                     "rgb is " + io_detail::describe(image.rgb) + ", expected 8-bit RGB or gray");
  }
  const cv::Size size = image.rgb.size();
  if (options_.write_depth) {
    const std::string path = root_ + "/" + bop_layout::depth_file(s, i);
    files.emplace_back(path, encode_depth(image.depth, image.camera.depth_scale, size, path));
  }
  if (options_.write_masks) {
    for (std::size_t gt_id = 0; gt_id < image.parts.size(); ++gt_id) {
      const PartAnnotation& part = image.parts[gt_id];
      for (bool visible : {false, true}) {
        const std::string path =
            root_ + "/" + bop_layout::mask_file(s, i, static_cast<int>(gt_id), visible);
        files.emplace_back(path, mask_to_write(visible ? part.mask_visib : part.mask, size, path));
      }
    }
  }

  check_and_reserve(image);
  try {
    const std::vector<int> jpg_params{cv::IMWRITE_JPEG_QUALITY, options_.jpg_quality};
    for (const auto& [path, data] : files) {
      const bool jpg = path.size() > 4 && path.compare(path.size() - 4, 4, ".jpg") == 0;
      const bool mask = data.type() == CV_8UC1 && path.find("/rgb/") == std::string::npos;
      dataset_files::write_encoded_image(path, data,
                                         jpg ? jpg_params : (mask ? kMaskPngParams : kPngParams));
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    reserved_.erase({s, i});
    throw;
  }

  BopImageRecord record;
  record.camera = image.camera;
  // The flips go with the camera entry: a reader of poses must know the image is
  // mirrored (annotated_image.h); keys only when set, as most images have none.
  if (image.flipped_horizontally) record.camera.extra["flip_horizontal"] = true;
  if (image.flipped_vertically) record.camera.extra["flip_vertical"] = true;
  record.parts = image.parts;
  for (PartAnnotation& part : record.parts) {
    part.mask.release();  // the records stay small: masks are on disk or not kept
    part.mask_visib.release();
  }
  std::lock_guard<std::mutex> lock(mutex_);
  scenes_[s][i] = std::move(record);
}

void BopWriter::check_and_reserve(const AnnotatedImage& image) {
  const int s = image.scene_id, i = image.im_id;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) throw std::logic_error("BopWriter::write after finish()");
  if (!reserved_.insert({s, i}).second) {
    throw InputError(
        root_ + "/" + bop_layout::rgb_file(s, i, options_.rgb_extension()),
        "image " + std::to_string(i) + " of scene " + std::to_string(s) + " is written twice");
  }
  if (scene_dirs_made_.count(s)) return;
  for (const std::string& folder : options_.scene_folders()) {
    const std::string path = root_ + "/" + bop_layout::scene_dir(s) + "/" + folder;
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec) {
      reserved_.erase({s, i});
      throw InputError(path, "cannot be created (" + ec.message() + ")");
    }
  }
  scene_dirs_made_.insert(s);
}

void BopWriter::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) throw std::logic_error("BopWriter::finish called twice");
  finished_ = true;
  for (const auto& [scene_id, records] : scenes_) {
    write_bop_scene_json(root_ + "/" + bop_layout::scene_dir(scene_id), records);
  }
}

std::map<int, BopSceneRecords> BopWriter::records() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return scenes_;
}

}  // namespace flexsight

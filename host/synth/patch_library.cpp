#include "host/synth/patch_library.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/io/atomic_file.h"
#include "host/io/folder_listing.h"
#include "host/io/input_error.h"
#include "host/synth/part_library.h"

namespace flexsight {
namespace {
namespace fs = std::filesystem;

bool is_mask_file(const fs::path& path) {
  const std::string stem = path.stem().string();
  return stem.size() > 5 && stem.compare(stem.size() - 5, 5, "_mask") == 0;
}

// Reads one patch: the colour, and the mask from the alpha channel or the _mask file.
Patch read_patch(const fs::path& path, int obj_id) {
  Patch patch;
  patch.obj_id = obj_id;
  patch.source = path.string();
  const cv::Mat pixels = cv::imread(patch.source, cv::IMREAD_UNCHANGED);
  if (pixels.empty() || pixels.depth() != CV_8U) {
    throw InputError(patch.source, "cannot be decoded as an 8-bit image");
  }
  cv::Mat mask;
  const fs::path mask_path = path.parent_path() / (path.stem().string() + "_mask.png");
  if (pixels.channels() == 4) {
    cv::extractChannel(pixels, mask, 3);
  } else if (fs::exists(mask_path)) {
    mask = cv::imread(mask_path.string(), cv::IMREAD_GRAYSCALE);
    if (mask.empty()) throw InputError(mask_path.string(), "cannot be decoded as an image");
    if (mask.size() != pixels.size()) {
      throw InputError(mask_path.string(), "is not the size of " + patch.source);
    }
  } else {
    throw InputError(patch.source, "has no mask: expected an alpha channel or " +
                                       mask_path.filename().string() + " beside it");
  }
  cv::threshold(mask, mask, 127, 255, cv::THRESH_BINARY);
  const cv::Rect box = cv::boundingRect(mask);
  if (box.area() == 0) throw InputError(patch.source, "its mask is empty");
  cv::Mat rgb;
  if (pixels.channels() == 1) {
    cv::cvtColor(pixels, rgb, cv::COLOR_GRAY2RGB);
  } else {
    cv::cvtColor(pixels, rgb, pixels.channels() == 4 ? cv::COLOR_BGRA2RGB : cv::COLOR_BGR2RGB);
  }
  patch.rgb = rgb(box).clone();
  patch.mask = mask(box).clone();
  return patch;
}

}  // namespace

std::vector<Patch> load_patch_library(const std::string& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(folder, "is not a folder of patches");
  const std::vector<fs::path> files = files_with_extension_below(
      folder, {".png", ".jpg", ".jpeg"}, [](const fs::path& path) { return !is_mask_file(path); });
  std::vector<Patch> patches;
  for (const fs::path& file : files) {
    const int obj_id = object_id_from_name(file.parent_path().filename().string());
    if (obj_id < 0) {
      throw InputError(file.string(), "its folder's name holds no object id (expected "
                                      "obj_000005/ or similar)");
    }
    patches.push_back(read_patch(file, obj_id));
  }
  if (patches.empty()) {
    throw InputError(folder, "holds no patch (RGBA PNGs, or images with X_mask.png, in "
                             "folders named by object id)");
  }
  return patches;
}

std::string patch_file_name(int obj_id, int scene_id, int im_id, int gt_id) {
  char name[64];
  std::snprintf(name, sizeof name, "obj_%06d/%06d_%06d_%06d.png", obj_id, scene_id, im_id, gt_id);
  return name;
}

void write_patch(const std::string& path, const cv::Mat& rgb, const cv::Mat& mask) {
  cv::Mat bgra;
  cv::cvtColor(rgb, bgra, cv::COLOR_RGB2BGRA);
  cv::insertChannel(mask, bgra, 3);
  write_atomically(path, [&](const std::string& tmp) {
    if (!cv::imwrite(tmp, bgra)) throw InputError(path, "cannot be written as a PNG");
  });
}

}  // namespace flexsight

#include "host/synth/background_library.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

bool is_image_file(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".jpg" || ext == ".jpeg" || ext == ".png";
}

}  // namespace

BackgroundLibrary::BackgroundLibrary(const std::string& folder) {
  std::error_code error;
  if (!fs::exists(folder, error)) throw InputError(folder, "does not exist");
  if (!fs::is_directory(folder, error)) throw InputError(folder, "is not a folder");
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    if (entry.is_regular_file(error) && is_image_file(entry.path())) files.push_back(entry.path());
  }
  if (error) throw InputError(folder, "cannot be listed (" + error.message() + ")");
  if (files.empty()) throw InputError(folder, "holds no background image (.jpg, .jpeg or .png)");
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return a.filename().string() < b.filename().string();
  });
  for (const fs::path& file : files) paths_.push_back(file.string());
}

cv::Mat BackgroundLibrary::load(int index) const {
  const std::string& file = path(index);
  // IMREAD_COLOR: grey becomes three channels, alpha is dropped, 16-bit is scaled to 8.
  const cv::Mat bgr = cv::imread(file, cv::IMREAD_COLOR);
  if (bgr.empty()) throw InputError(file, "cannot be decoded as an image");
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return rgb;
}

}  // namespace flexsight

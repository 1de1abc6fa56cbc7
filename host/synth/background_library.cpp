#include "host/synth/background_library.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/io/folder_listing.h"
#include "host/io/input_error.h"

namespace flexsight {

BackgroundLibrary::BackgroundLibrary(const std::string& folder) {
  const std::vector<std::filesystem::path> files =
      files_with_extension(folder, {".jpg", ".jpeg", ".png"}, "background image");
  for (const std::filesystem::path& file : files) paths_.push_back(file.string());
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

#include "host/cli/image_inputs.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

bool has_image_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg";
}

std::vector<std::string> folder_images(const std::string& folder) {
  std::vector<std::string> images;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec) && has_image_extension(it->path())) {
      images.push_back(it->path().string());
    }
  }
  if (ec) throw InputError(folder, "cannot be listed (" + ec.message() + ")");
  if (images.empty()) throw InputError(folder, "holds no .png, .jpg or .jpeg images");
  return images;
}

}  // namespace

std::vector<std::string> list_input_images(const std::vector<std::string>& arguments) {
  std::vector<std::string> images;
  for (const std::string& argument : arguments) {
    std::error_code ec;
    if (fs::is_directory(argument, ec)) {
      const std::vector<std::string> found = folder_images(argument);
      images.insert(images.end(), found.begin(), found.end());
    } else {
      images.push_back(argument);
    }
  }
  for (const std::string& image : images) {
    io_detail::require_readable_file(image);
    if (!cv::haveImageReader(image)) {
      throw InputError(image, "is not an image OpenCV can decode (PNG, JPEG, ...)");
    }
  }
  std::sort(images.begin(), images.end());
  return images;
}

}  // namespace flexsight

#include "host/service/request_images.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

namespace flexsight {
namespace fs = std::filesystem;

RequestImages::RequestImages(const PickRequest& request) : files_(request.files), described_(request.files) {
  const std::pair<const std::string*, std::string*> given[] = {
      {&request.left_bytes, &files_.left}, {&request.right_bytes, &files_.right},
      {&request.passive_left_bytes, &files_.passive_left}};
  const char* names[] = {"left", "right", "passive_left"};
  std::string* described[] = {&described_.left, &described_.right, &described_.passive_left};
  for (int i = 0; i < 3; ++i) {
    if (given[i].first->empty()) continue;
    if (folder_.empty()) {
      std::string pattern = (fs::temp_directory_path() / "flexsight-serve-XXXXXX").string();
      if (::mkdtemp(pattern.data()) == nullptr) throw RequestError(500, "service: no temporary folder for the body's images");
      folder_ = pattern;
    }
    const std::string path = (fs::path(folder_) / (std::string(names[i]) + ".png")).string();
    std::ofstream out(path, std::ios::binary);
    out.write(given[i].first->data(), static_cast<std::streamsize>(given[i].first->size()));
    if (!out) throw RequestError(500, "service: cannot write the body's " + std::string(names[i]) + "_png");
    *given[i].second = path;
    *described[i] = "body:" + std::string(names[i]) + "_png";
  }
}

std::string RequestImages::in_request_terms(std::string message) const {
  const std::pair<const std::string*, const std::string*> names[] = {
      {&files_.left, &described_.left}, {&files_.right, &described_.right},
      {&files_.passive_left, &described_.passive_left}};
  for (const auto& [file, described] : names) {
    if (file->empty() || *file == *described) continue;
    for (std::size_t at = message.find(*file); at != std::string::npos; at = message.find(*file, at)) {
      message.replace(at, file->size(), *described);
    }
  }
  return message;
}

RequestImages::~RequestImages() {
  std::error_code ignored;
  if (!folder_.empty()) fs::remove_all(folder_, ignored);
}

}  // namespace flexsight

#pragma once
// The photographs that go behind the parts: every .jpg, .jpeg and .png of a folder,
// listed once and decoded when an image needs one (300 BSDS photographs would take
// about 140 MB decoded; one JPEG of 481x321 decodes in about a millisecond).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace flexsight {

class BackgroundLibrary {
 public:
  // The image files directly in `folder` (extension in any letter case), sorted by file
  // name. Throws InputError naming the folder when it is missing, not a folder, or holds
  // no image file. Files are not opened here.
  explicit BackgroundLibrary(const std::string& folder);

  int size() const { return static_cast<int>(paths_.size()); }
  const std::string& path(int index) const { return paths_.at(index); }
  // Image `index` decoded, CV_8UC3 in RGB order (grey and alpha images converted).
  // Thread-safe. Throws InputError naming the file when it cannot be decoded.
  cv::Mat load(int index) const;

 private:
  std::vector<std::string> paths_;
};

}  // namespace flexsight

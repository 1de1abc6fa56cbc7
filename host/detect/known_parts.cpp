#include "host/detect/known_parts.h"

#include <algorithm>

#include "host/io/input_error.h"
#include "host/io/object_ids.h"

namespace flexsight {

bool KnownParts::contains(int obj_id) const {
  return every_part() || std::binary_search(obj_ids.begin(), obj_ids.end(), obj_id);
}

KnownParts parse_known_parts(const std::string& text, const std::string& option) {
  return {parse_object_ids(text, option)};
}

std::vector<int> known_part_classes(const KnownParts& parts, const std::vector<DetectorLabel>& labels,
                                    const std::string& model, const std::string& option) {
  std::vector<int> classes;
  for (int id : parts.obj_ids) {
    const auto label = std::find_if(labels.begin(), labels.end(),
                                    [&](const DetectorLabel& l) { return l.category_id == id; });
    if (label == labels.end()) {
      throw InputError("option " + option, "object " + std::to_string(id) + " is not a class of the detector " + model);
    }
    classes.push_back(static_cast<int>(label - labels.begin()));
  }
  std::sort(classes.begin(), classes.end());
  return classes;
}

cv::Mat known_part_logits(const cv::Mat& class_logits, const std::vector<int>& classes) {
  cv::Mat kept(class_logits.rows, static_cast<int>(classes.size()) + 1, CV_32F);
  class_logits.col(0).copyTo(kept.col(0));
  for (std::size_t k = 0; k < classes.size(); ++k) {
    class_logits.col(classes[k] + 1).copyTo(kept.col(static_cast<int>(k) + 1));
  }
  return kept;
}

}  // namespace flexsight

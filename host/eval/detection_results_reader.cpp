#include "host/eval/detection_results_reader.h"

#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"
#include "host/io/physical_checks.h"

namespace flexsight {
namespace {

using Json = nlohmann::json;

// Python's json.dump writes float("nan") and float("inf") as the bare words NaN,
// Infinity and -Infinity, which no JSON parser takes. Quoted, they parse, and the checks
// below can name the entry and key that holds one instead of a line and column.
std::string quote_non_finite_words(const std::string& text) {
  static const char* const kWords[] = {"-Infinity", "Infinity", "-NaN", "NaN"};
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') in_string = true;
    const char* word = nullptr;
    for (const char* candidate : kWords) {
      if (text.compare(i, std::strlen(candidate), candidate) == 0) {
        word = candidate;
        break;
      }
    }
    if (word) {
      out += '"' + std::string(word) + '"';
      i += std::strlen(word) - 1;
    } else {
      out += c;
    }
  }
  return out;
}

Json parse_results(const std::string& path) {
  return dataset_files::parse_json(quote_non_finite_words(io_detail::read_whole_file(path)), path);
}

class EntryReader {
 public:
  EntryReader(const std::string& path, const Json& entry, std::size_t index)
      : path_(path), entry_(entry), where_("entry " + std::to_string(index)) {
    if (!entry.is_object()) fail("expected an object, found " + std::string(entry.type_name()));
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_, where_ + ": " + problem);
  }

  const Json& key(const char* name) const {
    return dataset_files::require_key(entry_, name, path_, where_);
  }

  long long integer(const char* name) const {
    return dataset_files::to_integer(key(name), path_, where_ + ": " + name);
  }

  int int_value(const char* name) const {
    return dataset_files::to_int(key(name), path_, where_ + ": " + name);
  }

  // A number; the quoted NaN and Infinity words get their own message.
  double number(const Json& value, const std::string& name) const {
    if (value.is_string()) {
      const std::string word = value.get<std::string>();
      if (word.find("NaN") != std::string::npos || word.find("Infinity") != std::string::npos) {
        fail(name + " is " + word + ", not a number");
      }
    }
    if (!value.is_number()) {
      fail(name + ": expected a number, found " + value.type_name() + " " + value.dump());
    }
    const double result = value.get<double>();
    if (!std::isfinite(result)) fail(name + " is not finite");
    return result;
  }

  BoxXywh bbox() const {
    const Json& value = key("bbox");
    if (!value.is_array() || value.size() != 4) {
      fail("bbox: expected [x, y, width, height], found " + value.dump());
    }
    BoxXywh box;
    for (std::size_t k = 0; k < 4; ++k) box[k] = number(value[k], "bbox[" + std::to_string(k) + "]");
    if (box[2] < 0 || box[3] < 0) {
      fail("bbox " + value.dump() +
           " has a negative width or height (expected x, y, width, height, not corners)");
    }
    for (std::size_t k = 0; k < 4; ++k) {
      if (std::fabs(box[k]) > physical_checks::kMaxBoxPx) {
        fail("bbox " + value.dump() + " reaches beyond " +
             physical_checks::number_text(physical_checks::kMaxBoxPx) + " pixels");
      }
    }
    return box;
  }

  double score() const {
    const double value = number(key("score"), "score");
    if (value < 0 || value > 1) fail("score " + key("score").dump() + " is outside [0, 1]");
    return value;
  }

  bool has(const char* name) const { return entry_.contains(name); }

 private:
  const std::string& path_;
  const Json& entry_;
  std::string where_;
};

std::string id_list(const std::vector<DetectionCategory>& categories) {
  std::string text;
  for (const DetectionCategory& category : categories) {
    text += (text.empty() ? "" : ", ") + std::to_string(category.id);
  }
  return text.empty() ? "none" : text;
}

}  // namespace

DetectionResults read_detection_results(const std::string& path, const DetectionGroundTruth& truth) {
  const Json root = parse_results(path);
  if (!root.is_array()) {
    throw InputError(path, std::string("must be a JSON list of detections, found ") +
                               root.type_name());
  }
  DetectionResults results;
  results.source = path;
  results.per_image.resize(truth.images().size());
  if (root.empty()) {
    results.format = "empty";
    return results;
  }
  std::map<std::int64_t, std::size_t> by_coco_id;
  std::map<std::pair<int, int>, std::size_t> by_bop_ids;
  for (std::size_t i = 0; i < truth.images().size(); ++i) {
    const DetectionImage& image = truth.images()[i];
    if (truth.format() == DetectionGroundTruth::Format::coco) by_coco_id[image.coco_id] = i;
    if (image.scene_id >= 0 && image.im_id >= 0) by_bop_ids[{image.scene_id, image.im_id}] = i;
  }
  std::set<int> known_categories;
  for (const DetectionCategory& category : truth.categories()) known_categories.insert(category.id);

  const bool bop_form = root[0].is_object() && root[0].contains("scene_id");
  results.format = bop_form ? "BOP results" : "COCO results";
  for (std::size_t index = 0; index < root.size(); ++index) {
    const EntryReader entry(path, root[index], index);
    if (entry.has("scene_id") != bop_form) {
      entry.fail(bop_form ? "has no scene_id, but entry 0 has (BOP results); one form per file"
                          : "has a scene_id, but entry 0 has none (COCO results); one form per file");
    }
    std::size_t image = 0;
    if (bop_form) {
      const int scene_id = entry.int_value("scene_id");
      const int im_id = entry.int_value("image_id");
      if (by_bop_ids.empty()) {
        entry.fail("BOP results name images by scene_id and im_id, which " + truth.source() +
                   " does not record; give COCO results (image_id = its image id)");
      }
      const auto found = by_bop_ids.find({scene_id, im_id});
      if (found == by_bop_ids.end()) {
        entry.fail("scene_id " + std::to_string(scene_id) + ", image_id (im_id) " +
                   std::to_string(im_id) + " is not an image of " + truth.source());
      }
      image = found->second;
    } else {
      const long long image_id = entry.integer("image_id");
      if (truth.format() == DetectionGroundTruth::Format::bop) {
        entry.fail("COCO results (no scene_id) name images by COCO image id, and " +
                   truth.source() +
                   " is a BOP folder; give BOP results (scene_id, image_id = im_id) or "
                   "evaluate against a COCO file");
      }
      const auto found = by_coco_id.find(image_id);
      if (found == by_coco_id.end()) {
        entry.fail("image_id " + std::to_string(image_id) + " is not an image of " + truth.source());
      }
      image = found->second;
    }
    DetectedBox box;
    box.category_id = entry.int_value("category_id");
    if (known_categories.count(box.category_id) == 0) {
      entry.fail("category_id " + std::to_string(box.category_id) + " is not a category of " +
                 truth.source() + " (its ids: " + id_list(truth.categories()) + ")");
    }
    box.bbox = entry.bbox();
    box.score = entry.score();
    results.per_image[image].push_back(box);
  }
  return results;
}

}  // namespace flexsight

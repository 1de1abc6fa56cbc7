#include "host/cli/detection_outputs.h"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

// The double nearest the shortest decimal of `value` (nlohmann prints doubles in their
// shortest form, so 0.9f is written "0.9", not "0.8999999761581421").
double json_float(float value) {
  char text[32];
  const std::to_chars_result end = std::to_chars(text, text + sizeof text, value);
  double exact = 0.0;
  std::from_chars(text, end.ptr, exact);
  return exact;
}

nlohmann::ordered_json coco_result(const ImageDetections& image, const ObjectDetection& d) {
  nlohmann::ordered_json json;
  json["image_id"] = image.image_id;
  json["category_id"] = d.category_id;
  json["bbox"] = {json_float(d.box[0]), json_float(d.box[1]), json_float(d.box[2] - d.box[0]),
                  json_float(d.box[3] - d.box[1])};
  json["score"] = json_float(d.score);
  json["file_name"] = image.file;
  return json;
}

}  // namespace

std::string coco_results_text(const std::vector<ImageDetections>& images) {
  std::string text = "[";
  bool first = true;
  for (const ImageDetections& image : images) {
    for (const ObjectDetection& d : image.found) {
      text += first ? "\n" : ",\n";
      text += coco_result(image, d).dump();
      first = false;
    }
  }
  return text + (first ? "]\n" : "\n]\n");
}

void write_coco_results(const std::string& path, const std::vector<ImageDetections>& images) {
  const std::string text = coco_results_text(images);
  write_atomically(path, [&text](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary);
    if (!out) throw InputError(tmp_path, "cannot be created");
    out << text;
    out.close();
    if (!out) throw InputError(tmp_path, "cannot be written");
  });
}

std::string detection_table(const std::vector<ImageDetections>& images,
                            const std::vector<DetectorLabel>& labels) {
  std::map<int, std::string> names;
  for (const DetectorLabel& label : labels) names[label.category_id] = label.name;
  std::ostringstream table;
  char row[256];
  for (const ImageDetections& image : images) {
    std::snprintf(row, sizeof row, "image %d: %s (%dx%d): %zu detection%s\n", image.image_id,
                  image.file.c_str(), image.width, image.height, image.found.size(),
                  image.found.size() == 1 ? "" : "s");
    table << row;
    if (image.found.empty()) continue;
    table << "  category  name                  score        x        y    width   height\n";
    for (const ObjectDetection& d : image.found) {
      std::snprintf(row, sizeof row, "  %8d  %-20.20s  %5.3f  %7.1f  %7.1f  %7.1f  %7.1f\n",
                    d.category_id, names[d.category_id].c_str(), d.score, d.box[0], d.box[1],
                    d.box[2] - d.box[0], d.box[3] - d.box[1]);
      table << row;
    }
  }
  return table.str();
}

}  // namespace flexsight

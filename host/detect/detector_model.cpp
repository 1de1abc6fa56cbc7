#include "host/detect/detector_model.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

std::string trimmed(std::string text) {
  const char* const space = " \t\r";
  text.erase(0, std::min(text.find_first_not_of(space), text.size()));
  text.erase(text.find_last_not_of(space) + 1);
  return text;
}

// A whole decimal integer (optionally signed) that fits an int; false otherwise.
bool parse_int(const std::string& text, int& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long long parsed = std::strtoll(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || parsed < -2147483647LL || parsed > 2147483647LL) {
    return false;
  }
  value = static_cast<int>(parsed);
  return true;
}

float positive_scale(const std::string& path, const nlohmann::json& value) {
  if (value.is_number()) {
    const double number = value.get<double>();
    if (std::isfinite(number) && number > 0.0) return static_cast<float>(number);
  }
  throw InputError(path,
                   "\"box_scale\" must be 4 positive numbers (y, x, h, w), got " + value.dump());
}

}  // namespace

DetectorFiles detector_files(const std::string& model_path) {
  const fs::path folder = fs::path(model_path).parent_path();
  DetectorFiles files;
  files.model = model_path;
  files.anchors = (folder / "anchors.csv").string();
  files.labels = (folder / "labels.txt").string();
  files.settings = (folder / "model.json").string();
  return files;
}

DetectorSettings read_detector_settings(const std::string& path) {
  DetectorSettings settings;
  std::error_code ec;
  if (!fs::exists(path, ec)) return settings;
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(io_detail::read_whole_file(path));
  } catch (const nlohmann::json::exception& error) {
    throw InputError(path, std::string("is not valid JSON: ") + error.what());
  }
  if (!json.is_object()) throw InputError(path, "must hold a JSON object");

  if (json.contains("score_function")) {
    const nlohmann::json& value = json["score_function"];
    if (!value.is_string()) {
      throw InputError(
          path, "\"score_function\" must be \"softmax\" or \"sigmoid\", got " + value.dump());
    }
    settings.score_function =
        parse_score_function(value.get<std::string>(), path + ": \"score_function\"");
  }
  if (json.contains("input_size")) {
    const nlohmann::json& value = json["input_size"];
    if (!value.is_number_integer() || value.get<long long>() < 1 || value.get<long long>() > 4096) {
      throw InputError(
          path, "\"input_size\" must be a whole number of pixels in 1..4096, got " + value.dump());
    }
    settings.input_size = value.get<int>();
  }
  // The detector scales to [-1, 1] in RGB order, nothing else: a model that wants another
  // input is refused rather than fed the wrong one.
  if (json.contains("input_range")) {
    const nlohmann::json& value = json["input_range"];
    if (value != nlohmann::json::array({-1, 1})) {
      throw InputError(path, "\"input_range\" " + value.dump() +
                                 " is not supported: the detector scales pixels to [-1, 1]");
    }
  }
  if (json.contains("color_order")) {
    const nlohmann::json& value = json["color_order"];
    if (value != "rgb") {
      throw InputError(path, "\"color_order\" " + value.dump() +
                                 " is not supported: the detector feeds \"rgb\"");
    }
  }
  if (json.contains("box_scale")) {
    const nlohmann::json& value = json["box_scale"];
    if (!value.is_array() || value.size() != 4) {
      throw InputError(
          path, "\"box_scale\" must be 4 positive numbers (y, x, h, w), got " + value.dump());
    }
    settings.box_scale = {positive_scale(path, value[0]), positive_scale(path, value[1]),
                          positive_scale(path, value[2]), positive_scale(path, value[3])};
  }
  return settings;
}

std::vector<DetectorLabel> read_detector_labels(const std::string& path) {
  std::istringstream text(io_detail::read_whole_file(path));
  std::vector<DetectorLabel> labels;
  std::set<int> category_ids;
  std::string line;
  int line_number = 0;
  int next_index = 0;
  while (std::getline(text, line)) {
    ++line_number;
    line = trimmed(line);
    if (line.empty()) continue;
    const std::string where = "line " + std::to_string(line_number) + ": ";
    // INDEX CATEGORY_ID NAME, the name being the rest of the line (it may hold spaces).
    const size_t first_end = line.find_first_of(" \t");
    const size_t second_start =
        first_end == std::string::npos ? first_end : line.find_first_not_of(" \t", first_end);
    const size_t second_end =
        second_start == std::string::npos ? second_start : line.find_first_of(" \t", second_start);
    int index = 0;
    DetectorLabel label;
    if (second_end == std::string::npos || !parse_int(line.substr(0, first_end), index) ||
        !parse_int(line.substr(second_start, second_end - second_start), label.category_id)) {
      throw InputError(path, where + "expected 'INDEX CATEGORY_ID NAME', got '" + line + "'");
    }
    label.name = trimmed(line.substr(second_end));
    if (index != next_index) {
      throw InputError(path, where + "expected index " + std::to_string(next_index) +
                                 " (indices run 0, 1, 2, ... with 0 the background), got " +
                                 std::to_string(index));
    }
    ++next_index;
    if (index == 0) continue;  // the background
    if (!category_ids.insert(label.category_id).second) {
      throw InputError(path, where + "category id " + std::to_string(label.category_id) +
                                 " is given to two classes");
    }
    labels.push_back(label);
  }
  if (next_index == 0) throw InputError(path, "holds no labels");
  return labels;
}

std::string default_detector_model_path() {
  const char* environment = std::getenv("FLEXSIGHT_DETECT_MODEL");
  if (environment != nullptr && *environment != '\0') return environment;
  return FLEXSIGHT_DEFAULT_DETECT_MODEL;
}

bool default_detector_model_from_environment() {
  const char* environment = std::getenv("FLEXSIGHT_DETECT_MODEL");
  return environment != nullptr && *environment != '\0';
}

std::string resolve_detector_model_path(const std::string& given) {
  if (!given.empty()) return given;
  const std::string path = default_detector_model_path();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    if (default_detector_model_from_environment()) {
      throw InputError(path,
                       "does not exist (FLEXSIGHT_DETECT_MODEL names it as the default "
                       "model); set it to a model.onnx or pass --model M.onnx");
    }
    throw InputError(path,
                     "the default detector model does not exist (the shipped T-LESS "
                     "model is not in this checkout); pass --model M.onnx or set "
                     "FLEXSIGHT_DETECT_MODEL");
  }
  return path;
}

}  // namespace flexsight

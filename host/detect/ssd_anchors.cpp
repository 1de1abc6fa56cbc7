#include "host/detect/ssd_anchors.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

const char* const kHeader = "ycenter,xcenter,height,width";

struct BoxSpec {
  float scale;
  float aspect_ratio;
};

std::vector<std::vector<BoxSpec>> box_specs(const SsdAnchorConfig& config) {
  const int layers = static_cast<int>(config.feature_maps.size());
  // TF computes the scales in Python doubles, then uses them as float32.
  std::vector<double> scales;
  for (int i = 0; i < layers; ++i) {
    scales.push_back(layers == 1 ? config.min_scale
                                 : config.min_scale + (static_cast<double>(config.max_scale) -
                                                       config.min_scale) *
                                                          i / (layers - 1));
  }
  scales.push_back(1.0);
  std::vector<std::vector<BoxSpec>> specs(layers);
  for (int layer = 0; layer < layers; ++layer) {
    const float scale = static_cast<float>(scales[layer]);
    if (layer == 0 && config.reduce_boxes_in_lowest_layer) {
      specs[layer] = {{0.1f, 1.0f}, {scale, 2.0f}, {scale, 0.5f}};
      continue;
    }
    for (float ratio : config.aspect_ratios) specs[layer].push_back({scale, ratio});
    if (config.interpolated_scale_aspect_ratio > 0.0f) {
      specs[layer].push_back({static_cast<float>(std::sqrt(scales[layer] * scales[layer + 1])),
                              config.interpolated_scale_aspect_ratio});
    }
  }
  return specs;
}

std::string line_text(const std::string& line) {
  return line.size() <= 60 ? line : line.substr(0, 57) + "...";
}

// The four numbers of a data line, or an InputError naming the file and line.
void parse_anchor_line(const std::string& path, int line_number, const std::string& line,
                       float values[4]) {
  const std::string where = "line " + std::to_string(line_number) + ": ";
  const char* cursor = line.c_str();
  for (int k = 0; k < 4; ++k) {
    char* end = nullptr;
    errno = 0;
    values[k] = std::strtof(cursor, &end);
    if (end == cursor || errno == ERANGE) {
      throw InputError(path, where + "expected 4 comma-separated numbers (" + kHeader +
                                 "), got '" + line_text(line) + "'");
    }
    cursor = end;
    while (*cursor == ' ' || *cursor == '\t') ++cursor;
    const char expected = k < 3 ? ',' : '\0';
    if (*cursor != expected) {
      throw InputError(path, where + "expected 4 comma-separated numbers (" + kHeader +
                                 "), got '" + line_text(line) + "'");
    }
    if (k < 3) ++cursor;
  }
  for (int k = 0; k < 4; ++k) {
    if (!std::isfinite(values[k])) {
      throw InputError(path, where + "values must be finite, got '" + line_text(line) + "'");
    }
  }
  if (!(values[2] > 0.0f) || !(values[3] > 0.0f)) {
    throw InputError(path, where + "height and width must be positive, got '" +
                               line_text(line) + "'");
  }
}

std::string trimmed(std::string line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) {
    line.pop_back();
  }
  return line;
}

}  // namespace

std::vector<float> generate_ssd_anchors(const SsdAnchorConfig& config) {
  std::vector<float> anchors;
  const std::vector<std::vector<BoxSpec>> specs = box_specs(config);
  for (size_t layer = 0; layer < specs.size(); ++layer) {
    const int side = config.feature_maps[layer];
    // tile_anchors: stride 1 / side and offset half a stride, in float32.
    const float stride = 1.0f / static_cast<float>(side);
    const float offset = 0.5f * stride;
    for (int row = 0; row < side; ++row) {
      const float ycenter = static_cast<float>(row) * stride + offset;
      for (int column = 0; column < side; ++column) {
        const float xcenter = static_cast<float>(column) * stride + offset;
        for (const BoxSpec& spec : specs[layer]) {
          const float ratio_sqrt = std::sqrt(spec.aspect_ratio);
          anchors.push_back(ycenter);
          anchors.push_back(xcenter);
          anchors.push_back(spec.scale / ratio_sqrt);
          anchors.push_back(spec.scale * ratio_sqrt);
        }
      }
    }
  }
  return anchors;
}

std::vector<float> read_anchor_file(const std::string& path, int expected_count) {
  std::istringstream text(io_detail::read_whole_file(path));
  std::string line;
  if (!std::getline(text, line) || trimmed(line) != kHeader) {
    throw InputError(path, std::string("is not an anchors file: its first line must be '") +
                               kHeader + "', got '" + line_text(trimmed(line)) + "'");
  }
  std::vector<float> anchors;
  int line_number = 1;
  while (std::getline(text, line)) {
    ++line_number;
    line = trimmed(line);
    if (line.empty()) continue;
    float values[4];
    parse_anchor_line(path, line_number, line, values);
    anchors.insert(anchors.end(), values, values + 4);
  }
  const int count = static_cast<int>(anchors.size() / 4);
  if (count == 0) throw InputError(path, "holds no anchors");
  if (expected_count > 0 && count != expected_count) {
    throw InputError(path, "holds " + std::to_string(count) + " anchors, the model outputs " +
                               std::to_string(expected_count) + " boxes");
  }
  return anchors;
}

void write_anchor_file(const std::string& path, const std::vector<float>& anchors) {
  write_atomically(path, [&anchors](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary);
    if (!out) throw InputError(tmp_path, "cannot be created");
    out << kHeader << '\n';
    char line[128];
    for (size_t i = 0; i + 3 < anchors.size(); i += 4) {
      std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g\n", anchors[i], anchors[i + 1],
                    anchors[i + 2], anchors[i + 3]);
      out << line;
    }
    out.close();
    if (!out) throw InputError(tmp_path, "cannot be written");
  });
}

}  // namespace flexsight

#include "host/io/calibration.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "host/io/image_header.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

std::string trim(std::string_view text) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return std::string(text);
}

// Lines without their terminator; handles "\n" and "\r\n" files alike.
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> split_whitespace(const std::string& text) {
  std::vector<std::string> tokens;
  std::istringstream in(text);
  for (std::string token; in >> token;) tokens.push_back(token);
  return tokens;
}

// Locale-independent and strict: the whole token must be one finite number.
bool parse_double(std::string_view token, double& value) {
  if (token.size() > 1 && token.front() == '+') token.remove_prefix(1);  // from_chars rejects '+'
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

bool parse_int(std::string_view token, int& value) {
  if (token.size() > 1 && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// Long lines (or a binary file read by mistake) are cut short in messages.
std::string quoted(const std::string& text) {
  return "'" + (text.size() > 60 ? text.substr(0, 60) + "..." : text) + "'";
}

// ---- Middlebury calib.txt: one "key=value" per line --------------------------------

class MiddleburyFields {
 public:
  explicit MiddleburyFields(const std::string& path) : path_(path) {
    const std::vector<std::string> lines = split_lines(io_detail::read_whole_file(path));
    for (std::size_t i = 0; i < lines.size(); ++i) add_line(lines[i], i + 1);
  }

  bool has(const std::string& key) const { return values_.count(key) != 0; }

  bool has_prefix(const std::string& prefix) const {
    const auto it = values_.lower_bound(prefix);
    return it != values_.end() && it->first.compare(0, prefix.size(), prefix) == 0;
  }

  const std::string& text(const std::string& key) const { return required(key); }
  const std::string& path() const { return path_; }

  // "[x y z]"
  std::array<double, 3> vector3(const std::string& key) const {
    const std::string& text = required(key);
    const auto malformed = [&] { fail(key, "is not a vector like [x y z]: " + quoted(text)); };
    if (text.size() < 2 || text.front() != '[' || text.back() != ']') malformed();
    const std::vector<std::string> tokens = split_whitespace(text.substr(1, text.size() - 2));
    if (tokens.size() != 3) malformed();
    std::array<double, 3> v{};
    for (int i = 0; i < 3; ++i) {
      if (!parse_double(tokens[i], v[i])) malformed();
    }
    return v;
  }

  double number(const std::string& key) const {
    double value = 0;
    if (!parse_double(required(key), value)) fail(key, "is not a number: " + quoted(required(key)));
    return value;
  }

  int integer(const std::string& key) const {
    int value = 0;
    if (!parse_int(required(key), value)) {
      fail(key, "is not an integer: " + quoted(required(key)));
    }
    return value;
  }

  // "[f 0 cx; 0 f cy; 0 0 1]" -> row-major 3x3.
  std::array<double, 9> matrix3x3(const std::string& key) const {
    const std::string& text = required(key);
    const auto malformed = [&] {
      fail(key, "is not a 3x3 matrix like [f 0 cx; 0 f cy; 0 0 1]: " + quoted(text));
    };
    if (text.size() < 2 || text.front() != '[' || text.back() != ']') malformed();

    std::array<double, 9> m{};
    std::size_t count = 0;
    std::istringstream rows(text.substr(1, text.size() - 2));
    std::size_t row_count = 0;
    for (std::string row; std::getline(rows, row, ';'); ++row_count) {
      const std::vector<std::string> tokens = split_whitespace(row);
      if (row_count >= 3 || tokens.size() != 3) malformed();
      for (const std::string& token : tokens) {
        if (!parse_double(token, m[count++])) malformed();
      }
    }
    if (count != 9) malformed();
    return m;
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(path_, "key '" + key + "' " + problem);
  }

 private:
  void add_line(const std::string& raw, std::size_t number) {
    const std::string line = trim(raw);
    if (line.empty() || line.front() == '#') return;
    const std::size_t eq = line.find('=');
    const std::string key = eq == std::string::npos ? "" : trim(line.substr(0, eq));
    if (key.empty()) {
      throw InputError(path_,
                       "line " + std::to_string(number) + " is not 'key=value': " + quoted(line));
    }
    if (!values_.emplace(key, trim(line.substr(eq + 1))).second) {
      throw InputError(path_, "key '" + key + "' appears more than once");
    }
  }

  const std::string& required(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) throw InputError(path_, "missing key '" + key + "'");
    return it->second;
  }

  std::string path_;
  std::map<std::string, std::string> values_;
};

void require_positive_focal(const MiddleburyFields& fields, const std::string& key,
                            const std::array<double, 9>& cam) {
  if (!(cam[0] > 0) || !(cam[4] > 0)) fields.fail(key, "has a focal length <= 0");
}

std::string number_text(double value) {
  std::ostringstream text;
  text << value;  // "0", "-3.5", "1e+300": shortest readable form, unlike std::to_string
  return text.str();
}

// What makes two pinhole matrices a rectified pair as the matcher and the 3D code use
// it: [f 0 cx; 0 f cy; 0 0 1] each, the same f (square pixels), the same row of the
// principal point, and doffs = cx1 - cx0 (Middlebury's convention). Anything else would
// be read silently as something it is not.
constexpr double kFocalTolerance = 1e-4;  // relative: files print 3-7 digits
constexpr double kPixelTolerance = 0.5;   // px

void require_rectified_pair(const MiddleburyFields& fields, const MiddleburyCalib& calib) {
  for (const auto& [key, cam] : {std::pair{"cam0", &calib.cam0}, std::pair{"cam1", &calib.cam1}}) {
    const std::array<double, 9>& m = *cam;
    for (double v : m) {
      if (!std::isfinite(v)) fields.fail(key, "has a value that is not finite");
    }
    if (m[1] != 0 || m[3] != 0 || m[6] != 0 || m[7] != 0 || m[8] != 1) {
      fields.fail(key, "is not a pinhole matrix [f 0 cx; 0 f cy; 0 0 1]");
    }
    if (std::abs(m[0] - m[4]) > kFocalTolerance * m[0]) {
      fields.fail(key, "has fx " + number_text(m[0]) + " and fy " + number_text(m[4]) +
                           ": only square pixels are supported");
    }
  }
  if (std::abs(calib.cam0[0] - calib.cam1[0]) > kFocalTolerance * calib.cam0[0]) {
    fields.fail("cam1", "has focal length " + number_text(calib.cam1[0]) + ", cam0 " + number_text(calib.cam0[0]) +
                            ": the cameras of a rectified pair have the same focal length");
  }
  if (std::abs(calib.cam0[5] - calib.cam1[5]) > kPixelTolerance) {
    fields.fail("cam1", "has its principal point on row " + number_text(calib.cam1[5]) + ", cam0 on row " +
                            number_text(calib.cam0[5]) + ": the rows of a rectified pair match");
  }
  const double shift = calib.cam1[2] - calib.cam0[2];
  if (!std::isfinite(calib.doffs) || std::abs(calib.doffs - shift) > kPixelTolerance) {
    fields.fail("doffs", "is " + number_text(calib.doffs) + ", but cam1's cx - cam0's cx is " + number_text(shift) +
                             " (doffs is the difference of the principal points)");
  }
}

void require_positive(const MiddleburyFields& fields, const std::string& key, double value) {
  if (!(value > 0)) {
    fields.fail(key, "must be positive, got " + number_text(value));
  }
}

// ---- The projector's optional lines ------------------------------------------------

constexpr double kRotationTolerance = 1e-3;

void require_rotation(const MiddleburyFields& fields, const std::array<double, 9>& R) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += R[3 * i + k] * R[3 * j + k];
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > kRotationTolerance) {
        fields.fail("projR", "is not a rotation (its rows are not orthonormal)");
      }
    }
  }
  const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                     R[2] * (R[3] * R[7] - R[4] * R[6]);
  if (det < 0) fields.fail("projR", "is a reflection, not a rotation");
}

ProjectorCalib read_projector(const MiddleburyFields& fields) {
  ProjectorCalib projector;
  for (const char* key : {"proj", "projwidth", "projheight", "projt", "projpattern"}) {
    if (!fields.has(key)) {
      throw InputError(fields.path(), std::string("missing key '") + key +
                                          "' (the projector entry needs proj, projwidth, projheight, projt, "
                                          "projpattern)");
    }
  }
  projector.K = fields.matrix3x3("proj");
  projector.width = fields.integer("projwidth");
  projector.height = fields.integer("projheight");
  projector.t = fields.vector3("projt");
  if (fields.has("projR")) projector.R = fields.matrix3x3("projR");
  projector.pattern = fields.text("projpattern");
  require_positive(fields, "projwidth", projector.width);
  require_positive(fields, "projheight", projector.height);
  const std::array<double, 9>& K = projector.K;
  if (K[1] != 0 || K[3] != 0 || K[6] != 0 || K[7] != 0 || K[8] != 1 || !(K[0] > 0) || !(K[4] > 0)) {
    fields.fail("proj", "is not a pinhole matrix [fx 0 cx; 0 fy cy; 0 0 1] with positive focal lengths");
  }
  if (!(K[2] >= 0 && K[2] <= projector.width) || !(K[5] >= 0 && K[5] <= projector.height)) {
    fields.fail("proj", "has its principal point (" + number_text(K[2]) + ", " + number_text(K[5]) +
                            ") outside the " + std::to_string(projector.width) + "x" +
                            std::to_string(projector.height) + " pattern");
  }
  require_rotation(fields, projector.R);

  const std::filesystem::path pattern(projector.pattern);
  projector.pattern_path = (pattern.is_absolute() ? pattern
                                                  : std::filesystem::path(fields.path()).parent_path() / pattern)
                               .string();
  const cv::Size size = image_size_from_header(projector.pattern_path);  // names the file
  if (size.width != projector.width || size.height != projector.height) {
    throw InputError(projector.pattern_path,
                     "is " + std::to_string(size.width) + "x" + std::to_string(size.height) + ", but " +
                         fields.path() + " gives the projector " + std::to_string(projector.width) + "x" +
                         std::to_string(projector.height) + " (projwidth, projheight)");
  }
  return projector;
}

// ---- KITTI calibration: "NAME: n1 n2 ..." per line ----------------------------------

struct KittiMatrixName {
  const char* kitti2012;  // "P0"
  const char* rectified;  // "P_rect_00"
};

// Returns the 12 numbers of the line named `name` (either spelling), or throws.
std::array<double, 12> kitti_matrix(const std::vector<std::string>& lines,
                                    const KittiMatrixName& name, const std::string& path) {
  bool found = false;
  std::array<double, 12> p{};
  for (const std::string& line : lines) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim(line.substr(0, colon));
    if (key != name.kitti2012 && key != name.rectified) continue;
    if (found) throw InputError(path, "'" + key + "' is defined more than once");
    found = true;

    const std::vector<std::string> tokens = split_whitespace(line.substr(colon + 1));
    if (tokens.size() != 12) {
      throw InputError(path, "line '" + key + "' has " + std::to_string(tokens.size()) +
                                 " numbers (expected 12 for a 3x4 projection matrix)");
    }
    for (std::size_t i = 0; i < 12; ++i) {
      if (!parse_double(tokens[i], p[i])) {
        throw InputError(path, "line '" + key + "' has a malformed number " + quoted(tokens[i]));
      }
    }
    if (!(p[0] > 0)) throw InputError(path, "line '" + key + "' has a focal length <= 0");
  }
  if (!found) {
    throw InputError(path, std::string("missing '") + name.kitti2012 + "' (or '" + name.rectified +
                               "') projection matrix");
  }
  return p;
}

}  // namespace

MiddleburyCalib read_middlebury_calib(const std::string& path) {
  const MiddleburyFields fields(path);
  MiddleburyCalib calib;
  calib.cam0 = fields.matrix3x3("cam0");
  calib.cam1 = fields.matrix3x3("cam1");
  calib.doffs = fields.number("doffs");
  calib.baseline_mm = fields.number("baseline");
  calib.width = fields.integer("width");
  calib.height = fields.integer("height");
  calib.ndisp = fields.integer("ndisp");
  if (fields.has("vmin")) calib.vmin = fields.integer("vmin");
  if (fields.has("vmax")) calib.vmax = fields.integer("vmax");

  require_positive_focal(fields, "cam0", calib.cam0);
  require_positive_focal(fields, "cam1", calib.cam1);
  require_positive(fields, "baseline", calib.baseline_mm);
  require_positive(fields, "width", calib.width);
  require_positive(fields, "height", calib.height);
  require_positive(fields, "ndisp", calib.ndisp);
  require_rectified_pair(fields, calib);
  if (fields.has_prefix("proj")) calib.projector = read_projector(fields);
  return calib;
}

std::string projector_calib_text(const ProjectorCalib& p) {
  char text[640];
  std::snprintf(text, sizeof text,
                "proj=[%.3f 0 %.3f; 0 %.3f %.3f; 0 0 1]\nprojwidth=%d\nprojheight=%d\n"
                "projR=[%.9g %.9g %.9g; %.9g %.9g %.9g; %.9g %.9g %.9g]\nprojt=[%.3f %.3f %.3f]\n",
                p.K[0], p.K[2], p.K[4], p.K[5], p.width, p.height, p.R[0], p.R[1], p.R[2], p.R[3], p.R[4],
                p.R[5], p.R[6], p.R[7], p.R[8], p.t[0], p.t[1], p.t[2]);
  return std::string(text) + "projpattern=" + p.pattern + "\n";
}

std::string calib_text_without_projector(const std::string& path) {
  std::string text;
  for (const std::string& line : split_lines(io_detail::read_whole_file(path))) {
    if (line.rfind("proj", 0) != 0) text += line + "\n";
  }
  return text;
}

KittiCalib read_kitti_calib(const std::string& path) {
  const std::vector<std::string> lines = split_lines(io_detail::read_whole_file(path));
  KittiCalib calib;
  calib.P0 = kitti_matrix(lines, {"P0", "P_rect_00"}, path);
  calib.P1 = kitti_matrix(lines, {"P1", "P_rect_01"}, path);
  const std::array<double, 12>& p0 = calib.P0;
  const std::array<double, 12>& p1 = calib.P1;
  for (std::size_t i = 0; i < 12; ++i) {
    if (!std::isfinite(p0[i]) || !std::isfinite(p1[i])) throw InputError(path, "has a value that is not finite");
  }
  if (std::abs(p0[0] - p0[5]) > kFocalTolerance * p0[0]) {
    throw InputError(path, "P0 has fx " + number_text(p0[0]) + " and fy " + number_text(p0[5]) +
                               ": only square pixels are supported");
  }
  if (std::abs(p0[0] - p1[0]) > kFocalTolerance * p0[0] || std::abs(p0[5] - p1[5]) > kFocalTolerance * p0[5]) {
    throw InputError(path, "P1 has focal length " + number_text(p1[0]) + ", P0 " + number_text(p0[0]) +
                               ": the cameras of a rectified pair have the same focal length");
  }
  if (std::abs(p0[6] - p1[6]) > kPixelTolerance) {
    throw InputError(path, "P1 has its principal point on row " + number_text(p1[6]) + ", P0 on row " +
                               number_text(p0[6]) + ": the rows of a rectified pair match");
  }
  return calib;
}

}  // namespace flexsight

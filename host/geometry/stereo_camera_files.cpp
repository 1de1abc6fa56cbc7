// The rig's calibration files (stereo_camera.h read_stereo_camera): Middlebury calib.txt,
// KITTI calib, and OpenCV's stereo calibration (YAML/XML/JSON), the last checked before
// OpenCV's parser sees it.
#include "host/geometry/stereo_camera.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <sstream>
#include <vector>

#include "host/io/calibration.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

double unit_in_metres(const std::string& unit, const std::string& path) {
  if (unit == "m") return 1.0;
  if (unit == "cm") return 1e-2;
  if (unit == "mm") return 1e-3;
  throw InputError(path, "unknown length unit '" + unit + "' (expected mm, cm or m)");
}

std::string head_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be opened");
  std::string head(512, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

// ------------------------------------------------ before OpenCV's FileStorage parser

// Debian's OpenCV 4.6 FileStorage parser never returns on some malformed YAML (a second
// "%YAML" directive after "---", an unknown version, mangled tags: tests/fuzz/known,
// docs/reliability.md finding 4). So a file goes to it only when it has the shape that
// cv::FileStorage writes: at most 1 MiB of printable ASCII; YAML beginning with
// "%YAML:1.x", an optional "---" second line, no other directive or document marker,
// the first name at the start of its line,
// only OpenCV's own !!opencv-... tags, quotes closed on their line and brackets
// balanced; XML beginning with "<?xml" with its elements balanced and no DOCTYPE or
// CDATA; JSON beginning with "{" with its strings closed and brackets balanced. What
// OpenCV would refuse anyway (no "%YAML" or "<?xml" at byte 0) is refused here first.
constexpr size_t kMaxOpenCvFileBytes = 1 << 20;
constexpr int kMaxNesting = 32;

[[noreturn]] void refuse_storage(const std::string& path, size_t line, const std::string& why) {
  throw InputError(path, "is not valid OpenCV YAML/XML (line " + std::to_string(line) + ": " + why + ")");
}

enum class BracketStep { kNone, kOpened, kClosed };

// Follows `c` in the stack of open brackets (JSON's and YAML flow style's [ ] { }),
// refusing nesting beyond kMaxNesting and a bracket closed that was not open.
BracketStep track_bracket(std::vector<char>& open, char c, const std::string& path, size_t line_number) {
  if (c == '[' || c == '{') {
    open.push_back(c);
    if (open.size() > size_t(kMaxNesting)) refuse_storage(path, line_number, "brackets nested too deep");
    return BracketStep::kOpened;
  }
  if (c == ']' || c == '}') {
    if (open.empty() || open.back() != (c == ']' ? '[' : '{')) {
      refuse_storage(path, line_number, std::string("an unmatched '") + c + "'");
    }
    open.pop_back();
    return BracketStep::kClosed;
  }
  return BracketStep::kNone;
}

void check_yaml_storage(const std::string& path, const std::string& text) {
  std::vector<char> open;  // brackets not closed yet
  size_t line_number = 0;
  bool seen_content = false;
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t last = line.find_last_not_of(' ');
    line.resize(last == std::string::npos ? 0 : last + 1);
    if (line_number == 1) {
      // %YAML:1.0 (what OpenCV writes), %YAML 1.0, 1.1 or 1.2.
      if (!(line.size() == 9 && line.compare(0, 5, "%YAML") == 0 && (line[5] == ':' || line[5] == ' ') &&
            line.compare(6, 2, "1.") == 0 && line[8] >= '0' && line[8] <= '2')) {
        refuse_storage(path, 1, "expected %YAML:1.0");
      }
      continue;
    }
    if (line_number == 2 && (line == "---" || line == "--- !!opencv-storage")) continue;
    if (!line.empty() && line[0] == '%') refuse_storage(path, line_number, "a directive after the first line");
    if (line.compare(0, 3, "---") == 0 || line.compare(0, 3, "...") == 0) {
      refuse_storage(path, line_number, "a second document");
    }
    if (!line.empty() && line[0] == '\t') refuse_storage(path, line_number, "a tab in the indentation");
    // OpenCV writes its top-level names at the start of a line; a first name indented,
    // then one less indented, hangs its parser (tests/fuzz/known/opencv_camera_hang_3.yml).
    const size_t content = line.find_first_not_of(' ');
    if (!seen_content && content != std::string::npos && line[content] != '#') {
      if (content != 0) refuse_storage(path, line_number, "the first name is indented");
      seen_content = true;
    }
    for (size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) break;  // a comment
      if (c == '"' || c == '\'') {
        size_t close = i + 1;
        while (close < line.size() && line[close] != c) close += (c == '"' && line[close] == '\\') ? 2 : 1;
        if (close >= line.size()) refuse_storage(path, line_number, "a quote not closed on its line");
        i = close;
      } else if (c == '!') {
        static const char* const tags[] = {"!!opencv-matrix", "!!opencv-nd-matrix",
                                           "!!opencv-sparse-matrix", "!!opencv-seq", "!!opencv-map"};
        bool known = false;
        for (const char* tag : tags) {
          const size_t n = std::strlen(tag);
          if (line.compare(i, n, tag) == 0 && (i + n == line.size() || line[i + n] == ' ')) {
            known = true;
            i += n - 1;
            break;
          }
        }
        if (!known) refuse_storage(path, line_number, "a tag other than OpenCV's !!opencv-...");
      } else {
        track_bracket(open, c, path, line_number);
      }
    }
  }
  if (!open.empty()) refuse_storage(path, line_number, std::string("a '") + open.back() + "' never closed");
}

void check_xml_storage(const std::string& path, const std::string& text) {
  std::vector<std::string> open;  // elements not closed yet
  bool had_root = false;
  const auto line_at = [&](size_t pos) {
    return 1 + size_t(std::count(text.begin(), text.begin() + long(pos), '\n'));
  };
  const auto name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':';
  };
  for (size_t pos = 0; pos < text.size();) {
    const size_t lt = text.find('<', pos);
    if (lt == std::string::npos) {
      if (open.empty() && text.find_first_not_of(" \t\r\n", pos) != std::string::npos) {
        refuse_storage(path, line_at(pos), "text outside the root element");
      }
      break;
    }
    if (open.empty() && text.find_first_not_of(" \t\r\n", pos) < lt) {
      refuse_storage(path, line_at(pos), "text outside the root element");
    }
    if (text.compare(lt, 4, "<!--") == 0) {
      const size_t close = text.find("-->", lt + 4);
      if (close == std::string::npos) refuse_storage(path, line_at(lt), "a comment never closed");
      pos = close + 3;
      continue;
    }
    if (text.compare(lt, 2, "<?") == 0) {
      const size_t close = text.find("?>", lt + 2);
      if (close == std::string::npos || !open.empty() || had_root) {
        refuse_storage(path, line_at(lt), "a processing instruction not closed or not before the root");
      }
      pos = close + 2;
      continue;
    }
    if (text.compare(lt, 2, "<!") == 0) refuse_storage(path, line_at(lt), "a DOCTYPE or CDATA section");
    const bool closing = text.compare(lt, 2, "</") == 0;
    size_t i = lt + (closing ? 2 : 1);
    const size_t name_begin = i;
    while (i < text.size() && name_char(text[i])) ++i;
    if (i == name_begin || std::isdigit(static_cast<unsigned char>(text[name_begin])) ||
        text[name_begin] == '-' || text[name_begin] == '.') {
      refuse_storage(path, line_at(lt), "a '<' that starts no element name");
    }
    const std::string name = text.substr(name_begin, i - name_begin);
    // Attributes (type_id="opencv-matrix"): quoted values, up to '>' or '/>'.
    char quote = 0;
    while (i < text.size() && (quote != 0 || (text[i] != '>' && text[i] != '<'))) {
      if (quote == 0 && (text[i] == '"' || text[i] == '\'')) {
        quote = text[i];
      } else if (quote != 0 && text[i] == quote) {
        quote = 0;
      }
      ++i;
    }
    if (i == text.size() || text[i] != '>') refuse_storage(path, line_at(lt), "a tag never closed");
    const bool empty_element = !closing && text[i - 1] == '/';
    pos = i + 1;
    if (closing) {
      if (open.empty() || open.back() != name) refuse_storage(path, line_at(lt), "a closing tag that matches no element");
      open.pop_back();
      continue;
    }
    if (open.empty()) {
      if (had_root) refuse_storage(path, line_at(lt), "a second root element");
      had_root = true;
    }
    if (!empty_element) {
      open.push_back(name);
      if (open.size() > size_t(kMaxNesting)) refuse_storage(path, line_at(lt), "elements nested too deep");
    }
  }
  if (!open.empty()) refuse_storage(path, line_at(text.size()), "element <" + open.back() + "> never closed");
  if (!had_root) refuse_storage(path, line_at(text.size()), "no root element");
}

void check_json_storage(const std::string& path, const std::string& text) {
  std::vector<char> open;
  size_t line_number = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line_number;
    if (c == '"') {
      size_t close = i + 1;
      while (close < text.size() && text[close] != '"' && text[close] != '\n') {
        close += text[close] == '\\' ? 2 : 1;
      }
      if (close >= text.size() || text[close] != '"') refuse_storage(path, line_number, "a string not closed on its line");
      i = close;
    } else if (track_bracket(open, c, path, line_number) == BracketStep::kClosed) {
      if (open.empty() && text.find_first_not_of(" \t\r\n", i + 1) != std::string::npos) {
        refuse_storage(path, line_number, "text after the top-level object");
      }
    }
  }
  if (!open.empty()) refuse_storage(path, line_number, std::string("a '") + open.back() + "' never closed");
}

void check_opencv_storage(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error) throw InputError(path, "cannot be read");
  if (size > kMaxOpenCvFileBytes) {
    throw InputError(path, "is " + std::to_string(size) +
                               " bytes: too large for a calibration (at most 1 MiB of OpenCV YAML/XML)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be opened");
  std::string text(size, '\0');
  in.read(text.data(), std::streamsize(size));
  text.resize(size_t(in.gcount()));
  size_t line_number = 1;
  for (char c : text) {
    if (c == '\n') ++line_number;
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n' && c != '\r' && c != '\t') || u >= 0x7f) {
      refuse_storage(path, line_number, "a byte that is not printable ASCII");
    }
  }
  if (text.compare(0, 5, "%YAML") == 0) return check_yaml_storage(path, text);
  if (text.compare(0, 5, "<?xml") == 0) return check_xml_storage(path, text);
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return check_json_storage(path, text);
  throw InputError(path, "is not valid OpenCV YAML/XML (it begins with neither %YAML, <?xml nor {)");
}

}  // namespace

StereoCamera read_middlebury_camera(const std::string& path) {
  const MiddleburyCalib calib = read_middlebury_calib(path);
  StereoCamera camera;
  const double cx = calib.cam0[2];
  camera.Q = reprojection_matrix(calib.cam0[0], cx, calib.cam0[5], cx + calib.doffs,
                                 calib.baseline_mm);
  camera.width = calib.width;
  camera.height = calib.height;
  camera.unit = "mm";
  camera.metres_per_unit = 1e-3;
  camera.source = path;
  if (!(calib.baseline_mm > 0)) throw InputError(path, "baseline must be positive");
  return camera;
}

StereoCamera read_kitti_camera(const std::string& path) {
  const KittiCalib calib = read_kitti_calib(path);
  const double f = calib.P0[0];
  const double baseline = calib.baseline_m() - (-calib.P0[3] / calib.P0[0]);
  if (!(f > 0)) throw InputError(path, "P0 has a non-positive focal length");
  if (!(baseline > 0)) {
    throw InputError(path, "P1 is not to the right of P0 (baseline " + std::to_string(baseline) +
                               " m)");
  }
  StereoCamera camera;
  camera.Q = reprojection_matrix(f, calib.P0[2], calib.P0[6], calib.P1[2], baseline);
  camera.unit = "m";
  camera.metres_per_unit = 1.0;
  camera.source = path;
  return camera;
}

StereoCamera read_opencv_camera(const std::string& path) {
  check_opencv_storage(path);  // before OpenCV's parser, which can hang
  cv::FileStorage storage;
  try {
    if (!storage.open(path, cv::FileStorage::READ)) {
      throw InputError(path, "cannot be read as OpenCV YAML/XML");
    }
  } catch (const cv::Exception& error) {
    throw InputError(path, std::string("is not valid OpenCV YAML/XML: ") + error.err);
  } catch (const std::exception& error) {
    // OpenCV's parser lets std::length_error and std::bad_alloc through on some
    // malformed files (found by tests/fuzz/fuzz_opencv_camera).
    throw InputError(path, std::string("is not valid OpenCV YAML/XML (") + error.what() + ")");
  }
  // The size first: OpenCV's reader allocates rows x cols before it reads the data, and
  // takes a size that is not a number as INT_MAX, so a few bytes could ask for 64 GB.
  // storage[name] asserts (cv::Exception) on a file whose top level is not a map.
  if (!storage.root().isMap()) {
    throw InputError(path, "is not OpenCV YAML/XML of named values (expected Q: !!opencv-matrix)");
  }
  const cv::FileNode q_node = storage["Q"];
  if (q_node.isMap()) {
    const cv::FileNode rows = q_node["rows"], cols = q_node["cols"];
    if (!rows.isInt() || !cols.isInt()) {
      throw InputError(path, "Q is not a matrix: rows and cols must be whole numbers");
    }
    const int r = static_cast<int>(rows), c = static_cast<int>(cols);
    if (r != 0 && c != 0 && (r != 4 || c != 4)) {  // 0 x 0: no Q, said below
      throw InputError(path, "Q is " + std::to_string(r) + "x" + std::to_string(c) + ", expected 4x4");
    }
  } else if (!q_node.empty() && !q_node.isNone()) {
    throw InputError(path, "Q is not a matrix (expected an opencv-matrix with rows, cols, dt, data)");
  }
  cv::Mat q;
  try {
    q_node >> q;
  } catch (const cv::Exception& error) {
    throw InputError(path, std::string("Q is not a matrix: ") + error.err);
  }
  if (q.empty()) throw InputError(path, "has no Q matrix (the output of cv::stereoRectify)");
  if (q.rows != 4 || q.cols != 4 || q.channels() != 1) {
    throw InputError(path, "Q is " + std::to_string(q.rows) + "x" + std::to_string(q.cols) +
                               ", expected 4x4");
  }
  StereoCamera camera;
  q.convertTo(q, CV_64F);
  cv::cv2eigen(q, camera.Q);
  if (!camera.Q.allFinite() || camera.Q(2, 3) == 0 || camera.Q(3, 2) == 0) {
    throw InputError(path, "Q has no focal length (Q[2][3]) or no baseline (Q[3][2])");
  }
  // OpenCV's convention puts Tx < 0 for a right camera to the right, giving Q[3][2] =
  // -1/Tx > 0. A negative entry means the views are swapped.
  if (camera.Q(3, 2) < 0) {
    throw InputError(path, "Q[3][2] < 0: the right camera is left of the left one (views swapped?)");
  }
  const cv::FileNode unit = storage["unit"];
  camera.unit = unit.isString() ? static_cast<std::string>(unit) : std::string("mm");
  camera.metres_per_unit = unit_in_metres(camera.unit, path);
  const cv::FileNode size = storage["image_size"];
  if (size.isSeq() && size.size() == 2) {
    camera.width = static_cast<int>(size[0]);
    camera.height = static_cast<int>(size[1]);
  } else {
    const cv::FileNode w = storage["image_width"], h = storage["image_height"];
    if (w.isInt() && h.isInt()) {
      camera.width = static_cast<int>(w);
      camera.height = static_cast<int>(h);
    }
  }
  camera.source = path;
  return camera;
}

StereoCamera read_stereo_camera(const std::string& path) {
  const std::string head = head_of(path);
  if (head.find("cam0") != std::string::npos) return read_middlebury_camera(path);
  if (head.rfind("P0:", 0) == 0 || head.find("\nP0:") != std::string::npos ||
      head.find("P_rect_00") != std::string::npos) {
    return read_kitti_camera(path);
  }
  if (head.rfind("%YAML", 0) == 0 || head.rfind("<?xml", 0) == 0 || head.find("Q:") != std::string::npos) {
    return read_opencv_camera(path);
  }
  throw InputError(path, "is not a calibration file this program reads (Middlebury calib.txt "
                         "with cam0=..., KITTI with P0:/P1:, or OpenCV YAML/XML with Q)");
}

}  // namespace flexsight

#include "host/dataset/bop_pose_results.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"
#include "host/io/physical_checks.h"

namespace flexsight {
namespace {

constexpr const char* kHeader = "scene_id,im_id,obj_id,score,R,t,time";
constexpr int kColumns = 7;
// The shortest text that reads back to the same double (std::to_chars without a
// precision), so that a file read and written again gives the same bytes.
std::string number_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

// Reads the lines of one file, each problem an InputError naming the file and line.
class LineParser {
 public:
  LineParser(const std::string& path, int line) : path_(path), line_(line) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_, "line " + std::to_string(line_) + ": " + problem);
  }

  int id(const std::string& field, const char* name) const {
    const std::string text = trimmed(field);
    int value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size() ||
        value < 0) {
      fail(std::string(name) + ": expected a whole number >= 0, found '" + text + "'");
    }
    return value;
  }

  double number(const std::string& text, const std::string& name) const {
    double value = 0.0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) {
      fail(name + ": expected a number, found '" + text + "'");
    }
    if (!std::isfinite(value)) fail(name + ": " + text + " is not a finite number");
    return value;
  }

  // `count` numbers separated by spaces.
  std::vector<double> numbers(const std::string& field, std::size_t count, const char* name) const {
    std::istringstream stream(field);
    std::vector<std::string> words;
    for (std::string word; stream >> word;) words.push_back(word);
    if (words.size() != count) {
      fail(std::string(name) + ": expected " + std::to_string(count) +
           " space-separated numbers, found " + std::to_string(words.size()));
    }
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) {
      values.push_back(number(words[i], std::string(name) + "[" + std::to_string(i) + "]"));
    }
    return values;
  }

  void check_pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) const {
    const std::string r_problem = physical_checks::rotation_problem(R);
    if (!r_problem.empty()) fail("R " + r_problem);
    const std::string t_problem = physical_checks::translation_problem(t, false);
    if (!t_problem.empty()) fail("t " + t_problem);
  }

 private:
  const std::string& path_;
  int line_;
};

PoseEstimateRecord parse_line(const std::string& path, int line_number, const std::string& line) {
  const LineParser parser(path, line_number);
  const std::vector<std::string> columns = split(line, ',');
  if (static_cast<int>(columns.size()) != kColumns) {
    parser.fail("expected 7 comma-separated columns (" + std::string(kHeader) + "), found " +
                std::to_string(columns.size()));
  }
  PoseEstimateRecord record;
  record.scene_id = parser.id(columns[0], "scene_id");
  record.im_id = parser.id(columns[1], "im_id");
  record.obj_id = parser.id(columns[2], "obj_id");
  record.score = parser.number(trimmed(columns[3]), "score");
  const std::vector<double> R = parser.numbers(columns[4], 9, "R");
  const std::vector<double> t = parser.numbers(columns[5], 3, "t");
  record.time_s = parser.number(trimmed(columns[6]), "time");
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) record.R(row, col) = R[3 * row + col];
  }
  record.t = Eigen::Vector3d(t[0], t[1], t[2]);
  parser.check_pose(record.R, record.t);
  return record;
}

void check_writable(const std::string& path, const PoseEstimateRecord& record, std::size_t index) {
  bool finite = std::isfinite(record.score) && std::isfinite(record.time_s) &&
                record.R.allFinite() && record.t.allFinite();
  if (!finite) {
    throw InputError(path, "record " + std::to_string(index) +
                               " has a number that is not finite (BOP's reader would refuse it)");
  }
}

}  // namespace

void write_bop_pose_results(const std::string& path, const std::vector<PoseEstimateRecord>& records) {
  std::string text = std::string(kHeader) + "\n";
  for (std::size_t i = 0; i < records.size(); ++i) {
    const PoseEstimateRecord& r = records[i];
    check_writable(path, r, i);
    text += std::to_string(r.scene_id) + "," + std::to_string(r.im_id) + "," +
            std::to_string(r.obj_id) + "," + number_text(r.score) + ",";
    for (int k = 0; k < 9; ++k) text += (k ? " " : "") + number_text(r.R(k / 3, k % 3));
    text += ",";
    for (int k = 0; k < 3; ++k) text += (k ? " " : "") + number_text(r.t(k));
    text += "," + number_text(r.time_s) + "\n";
  }
  dataset_files::write_text(path, text);
}

std::vector<PoseEstimateRecord> read_bop_pose_results(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "does not exist");
  if (fs::is_directory(path, ec)) throw InputError(path, "is a folder, not a results file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be opened");

  std::vector<PoseEstimateRecord> records;
  std::string line;
  int line_number = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trimmed(line).empty()) continue;
    // BOP's reader skips a first line that holds the header; so do we.
    const bool header_place = first;
    first = false;
    if (header_place && line.find("scene_id") != std::string::npos) {
      std::string compact;
      for (char c : line) {
        if (c != ' ' && c != '\t') compact += c;
      }
      if (compact != kHeader) {
        throw InputError(path, "line " + std::to_string(line_number) + ": a header, but not BOP's (expected '" + std::string(kHeader) +
                                   "', found '" + line + "')");
      }
      continue;
    }
    records.push_back(parse_line(path, line_number, line));
  }
  if (in.bad()) throw InputError(path, "cannot be read");
  // A file without even BOP's header line is what a run that died before writing leaves.
  if (first) {
    throw InputError(path, "is empty (expected BOP's header " + std::string(kHeader) + ")");
  }
  return records;
}

}  // namespace flexsight

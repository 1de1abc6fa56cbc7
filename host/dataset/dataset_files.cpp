#include "host/dataset/dataset_files.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight::dataset_files {
namespace {

void write_bytes(const std::string& path, const char* data, std::size_t size) {
  write_atomically(path, [&](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary | std::ios::trunc);
    out.write(data, static_cast<std::streamsize>(size));
    out.close();
    if (!out) throw InputError(path, "cannot be written (folder not writable or disk full)");
  });
}

std::string type_name(const Json& value) { return value.type_name(); }

[[noreturn]] void wrong_type(const Json& value, const std::string& expected,
                             const std::string& file, const std::string& where) {
  throw InputError(
      file, where + ": expected " + expected + ", found " + type_name(value) + " " + value.dump());
}

}  // namespace

void write_encoded_image(const std::string& path, const cv::Mat& image,
                         const std::vector<int>& params) {
  const std::string extension = std::filesystem::path(path).extension().string();
  std::vector<uchar> bytes;
  bool encoded = false;
  try {
    encoded = cv::imencode(extension, image, bytes, params);
  } catch (const cv::Exception& e) {
    throw InputError(path, "cannot be encoded (" + e.err + ")");
  }
  if (!encoded) throw InputError(path, "cannot be encoded as " + extension);
  write_bytes(path, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void write_text(const std::string& path, const std::string& text) {
  write_bytes(path, text.data(), text.size());
}

Json read_json(const std::string& path) {
  return parse_json(io_detail::read_whole_file(path), path);
}

Json parse_json(const std::string& text, const std::string& path) {
  try {
    return Json::parse(text);
  } catch (const Json::exception& e) {  // parse_error, and out_of_range for a number too large (1e999)
    // e.what() reads "[json.exception.parse_error.101] parse error at line 3, column 5:
    // ..."; the part after the bracket is the useful one.
    std::string message = e.what();
    const auto bracket = message.find("] ");
    if (bracket != std::string::npos) message = message.substr(bracket + 2);
    throw InputError(path, "is not valid JSON (" + message + ")");
  }
}

void create_empty_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw InputError(dir, "exists and is not a folder");
    if (!fs::is_empty(dir, ec)) {
      throw InputError(dir, "is not empty (a dataset is written into a new or empty folder)");
    }
    return;
  }
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot be created (" + ec.message() + ")");
}

bool is_directory(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec);
}

bool is_file(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

const Json& require_key(const Json& object, const std::string& key, const std::string& file,
                        const std::string& where) {
  if (!object.is_object()) wrong_type(object, "an object", file, where);
  const auto found = object.find(key);
  if (found == object.end()) throw InputError(file, where + ": key \"" + key + "\" is missing");
  return *found;
}

double to_double(const Json& value, const std::string& file, const std::string& where) {
  if (!value.is_number()) wrong_type(value, "a number", file, where);
  const double number = value.get<double>();
  if (!std::isfinite(number)) throw InputError(file, where + ": number is not finite");
  return number;
}

long long to_integer(const Json& value, const std::string& file, const std::string& where) {
  if (value.is_number_integer()) return value.get<long long>();
  // 3.0 is accepted as 3: some writers print every number as a float.
  if (value.is_number_float()) {
    const double number = value.get<double>();
    if (std::nearbyint(number) == number && std::fabs(number) < 9e15) {
      return static_cast<long long>(number);
    }
  }
  wrong_type(value, "an integer", file, where);
}

int to_int(const Json& value, const std::string& file, const std::string& where) {
  const long long number = to_integer(value, file, where);
  if (number < std::numeric_limits<int>::min() || number > std::numeric_limits<int>::max()) {
    throw InputError(file, where + ": " + std::to_string(number) + " is out of range");
  }
  return static_cast<int>(number);
}

std::string to_string(const Json& value, const std::string& file, const std::string& where) {
  if (!value.is_string()) wrong_type(value, "a string", file, where);
  return value.get<std::string>();
}

std::vector<double> to_doubles(const Json& value, std::size_t count, const std::string& file,
                               const std::string& where) {
  if (!value.is_array())
    wrong_type(value, "an array of " + std::to_string(count) + " numbers", file, where);
  if (value.size() != count) {
    throw InputError(file, where + ": expected " + std::to_string(count) + " numbers, found " +
                               std::to_string(value.size()));
  }
  std::vector<double> numbers;
  numbers.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    numbers.push_back(to_double(value[i], file, where + "[" + std::to_string(i) + "]"));
  }
  return numbers;
}

int parse_im_id(const std::string& key, const std::string& file) {
  const bool digits =
      !key.empty() && key.size() <= 9 && key.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) {
    throw InputError(file, "key \"" + key + "\" is not an image id (a non-negative integer)");
  }
  return std::stoi(key);
}

}  // namespace flexsight::dataset_files

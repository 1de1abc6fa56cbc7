#pragma once
// File input and output shared by the dataset writers, readers and the merge: encoded
// images and text written atomically, JSON read with errors that name the file, and the
// checks on JSON values that every reader of BOP and COCO files needs.
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace flexsight::dataset_files {

using Json = nlohmann::json;

// Encodes `image` (BGR order, or gray) with OpenCV into the format of `path`'s extension
// with `params` (cv::imwrite's), then writes the bytes atomically. Throws InputError
// naming `path` when encoding or writing fails.
void write_encoded_image(const std::string& path, const cv::Mat& image,
                         const std::vector<int>& params);

// Writes `text` to `path` atomically; InputError naming `path` on failure.
void write_text(const std::string& path, const std::string& text);

// Parses the JSON file at `path`. InputError naming it when it is missing, unreadable or
// not valid JSON (with the parser's position).
Json read_json(const std::string& path);

// Parses `text`, read from `path`; InputError naming `path` when it is not valid JSON.
Json parse_json(const std::string& text, const std::string& path);

// Creates `dir` (and its parents) unless it exists; throws InputError naming it when it
// cannot be created, or when it exists and holds anything: a dataset is written into a
// folder of its own, so files of an earlier run cannot mix with this one's.
void create_empty_directory(const std::string& dir);

// True when `path` is a directory (false when missing).
bool is_directory(const std::string& path);
bool is_file(const std::string& path);

// The value at `key` of `object`; InputError "<file>: <where>: key "<key>" is missing"
// (or "... is not an object" when `object` is not one).
const Json& require_key(const Json& object, const std::string& key, const std::string& file,
                        const std::string& where);

// Typed reads of a JSON value, each an InputError naming the file, the place and what was
// expected when the value is of another type (or out of range for an int).
double to_double(const Json& value, const std::string& file, const std::string& where);
long long to_integer(const Json& value, const std::string& file, const std::string& where);
int to_int(const Json& value, const std::string& file, const std::string& where);
std::string to_string(const Json& value, const std::string& file, const std::string& where);
// An array of exactly `count` numbers.
std::vector<double> to_doubles(const Json& value, std::size_t count, const std::string& file,
                               const std::string& where);

// An image id written as an object key ("42"): a non-negative decimal integer.
int parse_im_id(const std::string& key, const std::string& file);

}  // namespace flexsight::dataset_files

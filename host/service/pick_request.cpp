#include "host/service/pick_request.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace flexsight {
namespace {

using Json = nlohmann::json;

RequestError bad_key(const std::string& key, const std::string& problem) {
  return RequestError(400, "key " + key + ": " + problem);
}

// A key is an option's name in snake_case: lower-case letters, digits and '_'.
bool is_option_name(const std::string& key) {
  return !key.empty() && std::isalpha(static_cast<unsigned char>(key[0])) &&
         std::all_of(key.begin(), key.end(), [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

std::string number_text(const Json& value) {
  if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
  const double x = value.get<double>();
  if (std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 1e15) return std::to_string(static_cast<long long>(x));
  return value.dump();  // the shortest text that reads back as the same double
}

// The option tokens of one key: none, "--name", or "--name value".
std::vector<std::string> option_tokens(const std::string& key, const Json& value) {
  std::string name = "--" + key;
  std::replace(name.begin(), name.end(), '_', '-');
  if (value.is_boolean()) return value.get<bool>() ? std::vector<std::string>{name} : std::vector<std::string>{};
  if (value.is_string()) return {name, value.get<std::string>()};
  if (value.is_number()) return {name, number_text(value)};
  if (value.is_array() && !value.empty() &&
      std::all_of(value.begin(), value.end(), [](const Json& v) { return v.is_number() || v.is_string(); })) {
    std::string list;
    for (const Json& v : value) list += (list.empty() ? "" : ",") + (v.is_string() ? v.get<std::string>() : number_text(v));
    return {name, list};
  }
  throw bad_key(key, "expected a string, a number, true/false or a list, got " + std::string(value.type_name()));
}

std::string string_field(const Json& body, const std::string& key) {
  const Json& value = body.at(key);
  if (!value.is_string() || value.get<std::string>().empty()) throw bad_key(key, "expected a non-empty string");
  return value.get<std::string>();
}

// The path (`key`) or the base64 bytes (`key`_png) of one image; exactly one of them
// unless `optional`.
void take_image(const Json& body, const std::string& key, bool optional, std::string* path, std::string* bytes) {
  const bool has_path = body.contains(key), has_bytes = body.contains(key + "_png");
  if (has_path && has_bytes) throw bad_key(key, "give the path or " + key + "_png, not both");
  if (has_path) *path = string_field(body, key);
  if (has_bytes) *bytes = decode_base64(string_field(body, key + "_png"), key + "_png");
  if (!has_path && !has_bytes && !optional) throw bad_key(key, "missing (the image's path, or " + key + "_png)");
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

const std::vector<std::string>& keys_fixed_at_start() {
  static const std::vector<std::string> keys = {"templates", "cad", "model", "namer", "o", "png"};
  return keys;
}

PickRequest parse_pick_request(const std::string& body_text) {
  Json body;
  try {
    body = Json::parse(body_text);
  } catch (const Json::parse_error& e) {
    throw RequestError(400, std::string("body: not JSON (") + e.what() + ")");
  }
  if (!body.is_object()) throw RequestError(400, "body: expected a JSON object, got " + std::string(body.type_name()));
  PickRequest request;
  take_image(body, "left", false, &request.files.left, &request.left_bytes);
  take_image(body, "right", false, &request.files.right, &request.right_bytes);
  take_image(body, "passive_left", true, &request.files.passive_left, &request.passive_left_bytes);
  if (!body.contains("calib")) throw bad_key("calib", "missing (the pair's calibration file)");
  request.files.calib = string_field(body, "calib");
  const std::vector<std::string> images = {"left", "right", "passive_left", "left_png", "right_png", "passive_left_png", "calib"};
  for (const auto& [key, value] : body.items()) {
    if (std::find(images.begin(), images.end(), key) != images.end()) continue;
    const auto& fixed = keys_fixed_at_start();
    if (std::find(fixed.begin(), fixed.end(), key) != fixed.end()) {
      throw bad_key(key, key == "o" || key == "png" ? "the service answers the PICKS.json and writes no file"
                                                    : "loaded once when flexsight serve starts (its --" + key + ")");
    }
    if (!is_option_name(key)) throw bad_key(key, "not an option of flexsight pick");
    const std::vector<std::string> tokens = option_tokens(key, value);
    request.option_tokens.insert(request.option_tokens.end(), tokens.begin(), tokens.end());
  }
  return request;
}

std::vector<std::string> merge_pick_arguments(const std::vector<std::string>& base, const std::vector<std::string>& request) {
  auto is_name = [](const std::string& token) { return token.size() > 2 && token.compare(0, 2, "--") == 0; };
  std::vector<std::string> given;
  for (const std::string& token : request) {
    if (is_name(token)) given.push_back(token);
  }
  std::vector<std::string> merged;
  bool skipping = false;
  for (const std::string& token : base) {
    if (is_name(token)) skipping = std::find(given.begin(), given.end(), token) != given.end();
    if (!skipping) merged.push_back(token);
  }
  merged.insert(merged.end(), request.begin(), request.end());
  return merged;
}

std::string decode_base64(const std::string& text, const std::string& field) {
  std::string bytes;
  unsigned buffer = 0;
  int bits = 0, padding = 0;
  for (char c : text) {
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    if (c == '=') {
      ++padding;
      continue;
    }
    const int value = base64_value(c);
    if (value < 0 || padding > 0) throw bad_key(field, "not base64");
    buffer = (buffer << 6) | static_cast<unsigned>(value);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<char>((buffer >> bits) & 0xFF));
    }
  }
  if (padding > 2 || bits >= 6) throw bad_key(field, "not base64");
  if (bytes.empty()) throw bad_key(field, "empty");
  return bytes;
}

}  // namespace flexsight

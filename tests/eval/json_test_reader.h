#pragma once
// A small JSON reader for the tests of tests/eval/, to check that the report the eval
// command writes is real JSON and holds the numbers.
#include <cctype>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace flexsight::dataset_test_support {

struct Json {
  enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
  double number = 0;
  std::string text;
  std::vector<Json> items;           // array elements, or object values
  std::vector<std::string> keys;     // object keys, parallel to items

  const Json& operator[](const std::string& key) const {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == key) return items[i];
    }
    throw std::runtime_error("JSON object has no key " + key);
  }
  const Json& operator[](std::size_t index) const { return items.at(index); }
  double num() const {
    if (kind != Kind::Number) throw std::runtime_error("JSON value is not a number");
    return number;
  }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : text_(text) {}

  Json document() {
    Json value = parse_value();
    skip_space();
    if (pos_ != text_.size()) fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(pos_));
  }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  char peek() {
    skip_space();
    if (pos_ >= text_.size()) fail("unexpected end");
    return text_[pos_];
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  bool consume(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  bool literal(const std::string& word) {
    if (text_.compare(pos_, word.size(), word) != 0) return false;
    pos_ += word.size();
    return true;
  }

  Json parse_value() {
    const char c = peek();
    Json value;
    if (c == '{') return parse_object();
    if (c == '[') return parse_array();
    if (c == '"') {
      value.kind = Json::Kind::String;
      value.text = parse_string();
    } else if (literal("null")) {
      value.kind = Json::Kind::Null;
    } else if (literal("true") || literal("false")) {
      value.kind = Json::Kind::Bool;
    } else {
      value.kind = Json::Kind::Number;
      value.number = parse_number();
    }
    return value;
  }

  Json parse_object() {
    Json object;
    object.kind = Json::Kind::Object;
    expect('{');
    if (peek() != '}') {
      do {
        if (peek() != '"') fail("expected a key");
        object.keys.push_back(parse_string());
        expect(':');
        object.items.push_back(parse_value());
      } while (consume(','));
    }
    expect('}');
    return object;
  }

  Json parse_array() {
    Json array;
    array.kind = Json::Kind::Array;
    expect('[');
    if (peek() != ']') {
      do {
        array.items.push_back(parse_value());
      } while (consume(','));
    }
    expect(']');
    return array;
  }

  std::string parse_string() {
    expect('"');
    std::string out;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      const char c = text_[pos_++];
      if (static_cast<unsigned char>(c) < 0x20) fail("raw control character in string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) fail("unfinished escape");
      const char e = text_[pos_++];
      switch (e) {
        case '"': case '\\': case '/': out += e; break;
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        case 'r': out += '\r'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'u': {
          if (pos_ + 4 > text_.size()) fail("short \\u escape");
          out += static_cast<char>(std::stoi(text_.substr(pos_, 4), nullptr, 16));  // ASCII only
          pos_ += 4;
          break;
        }
        default: fail("bad escape");
      }
    }
    expect('"');
    return out;
  }

  double parse_number() {
    const std::size_t start = pos_;
    if (pos_ < text_.size() && text_[pos_] == '-') ++pos_;
    while (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) ||
                                   text_[pos_] == '.' || text_[pos_] == 'e' ||
                                   text_[pos_] == 'E' || text_[pos_] == '+' || text_[pos_] == '-')) {
      ++pos_;
    }
    if (pos_ == start) fail("expected a value");
    return std::stod(text_.substr(start, pos_ - start));
  }

  const std::string& text_;
  std::size_t pos_ = 0;
};

inline Json parse_json(const std::string& text) { return JsonReader(text).document(); }

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace flexsight::dataset_test_support

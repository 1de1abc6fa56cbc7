#include "host/render/mesh_files.h"

#include <charconv>
#include <cstring>
#include <limits>
#include <string_view>

#include "host/io/input_error.h"

namespace flexsight::mesh_files {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw InputError(path, problem);
}

// A token of the file as a message may show it: printable, at most 24 characters.
std::string shown(std::string_view token) {
  std::string out;
  for (char c : token.substr(0, 24)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (token.size() > 24) out += "...";
  return "'" + out + "'";
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// A whole token as a number of type T ('+' allowed in front, as C's strtod does).
template <typename T>
bool parse_number(std::string_view s, T& value) {
  if (!s.empty() && s[0] == '+') {
    s.remove_prefix(1);
    if (!s.empty() && s[0] == '-') return false;
  }
  if (s.empty()) return false;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  return error == std::errc() && end == s.data() + s.size();
}

// Whitespace-separated tokens of bytes[start, end), with the line each is on.
class Tokens {
 public:
  Tokens(const std::string& bytes, size_t start, size_t line) : bytes_(bytes), pos_(start), line_(line) {}

  bool next(std::string_view& token) {
    while (pos_ < bytes_.size() && is_space(bytes_[pos_])) {
      if (bytes_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == bytes_.size()) return false;
    const size_t begin = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) ++pos_;
    token = std::string_view(bytes_).substr(begin, pos_ - begin);
    return true;
  }
  // Skips what is left of the current line (an STL solid's name).
  void skip_line() {
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
  }
  size_t line() const { return line_; }
  size_t left() const { return bytes_.size() - pos_; }

 private:
  const std::string& bytes_;
  size_t pos_;
  size_t line_;
};

std::uint32_t little_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
         std::uint32_t(b[3]) << 24;
}

float little_float(const char* p) {
  const std::uint32_t bits = little_u32(p);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

std::uint32_t checked_index(const std::string& path, size_t count) {
  if (count >= std::numeric_limits<std::uint32_t>::max()) fail(path, "has more than 2^32 vertices");
  return std::uint32_t(count);
}

// ------------------------------------------------------------------------------ STL

RawMesh read_binary_stl(const std::string& path, const std::string& bytes, std::uint32_t facets) {
  RawMesh mesh;
  mesh.positions.reserve(3 * size_t(facets));
  mesh.triangles.reserve(facets);
  for (std::uint32_t f = 0; f < facets; ++f) {
    const char* facet = bytes.data() + 84 + 50 * size_t(f);
    for (int k = 0; k < 3; ++k) {
      const char* v = facet + 12 + 12 * k;  // after the facet normal
      mesh.positions.emplace_back(little_float(v), little_float(v + 4), little_float(v + 8));
    }
    const std::uint32_t base = checked_index(path, 3 * size_t(f));
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

RawMesh read_ascii_stl(const std::string& path, const std::string& bytes, size_t start) {
  RawMesh mesh;
  Tokens tokens(bytes, start, 1);
  std::string_view token;
  const auto where = [&] { return "line " + std::to_string(tokens.line()) + ": "; };
  const auto expect = [&](const char* word) {
    if (!tokens.next(token)) fail(path, where() + "ends where ASCII STL expects '" + word + "'");
    if (token != word) {
      fail(path, where() + "expected '" + std::string(word) + "', found " + shown(token));
    }
  };
  const auto number = [&]() {
    float value;
    if (!tokens.next(token)) fail(path, where() + "ends where ASCII STL expects a number");
    if (!parse_number(token, value)) fail(path, where() + shown(token) + " is not a number");
    return value;
  };
  expect("solid");
  tokens.skip_line();  // the solid's name
  bool in_solid = true;
  while (tokens.next(token)) {
    if (!in_solid) {
      if (token != "solid") {
        fail(path, where() + "expected 'solid' or the end after 'endsolid', found " + shown(token));
      }
      tokens.skip_line();
      in_solid = true;
      continue;
    }
    if (token == "endsolid") {
      tokens.skip_line();
      in_solid = false;
      continue;
    }
    if (token != "facet") {
      fail(path, where() + "expected 'facet' or 'endsolid', found " + shown(token));
    }
    expect("normal");
    for (int i = 0; i < 3; ++i) number();  // per facet: the corners' normals are ours
    expect("outer");
    expect("loop");
    const std::uint32_t base = checked_index(path, mesh.positions.size());
    for (int k = 0; k < 3; ++k) {
      expect("vertex");
      const float x = number(), y = number(), z = number();
      mesh.positions.emplace_back(x, y, z);
    }
    expect("endloop");
    expect("endfacet");
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  if (in_solid) fail(path, where() + "ends before 'endsolid'");
  return mesh;
}

// ------------------------------------------------------------------------------ PLY

enum class Kind { kSigned, kUnsigned, kFloat };

struct ScalarType {
  Kind kind;
  int size;  // bytes in a binary file
};

bool scalar_type(std::string_view name, ScalarType& type) {
  static const struct {
    const char* name;
    ScalarType type;
  } types[] = {
      {"char", {Kind::kSigned, 1}},    {"int8", {Kind::kSigned, 1}},
      {"uchar", {Kind::kUnsigned, 1}}, {"uint8", {Kind::kUnsigned, 1}},
      {"short", {Kind::kSigned, 2}},   {"int16", {Kind::kSigned, 2}},
      {"ushort", {Kind::kUnsigned, 2}}, {"uint16", {Kind::kUnsigned, 2}},
      {"int", {Kind::kSigned, 4}},     {"int32", {Kind::kSigned, 4}},
      {"uint", {Kind::kUnsigned, 4}},  {"uint32", {Kind::kUnsigned, 4}},
      {"float", {Kind::kFloat, 4}},    {"float32", {Kind::kFloat, 4}},
      {"double", {Kind::kFloat, 8}},   {"float64", {Kind::kFloat, 8}},
  };
  for (const auto& entry : types) {
    if (name == entry.name) {
      type = entry.type;
      return true;
    }
  }
  return false;
}

struct Property {
  std::string name;
  bool is_list = false;
  ScalarType count;  // lists only
  ScalarType value;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { kAscii, kLittle, kBig };

// The values of a PLY body, text or binary.
class PlyValues {
 public:
  PlyValues(const std::string& path, const std::string& bytes, size_t start, size_t line,
            Format format)
      : path_(path), bytes_(bytes), pos_(start), format_(format), tokens_(bytes, start, line) {}

  // A value of `type`: integers exactly (as double, which holds every 32-bit one).
  double next(const ScalarType& type) {
    if (format_ == Format::kAscii) return next_text(type);
    if (bytes_.size() - pos_ < size_t(type.size)) {
      fail(path_, "ends inside its data (byte " + std::to_string(bytes_.size()) + ")");
    }
    unsigned char b[8];
    for (int i = 0; i < type.size; ++i) {
      b[i] = static_cast<unsigned char>(
          bytes_[pos_ + (format_ == Format::kLittle ? i : type.size - 1 - i)]);
    }
    pos_ += type.size;
    std::uint64_t bits = 0;
    for (int i = type.size - 1; i >= 0; --i) bits = bits << 8 | b[i];
    if (type.kind == Kind::kFloat) {
      if (type.size == 4) {
        float value;
        const std::uint32_t bits32 = std::uint32_t(bits);
        std::memcpy(&value, &bits32, 4);
        return value;
      }
      double value;
      std::memcpy(&value, &bits, 8);
      return value;
    }
    if (type.kind == Kind::kUnsigned) return double(bits);
    const int shift = 64 - 8 * type.size;  // sign-extend
    return double(std::int64_t(bits << shift) >> shift);
  }

  // Bytes (binary) or characters (text) not read yet: what bounds every count.
  size_t left() const { return format_ == Format::kAscii ? tokens_.left() : bytes_.size() - pos_; }

  void expect_end() {
    if (format_ == Format::kAscii) {
      std::string_view token;
      if (tokens_.next(token)) {
        fail(path_, "line " + std::to_string(tokens_.line()) + ": " + shown(token) +
                        " after the last element the header declares");
      }
    } else if (pos_ != bytes_.size()) {
      fail(path_, "has " + std::to_string(bytes_.size() - pos_) +
                      " bytes after the last element the header declares");
    }
  }

 private:
  double next_text(const ScalarType& type) {
    std::string_view token;
    if (!tokens_.next(token)) fail(path_, "ends before the data its header declares");
    const auto at = [&] { return "line " + std::to_string(tokens_.line()) + ": "; };
    if (type.kind == Kind::kFloat) {
      double value;
      if (!parse_number(token, value)) fail(path_, at() + shown(token) + " is not a number");
      return value;
    }
    std::int64_t value;
    if (!parse_number(token, value)) fail(path_, at() + shown(token) + " is not a whole number");
    const std::int64_t bits = 8 * type.size;
    const std::int64_t low = type.kind == Kind::kSigned ? -(std::int64_t(1) << (bits - 1)) : 0;
    const std::int64_t high = type.kind == Kind::kSigned ? (std::int64_t(1) << (bits - 1)) - 1
                                                         : (std::int64_t(1) << bits) - 1;
    if (value < low || value > high) {
      fail(path_, at() + shown(token) + " is out of its property's type's range");
    }
    return double(value);
  }

  const std::string& path_;
  const std::string& bytes_;
  size_t pos_;
  Format format_;
  Tokens tokens_;
};

RawMesh parse_ply(const std::string& path, const std::string& bytes) {
  // The header: lines up to end_header.
  size_t pos = 0, line_number = 0;
  Format format = Format::kAscii;
  bool have_format = false;
  std::vector<Element> elements;
  const auto at = [&] { return "header line " + std::to_string(line_number) + ": "; };
  for (;;) {
    if (pos == bytes.size()) fail(path, "is not PLY: no end_header");
    const size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) fail(path, "is not PLY: no end_header");
    std::string_view line = std::string_view(bytes).substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_number;
    std::vector<std::string_view> words;
    for (size_t i = 0; i < line.size();) {
      while (i < line.size() && is_space(line[i])) ++i;
      const size_t begin = i;
      while (i < line.size() && !is_space(line[i])) ++i;
      if (i > begin) words.push_back(line.substr(begin, i - begin));
    }
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") fail(path, "is not PLY: the first line is not 'ply'");
      continue;
    }
    if (words.empty()) fail(path, at() + "is empty");
    const std::string_view keyword = words[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (words.size() != 1) fail(path, at() + "end_header followed by " + shown(words[1]));
      break;
    }
    if (keyword == "format") {
      if (have_format || line_number != 2) fail(path, at() + "format must be the second line, once");
      if (words.size() != 3 || words[2] != "1.0") {
        fail(path, at() + "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      if (words[1] == "ascii") {
        format = Format::kAscii;
      } else if (words[1] == "binary_little_endian") {
        format = Format::kLittle;
      } else if (words[1] == "binary_big_endian") {
        format = Format::kBig;
      } else {
        fail(path, at() + "unknown format " + shown(words[1]));
      }
      have_format = true;
      continue;
    }
    if (!have_format) fail(path, at() + "the format line must come second");
    if (keyword == "element") {
      Element element;
      if (words.size() != 3 || !parse_number(words[2], element.count)) {
        fail(path, at() + "expected 'element NAME COUNT' with a whole COUNT");
      }
      element.name = std::string(words[1]);
      for (const Element& other : elements) {
        if (other.name == element.name) fail(path, at() + "element " + shown(words[1]) + " twice");
      }
      elements.push_back(element);
      continue;
    }
    if (keyword == "property") {
      if (elements.empty()) fail(path, at() + "a property before any element");
      Property property;
      if (words.size() == 5 && words[1] == "list") {
        property.is_list = true;
        if (!scalar_type(words[2], property.count) || property.count.kind == Kind::kFloat ||
            !scalar_type(words[3], property.value)) {
          fail(path, at() + "a list needs an integer count type and a value type");
        }
        property.name = std::string(words[4]);
      } else if (words.size() == 3) {
        if (!scalar_type(words[1], property.value)) fail(path, at() + "unknown type " + shown(words[1]));
        property.name = std::string(words[2]);
      } else {
        fail(path, at() + "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      }
      elements.back().properties.push_back(property);
      continue;
    }
    fail(path, at() + "unknown keyword " + shown(keyword));
  }

  // What the mesh needs from the elements: vertex x y z (nx ny nz), face vertex_indices.
  const Element* vertices = nullptr;
  for (const Element& element : elements) {
    if (element.count > 0 && element.properties.empty()) {
      fail(path, "element " + shown(element.name) + " has a count but no property");
    }
    if (element.name == "vertex") vertices = &element;
  }
  if (vertices == nullptr) fail(path, "has no vertex element");
  const auto find = [](const Element& element, const char* name) {
    for (size_t i = 0; i < element.properties.size(); ++i) {
      if (element.properties[i].name == name && !element.properties[i].is_list) return int(i);
    }
    return -1;
  };
  const int x = find(*vertices, "x"), y = find(*vertices, "y"), z = find(*vertices, "z");
  if (x < 0 || y < 0 || z < 0) fail(path, "its vertex element lacks one of the properties x, y, z");
  const int nx = find(*vertices, "nx"), ny = find(*vertices, "ny"), nz = find(*vertices, "nz");
  const bool have_normals = nx >= 0 && ny >= 0 && nz >= 0;

  PlyValues values(path, bytes, pos, line_number + 1, format);
  RawMesh mesh;
  std::vector<Eigen::Vector3f> vertex_normals;
  std::vector<std::uint32_t> polygon;
  for (const Element& element : elements) {
    // Every value takes at least one byte (binary) or one character and a separator
    // (text): a count beyond that is refused before anything is allocated.
    size_t least = 0;
    for (const Property& property : element.properties) {
      least += format == Format::kAscii ? 1 : size_t(property.is_list ? property.count.size
                                                                      : property.value.size);
    }
    if (element.count > values.left() / std::max<size_t>(least, 1)) {
      fail(path, "its header declares " + std::to_string(element.count) + " " +
                     shown(element.name) + " elements, more than the file's " +
                     std::to_string(bytes.size()) + " bytes can hold");
    }
    const bool is_vertex = &element == vertices;
    const bool is_face = element.name == "face";
    int face_list = -1;
    if (is_face) {
      for (size_t i = 0; i < element.properties.size(); ++i) {
        const Property& property = element.properties[i];
        if (property.is_list && (property.name == "vertex_indices" || property.name == "vertex_index")) {
          face_list = int(i);
        }
      }
      if (face_list < 0) fail(path, "its face element has no vertex_indices list");
      if (element.properties[face_list].value.kind == Kind::kFloat) {
        fail(path, "its face indices are not of an integer type");
      }
    }
    if (is_vertex) {
      if (x >= 64 || y >= 64 || z >= 64 || (have_normals && (nx >= 64 || ny >= 64 || nz >= 64))) {
        fail(path, "its vertex element has over 64 properties before x, y, z or the normals");
      }
      mesh.positions.reserve(element.count);
      if (have_normals) vertex_normals.reserve(element.count);
    }
    for (std::uint64_t e = 0; e < element.count; ++e) {
      double scalar[64];  // the first 64 scalar properties of a vertex; more are skipped
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.is_list) {
          const double value = values.next(property.value);
          if (p < 64) scalar[p] = value;
          continue;
        }
        const double count = values.next(property.count);
        if (!(count >= 0) || count > double(values.left())) {
          fail(path, shown(element.name) + " " + std::to_string(e) + ": a list of " +
                         std::to_string(count) + " values, negative or beyond the file's end");
        }
        const bool indices = is_face && int(p) == face_list;
        if (indices) polygon.clear();
        for (std::uint64_t i = 0; i < std::uint64_t(count); ++i) {
          const double value = values.next(property.value);
          if (!indices) continue;
          if (value < 0 || value >= double(std::numeric_limits<std::uint32_t>::max())) {
            fail(path, "face " + std::to_string(e) + " has a vertex index out of range");
          }
          polygon.push_back(std::uint32_t(value));
        }
        // Points and lines (fewer than 3 corners) have no surface: skipped.
        for (size_t k = 1; indices && k + 1 < polygon.size(); ++k) {
          mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
        }
      }
      if (is_vertex) {
        checked_index(path, mesh.positions.size());
        mesh.positions.emplace_back(float(scalar[x]), float(scalar[y]), float(scalar[z]));
        if (have_normals) vertex_normals.emplace_back(float(scalar[nx]), float(scalar[ny]), float(scalar[nz]));
      }
    }
  }
  values.expect_end();
  if (have_normals) {
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t v : mesh.triangles[t]) {
        if (v >= vertex_normals.size()) {
          fail(path, "triangle " + std::to_string(t) + " has a vertex index out of range");
        }
        mesh.corner_normals.push_back(vertex_normals[v]);
      }
    }
  }
  return mesh;
}

}  // namespace

RawMesh read_stl(const std::string& path, const std::string& bytes) {
  // Binary when the size is exactly what the facet count in its header needs (a binary
  // header may begin with "solid" too); otherwise ASCII, which begins with "solid".
  if (bytes.size() >= 84) {
    const std::uint32_t facets = little_u32(bytes.data() + 80);
    if (std::uint64_t(bytes.size()) == 84 + 50 * std::uint64_t(facets)) {
      return read_binary_stl(path, bytes, facets);
    }
  }
  size_t start = 0;
  while (start < bytes.size() && is_space(bytes[start])) ++start;
  if (bytes.compare(start, 5, "solid") == 0) return read_ascii_stl(path, bytes, start);
  if (bytes.size() < 84) {
    fail(path, "is neither binary STL (" + std::to_string(bytes.size()) +
                   " bytes, under the 84 of its header) nor ASCII STL (no 'solid' at the start)");
  }
  const std::uint32_t facets = little_u32(bytes.data() + 80);
  fail(path, "is neither binary STL (" + std::to_string(bytes.size()) + " bytes where the " +
                 std::to_string(facets) + " facets of its header need " +
                 std::to_string(84 + 50 * std::uint64_t(facets)) +
                 ") nor ASCII STL (no 'solid' at the start)");
}

RawMesh read_ply(const std::string& path, const std::string& bytes) {
  return parse_ply(path, bytes);
}

RawMesh read_obj(const std::string& path, const std::string& bytes) {
  RawMesh mesh;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::array<std::int64_t, 2>> corners;  // position, normal (-1: none)
  bool every_corner_has_a_normal = true;
  size_t line_number = 0;
  std::vector<std::string_view> words;
  for (size_t pos = 0; pos < bytes.size();) {
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::string_view line = std::string_view(bytes).substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    words.clear();
    for (size_t i = 0; i < line.size();) {
      while (i < line.size() && is_space(line[i])) ++i;
      const size_t begin = i;
      while (i < line.size() && !is_space(line[i])) ++i;
      if (i > begin) words.push_back(line.substr(begin, i - begin));
    }
    if (words.empty()) continue;
    const std::string at = "line " + std::to_string(line_number) + ": ";
    const auto vector_of = [&](size_t least, size_t most) {
      if (words.size() < least + 1 || words.size() > most + 1) {
        fail(path, at + shown(words[0]) + " needs " + std::to_string(least) +
                       (least == most ? "" : " to " + std::to_string(most)) + " numbers");
      }
      float v[3];
      for (size_t i = 0; i < 3; ++i) {
        if (!parse_number(words[i + 1], v[i])) fail(path, at + shown(words[i + 1]) + " is not a number");
      }
      for (size_t i = 4; i < words.size(); ++i) {  // w, or a colour: checked, not kept
        float ignored;
        if (!parse_number(words[i], ignored)) fail(path, at + shown(words[i]) + " is not a number");
      }
      return Eigen::Vector3f(v[0], v[1], v[2]);
    };
    if (words[0] == "v") {
      checked_index(path, mesh.positions.size());
      mesh.positions.push_back(vector_of(3, 7));  // x y z, then w or r g b (extensions)
    } else if (words[0] == "vn") {
      checked_index(path, normals.size());
      normals.push_back(vector_of(3, 3));
    } else if (words[0] == "f") {
      corners.clear();
      for (size_t i = 1; i < words.size(); ++i) {
        // v, v/vt, v/vt/vn or v//vn; 1-based, or negative: counted back from the last.
        std::string_view parts[3];
        size_t n_parts = 0;
        std::string_view rest = words[i];
        for (;;) {
          const size_t slash = rest.find('/');
          if (n_parts == 2 && slash != std::string_view::npos) {
            fail(path, at + shown(words[i]) + " is not a face corner (v, v/vt, v/vt/vn, v//vn)");
          }
          parts[n_parts++] = rest.substr(0, slash);
          if (slash == std::string_view::npos) break;
          rest = rest.substr(slash + 1);
        }
        const auto resolve = [&](std::string_view text, size_t count, const char* what) {
          std::int64_t index;
          if (!parse_number(text, index) || index == 0) {
            fail(path, at + shown(words[i]) + ": " + what + " index " + shown(text) +
                           " is not a non-zero whole number");
          }
          const std::int64_t resolved = index > 0 ? index - 1 : std::int64_t(count) + index;
          if (resolved < 0 || resolved >= std::int64_t(count)) {
            fail(path, at + what + " index " + std::to_string(index) + " is out of range (" +
                           std::to_string(count) + " so far)");
          }
          return resolved;
        };
        const std::int64_t position = resolve(parts[0], mesh.positions.size(), "vertex");
        std::int64_t normal = -1;
        if (n_parts == 3 && !parts[2].empty()) normal = resolve(parts[2], normals.size(), "normal");
        if (n_parts >= 2 && !parts[1].empty()) {
          std::int64_t texture;  // texture coordinates are not kept, but must be numbers
          if (!parse_number(parts[1], texture)) {
            fail(path, at + shown(words[i]) + ": texture index is not a whole number");
          }
        }
        corners.push_back({position, normal});
      }
      for (size_t k = 1; k + 1 < corners.size(); ++k) {
        const size_t fan[3] = {0, k, k + 1};
        std::array<std::uint32_t, 3> triangle;
        for (int c = 0; c < 3; ++c) {
          triangle[c] = std::uint32_t(corners[fan[c]][0]);
          if (corners[fan[c]][1] < 0) {
            every_corner_has_a_normal = false;
          } else if (every_corner_has_a_normal) {
            mesh.corner_normals.push_back(normals[size_t(corners[fan[c]][1])]);
          }
        }
        mesh.triangles.push_back(triangle);
      }
    }
    // Anything else (vt, l, p, g, o, s, usemtl, mtllib, ...) has nothing for the mesh.
  }
  if (!every_corner_has_a_normal) mesh.corner_normals.clear();
  return mesh;
}

}  // namespace flexsight::mesh_files

// PLY, ASCII and binary of either byte order (mesh_files.h read_ply): the header's
// elements and properties, then the body element by element.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "host/render/mesh_file_text.h"
#include "host/render/mesh_files.h"

namespace flexsight::mesh_files {
namespace {

// The helpers every reader shares (mesh_file_text.h).
using namespace detail;

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

// ------------------------------------------------------------------------------ header

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  size_t body_start = 0;  // the byte after end_header's line
  size_t lines = 0;       // the header's lines, end_header's included
};

using Words = std::vector<std::string_view>;

Format format_of_line(const std::string& path, const std::string& at, const Words& words) {
  if (words.size() != 3 || words[2] != "1.0") {
    fail(path, at + "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  }
  if (words[1] == "ascii") return Format::kAscii;
  if (words[1] == "binary_little_endian") return Format::kLittle;
  if (words[1] == "binary_big_endian") return Format::kBig;
  fail(path, at + "unknown format " + shown(words[1]));
}

void add_element(const std::string& path, const std::string& at, const Words& words,
                 std::vector<Element>& elements) {
  Element element;
  if (words.size() != 3 || !parse_number(words[2], element.count)) {
    fail(path, at + "expected 'element NAME COUNT' with a whole COUNT");
  }
  element.name = std::string(words[1]);
  for (const Element& other : elements) {
    if (other.name == element.name) fail(path, at + "element " + shown(words[1]) + " twice");
  }
  elements.push_back(element);
}

void add_property(const std::string& path, const std::string& at, const Words& words,
                  std::vector<Element>& elements) {
  if (elements.empty()) fail(path, at + "a property before any element");
  Property property;
  if (words.size() == 5 && words[1] == "list") {
    property.is_list = true;
    if (!scalar_type(words[2], property.count) || property.count.kind == Kind::kFloat ||
        !scalar_type(words[3], property.value)) {
      fail(path, at + "a list needs an integer count type and a value type");
    }
    property.name = std::string(words[4]);
  } else if (words.size() == 3) {
    if (!scalar_type(words[1], property.value)) fail(path, at + "unknown type " + shown(words[1]));
    property.name = std::string(words[2]);
  } else {
    fail(path, at + "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
  }
  elements.back().properties.push_back(property);
}

// The header: lines up to end_header.
Header read_header(const std::string& path, const std::string& bytes) {
  Header header;
  size_t pos = 0, line_number = 0;
  bool have_format = false;
  Words words;
  for (;;) {
    if (pos == bytes.size()) fail(path, "is not PLY: no end_header");
    const size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) fail(path, "is not PLY: no end_header");
    std::string_view line = std::string_view(bytes).substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_number;
    detail::split_words(line, words);
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") fail(path, "is not PLY: the first line is not 'ply'");
      continue;
    }
    const std::string at = "header line " + std::to_string(line_number) + ": ";
    if (words.empty()) fail(path, at + "is empty");
    const std::string_view keyword = words[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (words.size() != 1) fail(path, at + "end_header followed by " + shown(words[1]));
      break;
    }
    if (keyword == "format") {
      if (have_format || line_number != 2) fail(path, at + "format must be the second line, once");
      header.format = format_of_line(path, at, words);
      have_format = true;
      continue;
    }
    if (!have_format) fail(path, at + "the format line must come second");
    if (keyword == "element") {
      add_element(path, at, words, header.elements);
    } else if (keyword == "property") {
      add_property(path, at, words, header.elements);
    } else {
      fail(path, at + "unknown keyword " + shown(keyword));
    }
  }
  header.body_start = pos;
  header.lines = line_number;
  return header;
}

// What the mesh needs of the vertex element: x y z (nx ny nz), as property numbers.
struct VertexLayout {
  const Element* element = nullptr;
  int x = -1, y = -1, z = -1;
  int nx = -1, ny = -1, nz = -1;
  bool have_normals = false;
};

int scalar_property(const Element& element, const char* name) {
  for (size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name && !element.properties[i].is_list) return int(i);
  }
  return -1;
}

VertexLayout vertex_layout(const std::string& path, const std::vector<Element>& elements) {
  VertexLayout layout;
  for (const Element& element : elements) {
    if (element.count > 0 && element.properties.empty()) {
      fail(path, "element " + shown(element.name) + " has a count but no property");
    }
    if (element.name == "vertex") layout.element = &element;
  }
  if (layout.element == nullptr) fail(path, "has no vertex element");
  const Element& vertices = *layout.element;
  layout.x = scalar_property(vertices, "x");
  layout.y = scalar_property(vertices, "y");
  layout.z = scalar_property(vertices, "z");
  if (layout.x < 0 || layout.y < 0 || layout.z < 0) {
    fail(path, "its vertex element lacks one of the properties x, y, z");
  }
  layout.nx = scalar_property(vertices, "nx");
  layout.ny = scalar_property(vertices, "ny");
  layout.nz = scalar_property(vertices, "nz");
  layout.have_normals = layout.nx >= 0 && layout.ny >= 0 && layout.nz >= 0;
  return layout;
}

// The face element's list of vertex indices, as a property number.
int face_list_property(const std::string& path, const Element& element) {
  int face_list = -1;
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
  return face_list;
}

// ------------------------------------------------------------------------------ body

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

// Reads the body after the header into a mesh, element by element.
class BodyReader {
 public:
  BodyReader(const std::string& path, const std::string& bytes, const Header& header,
             const VertexLayout& layout)
      : path_(path),
        bytes_(bytes),
        header_(header),
        layout_(layout),
        values_(path, bytes, header.body_start, header.lines + 1, header.format) {}

  RawMesh read() {
    for (const Element& element : header_.elements) read_element(element);
    values_.expect_end();
    if (layout_.have_normals) add_corner_normals();
    return std::move(mesh_);
  }

 private:
  // Every value takes at least one byte (binary) or one character and a separator
  // (text): a count beyond that is refused before anything is allocated.
  void check_count(const Element& element) {
    size_t least = 0;
    for (const Property& property : element.properties) {
      least += header_.format == Format::kAscii
                   ? 1
                   : size_t(property.is_list ? property.count.size : property.value.size);
    }
    if (element.count > values_.left() / std::max<size_t>(least, 1)) {
      fail(path_, "its header declares " + std::to_string(element.count) + " " +
                      shown(element.name) + " elements, more than the file's " +
                      std::to_string(bytes_.size()) + " bytes can hold");
    }
  }

  void read_element(const Element& element) {
    check_count(element);
    const bool is_vertex = &element == layout_.element;
    const bool is_face = element.name == "face";
    const int face_list = is_face ? face_list_property(path_, element) : -1;
    if (is_vertex) {
      const VertexLayout& v = layout_;
      if (v.x >= 64 || v.y >= 64 || v.z >= 64 ||
          (v.have_normals && (v.nx >= 64 || v.ny >= 64 || v.nz >= 64))) {
        fail(path_, "its vertex element has over 64 properties before x, y, z or the normals");
      }
      mesh_.positions.reserve(element.count);
      if (v.have_normals) vertex_normals_.reserve(element.count);
    }
    for (std::uint64_t e = 0; e < element.count; ++e) read_one(element, e, is_vertex, face_list);
  }

  // Element number `e`; `face_list` is the property of a face's indices (-1: not a face).
  void read_one(const Element& element, std::uint64_t e, bool is_vertex, int face_list) {
    double scalar[64];  // the first 64 scalar properties of a vertex; more are skipped
    for (size_t p = 0; p < element.properties.size(); ++p) {
      const Property& property = element.properties[p];
      if (!property.is_list) {
        const double value = values_.next(property.value);
        if (p < 64) scalar[p] = value;
        continue;
      }
      read_list(element, e, property, face_list >= 0 && int(p) == face_list);
    }
    if (is_vertex) {
      const VertexLayout& v = layout_;
      checked_index(path_, mesh_.positions.size());
      mesh_.positions.emplace_back(float(scalar[v.x]), float(scalar[v.y]), float(scalar[v.z]));
      if (v.have_normals) {
        vertex_normals_.emplace_back(float(scalar[v.nx]), float(scalar[v.ny]), float(scalar[v.nz]));
      }
    }
  }

  // A list property; a face's vertex indices (`indices`) become a fan of triangles.
  void read_list(const Element& element, std::uint64_t e, const Property& property, bool indices) {
    const double count = values_.next(property.count);
    if (!(count >= 0) || count > double(values_.left())) {
      fail(path_, shown(element.name) + " " + std::to_string(e) + ": a list of " +
                      std::to_string(count) + " values, negative or beyond the file's end");
    }
    if (indices) polygon_.clear();
    for (std::uint64_t i = 0; i < std::uint64_t(count); ++i) {
      const double value = values_.next(property.value);
      if (!indices) continue;
      if (value < 0 || value >= double(std::numeric_limits<std::uint32_t>::max())) {
        fail(path_, "face " + std::to_string(e) + " has a vertex index out of range");
      }
      polygon_.push_back(std::uint32_t(value));
    }
    // Points and lines (fewer than 3 corners) have no surface: skipped.
    for (size_t k = 1; indices && k + 1 < polygon_.size(); ++k) {
      mesh_.triangles.push_back({polygon_[0], polygon_[k], polygon_[k + 1]});
    }
  }

  void add_corner_normals() {
    for (size_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (std::uint32_t v : mesh_.triangles[t]) {
        if (v >= vertex_normals_.size()) {
          fail(path_, "triangle " + std::to_string(t) + " has a vertex index out of range");
        }
        mesh_.corner_normals.push_back(vertex_normals_[v]);
      }
    }
  }

  const std::string& path_;
  const std::string& bytes_;
  const Header& header_;
  const VertexLayout& layout_;
  PlyValues values_;
  RawMesh mesh_;
  std::vector<Eigen::Vector3f> vertex_normals_;
  std::vector<std::uint32_t> polygon_;
};

}  // namespace

RawMesh read_ply(const std::string& path, const std::string& bytes) {
  const Header header = read_header(path, bytes);
  const VertexLayout layout = vertex_layout(path, header.elements);
  return BodyReader(path, bytes, header, layout).read();
}

}  // namespace flexsight::mesh_files

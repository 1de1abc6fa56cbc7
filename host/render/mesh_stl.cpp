// STL, binary and ASCII (mesh_files.h read_stl).
#include <cstdint>
#include <string>

#include "host/render/mesh_file_text.h"
#include "host/render/mesh_files.h"

namespace flexsight::mesh_files {
namespace {

// The helpers every reader shares (mesh_file_text.h).
using namespace detail;

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
  while (start < bytes.size() && detail::is_space(bytes[start])) ++start;
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

}  // namespace flexsight::mesh_files

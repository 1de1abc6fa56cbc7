// Wavefront OBJ: v, vn and f lines (mesh_files.h read_obj).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "host/render/mesh_file_text.h"
#include "host/render/mesh_files.h"

namespace flexsight::mesh_files {
namespace {

// The helpers every reader shares (mesh_file_text.h).
using namespace detail;

using Words = std::vector<std::string_view>;
using Corner = std::array<std::int64_t, 2>;  // position, normal (-1: none)

// The vector of a v or vn line of `least` to `most` numbers: its first three.
Eigen::Vector3f parse_vector(const std::string& path, const std::string& at, const Words& words,
                             size_t least, size_t most) {
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
}

// A 1-based or negative (counted back from the last) index of a face corner, 0-based.
std::int64_t resolve_index(const std::string& path, const std::string& at, std::string_view corner,
                           std::string_view text, size_t count, const char* what) {
  std::int64_t index;
  if (!parse_number(text, index) || index == 0) {
    fail(path, at + shown(corner) + ": " + what + " index " + shown(text) +
                   " is not a non-zero whole number");
  }
  const std::int64_t resolved = index > 0 ? index - 1 : std::int64_t(count) + index;
  if (resolved < 0 || resolved >= std::int64_t(count)) {
    fail(path, at + what + " index " + std::to_string(index) + " is out of range (" +
                   std::to_string(count) + " so far)");
  }
  return resolved;
}

// One corner of an f line: v, v/vt, v/vt/vn or v//vn.
Corner parse_corner(const std::string& path, const std::string& at, std::string_view word,
                    size_t positions, size_t normals) {
  std::string_view parts[3];
  size_t n_parts = 0;
  std::string_view rest = word;
  for (;;) {
    const size_t slash = rest.find('/');
    if (n_parts == 2 && slash != std::string_view::npos) {
      fail(path, at + shown(word) + " is not a face corner (v, v/vt, v/vt/vn, v//vn)");
    }
    parts[n_parts++] = rest.substr(0, slash);
    if (slash == std::string_view::npos) break;
    rest = rest.substr(slash + 1);
  }
  const std::int64_t position = resolve_index(path, at, word, parts[0], positions, "vertex");
  std::int64_t normal = -1;
  if (n_parts == 3 && !parts[2].empty()) normal = resolve_index(path, at, word, parts[2], normals, "normal");
  if (n_parts >= 2 && !parts[1].empty()) {
    std::int64_t texture;  // texture coordinates are not kept, but must be numbers
    if (!parse_number(parts[1], texture)) {
      fail(path, at + shown(word) + ": texture index is not a whole number");
    }
  }
  return {position, normal};
}

// A face's fan of triangles from its first corner, with the corners' normals while every
// corner so far has one.
void add_fan(const std::vector<Corner>& corners, const std::vector<Eigen::Vector3f>& normals,
             bool& every_corner_has_a_normal, RawMesh& mesh) {
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

}  // namespace

RawMesh read_obj(const std::string& path, const std::string& bytes) {
  RawMesh mesh;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Corner> corners;
  bool every_corner_has_a_normal = true;
  size_t line_number = 0;
  Words words;
  for (size_t pos = 0; pos < bytes.size();) {
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::string_view line = std::string_view(bytes).substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    detail::split_words(line, words);
    if (words.empty()) continue;
    const std::string at = "line " + std::to_string(line_number) + ": ";
    if (words[0] == "v") {
      checked_index(path, mesh.positions.size());
      mesh.positions.push_back(parse_vector(path, at, words, 3, 7));  // x y z, then w or r g b (extensions)
    } else if (words[0] == "vn") {
      checked_index(path, normals.size());
      normals.push_back(parse_vector(path, at, words, 3, 3));
    } else if (words[0] == "f") {
      corners.clear();
      for (size_t i = 1; i < words.size(); ++i) {
        corners.push_back(parse_corner(path, at, words[i], mesh.positions.size(), normals.size()));
      }
      add_fan(corners, normals, every_corner_has_a_normal, mesh);
    }
    // Anything else (vt, l, p, g, o, s, usemtl, mtllib, ...) has nothing for the mesh.
  }
  if (!every_corner_has_a_normal) mesh.corner_normals.clear();
  return mesh;
}

}  // namespace flexsight::mesh_files

#pragma once
// Our own readers of the three mesh formats load_mesh takes (STL binary and ASCII, PLY
// ASCII and binary, OBJ), in place of Assimp: Debian's Assimp 5.2 aborts on an
// assertion, leaks and hangs on malformed PLY files (docs/reliability.md, finding 6), and
// nothing checked before it can promise it will not. These read the whole file into
// memory, check every count against the bytes there are before allocating, and throw
// InputError naming the file and the line or byte for anything they do not take.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace flexsight::mesh_files {

// What a file holds before joining and normals (host/render/mesh.cpp build_mesh).
struct RawMesh {
  std::vector<Eigen::Vector3f> positions;
  // Polygons are cut into fans of triangles from their first corner (the files of this
  // project hold triangles; a fan is exact for convex polygons). Indices are checked
  // against positions by build_mesh.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // Three per triangle when the file gives a normal at every corner (PLY nx ny nz, OBJ
  // vn on every face corner); empty otherwise (every STL: its normals are per facet).
  std::vector<Eigen::Vector3f> corner_normals;
};

// `bytes` is the file's content, `path` names it in messages. Each format's reader is in
// its own file: mesh_stl.cpp, mesh_ply.cpp, mesh_obj.cpp (what they share: mesh_file_text.h).
RawMesh read_stl(const std::string& path, const std::string& bytes);
RawMesh read_ply(const std::string& path, const std::string& bytes);
RawMesh read_obj(const std::string& path, const std::string& bytes);
// The reader of `extension` (lower case: .stl, .ply or .obj); any other is an InputError.
RawMesh read_mesh(const std::string& path, const std::string& bytes, const std::string& extension);

}  // namespace flexsight::mesh_files

#pragma once
// Triangle meshes of CAD parts: read from STL, PLY or OBJ, in the file's units
// (millimetres for every part of this project; never rescaled), with what the renderer
// and the pose metrics need beside the triangles: shading normals, bounding box and
// diameter.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace flexsight {

struct MeshOptions {
  // Where a file has no per-vertex normals (every STL: it stores one normal per facet),
  // the shading normal at a triangle corner averages the normals of the triangles
  // around that vertex whose normal lies within this angle of the corner's own
  // triangle. Across a sharper edge each side keeps its own normal, so a tessellated
  // cylinder shades smoothly and the edge of a box stays sharp. On the T-LESS parts the
  // angles between neighbouring facets fall in two groups, below 20 degrees (tessellated
  // curved surfaces) and 45 / 90 degrees (chamfers and edges of the part), with very
  // few edges between 25 and 40 degrees: 30 separates them.
  float crease_degrees = 30.0f;
};

struct Mesh {
  // The file it was read from (or the name given to make_mesh), for messages.
  std::string source;
  // Vertex positions in the file's units, identical vertices joined, so that
  // neighbouring triangles share their vertices exactly (no cracks for the ray caster).
  std::vector<Eigen::Vector3f> positions;
  // Indices into positions, counter-clockwise seen from outside (the STL convention).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // One unit normal per triangle, from its winding.
  std::vector<Eigen::Vector3f> face_normals;
  // Three unit shading normals per triangle (corner k of triangle t at 3 t + k): the
  // file's vertex normals where it has them, crease-angle normals otherwise.
  std::vector<Eigen::Vector3f> corner_normals;
  // Axis-aligned box of the positions.
  Eigen::AlignedBox3f bounds;
  // Largest distance between two vertices (the "diameter" of the ADD/ADD-S metrics).
  float diameter = 0.0f;
};

// Reads an STL (binary or ASCII), PLY (ASCII or binary) or OBJ file with the project's
// own readers (host/render/mesh_files.h; not Assimp, which crashes and hangs on
// malformed files): polygons are cut into triangle fans, points and lines dropped, identical positions joined, triangles whose
// corners coincide dropped. Throws InputError naming `path` when it does not exist,
// cannot be read or parsed, or has no triangle.
Mesh load_mesh(const std::string& path, const MeshOptions& options = {});

// A mesh from positions and triangles given in memory (test shapes, the bin's walls),
// with the same joining, normals, box and diameter as load_mesh. `source` names it in
// messages; throws InputError naming it for an index out of range, a position that is
// not finite or has a coordinate beyond 1e9 (load_mesh too), or no triangle left.
Mesh make_mesh(const std::string& source, std::vector<Eigen::Vector3f> positions,
               std::vector<std::array<std::uint32_t, 3>> triangles,
               const MeshOptions& options = {});

// The exact largest distance between two of the points (0 for fewer than two). A
// branch and bound over a tree of boxes: the few box pairs whose farthest corners could
// beat the best distance so far are opened, so the cost is far below the n^2 / 2 pairs.
float point_set_diameter(const std::vector<Eigen::Vector3f>& points);

}  // namespace flexsight

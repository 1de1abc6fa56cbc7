#include "host/render/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "host/io/input_error.h"
#include "host/render/mesh_files.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;
using Triangle = std::array<std::uint32_t, 3>;
constexpr float kMaxCoordinate = 1e9f;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Exact position key: the three floats' bits, with -0 read as +0 so that a vertex
// written as "-0.0" joins its "0.0" twin.
struct PositionKey {
  std::uint32_t bits[3];
  bool operator==(const PositionKey& other) const {
    return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
  }
};

struct PositionKeyHash {
  size_t operator()(const PositionKey& key) const {
    std::uint64_t h = 1469598103934665603ULL;
    for (std::uint32_t b : key.bits) h = (h ^ b) * 1099511628211ULL;
    return static_cast<size_t>(h);
  }
};

PositionKey key_of(const Eigen::Vector3f& p) {
  PositionKey key;
  for (int i = 0; i < 3; ++i) {
    const float v = p[i] == 0.0f ? 0.0f : p[i];
    std::memcpy(&key.bits[i], &v, 4);
  }
  return key;
}

// Interior angle of the triangle (a, b, c) at a; atan2 stays accurate for thin triangles
// where acos of a dot product would not.
float corner_angle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
  const Eigen::Vector3f u = b - a, v = c - a;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

// Crease-angle normals, weighted by the corner angle of each contributing triangle
// (Thürmer and Wüthrich 1998): unlike area weights, they do not lean towards the long
// thin triangles that CAD tessellations put along cylinders.
std::vector<Eigen::Vector3f> crease_normals(const Mesh& mesh, float crease_degrees) {
  const size_t n_vertices = mesh.positions.size();
  const size_t n_triangles = mesh.triangles.size();
  // Corners around each vertex, as compressed rows.
  std::vector<std::uint32_t> start(n_vertices + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) ++start[v + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> corners(3 * n_triangles);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < n_triangles; ++t)
    for (int k = 0; k < 3; ++k) corners[fill[mesh.triangles[t][k]]++] = std::uint32_t(3 * t + k);

  std::vector<float> angle(3 * n_triangles);
  for (size_t t = 0; t < n_triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto& tri = mesh.triangles[t];
      angle[3 * t + k] = corner_angle(mesh.positions[tri[k]], mesh.positions[tri[(k + 1) % 3]],
                                      mesh.positions[tri[(k + 2) % 3]]);
    }
  }

  const float cos_crease = std::cos(crease_degrees * float(M_PI) / 180.0f);
  std::vector<Eigen::Vector3f> normals(3 * n_triangles);
  for (size_t t = 0; t < n_triangles; ++t) {
    const Eigen::Vector3f& own = mesh.face_normals[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      for (std::uint32_t i = start[v]; i < start[v + 1]; ++i) {
        const std::uint32_t other = corners[i] / 3;
        const Eigen::Vector3f& n = mesh.face_normals[other];
        if (other == t || own.dot(n) >= cos_crease) sum += angle[corners[i]] * n;
      }
      const float length = sum.norm();
      normals[3 * t + k] = length > 0.0f ? Eigen::Vector3f(sum / length) : own;
    }
  }
  return normals;
}

// Joins identical positions, drops triangles with coinciding corners or no area, and
// fills in normals, box and diameter. `file_normals`, when given, holds three normals
// per input triangle.
Mesh build_mesh(const std::string& source, const std::vector<Eigen::Vector3f>& raw_positions,
                const std::vector<Triangle>& raw_triangles,
                const std::vector<Eigen::Vector3f>* file_normals, const MeshOptions& options) {
  Mesh mesh;
  mesh.source = source;
  for (const Eigen::Vector3f& p : raw_positions) {
    if (!p.allFinite()) throw InputError(source, "has a vertex that is not a finite number");
    // Beyond this, normals and the diameter overflow a float (found by fuzz_mesh: a
    // vertex at 2.6e38 gave an infinite diameter). 1e9 mm is 1000 km.
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate) {
      throw InputError(source, "has a vertex coordinate beyond 1e9 (in the file's units, mm: 1000 km)");
    }
  }
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> index_of;
  std::vector<std::uint32_t> remap(raw_positions.size());
  for (size_t i = 0; i < raw_positions.size(); ++i) {
    auto [it, inserted] =
        index_of.emplace(key_of(raw_positions[i]), std::uint32_t(mesh.positions.size()));
    if (inserted) mesh.positions.push_back(raw_positions[i]);
    remap[i] = it->second;
  }

  std::vector<Eigen::Vector3f> kept_file_normals;
  for (size_t t = 0; t < raw_triangles.size(); ++t) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      if (raw_triangles[t][k] >= raw_positions.size()) {
        throw InputError(source,
                         "triangle " + std::to_string(t) + " has a vertex index out of range");
      }
      tri[k] = remap[raw_triangles[t][k]];
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    const Eigen::Vector3f& a = mesh.positions[tri[0]];
    const Eigen::Vector3f normal = (mesh.positions[tri[1]] - a).cross(mesh.positions[tri[2]] - a);
    const float length = normal.norm();
    if (!(length > 0.0f)) continue;  // collinear corners: no surface to hit or shade
    mesh.triangles.push_back(tri);
    mesh.face_normals.push_back(normal / length);
    if (file_normals != nullptr) {
      for (int k = 0; k < 3; ++k) kept_file_normals.push_back((*file_normals)[3 * t + k]);
    }
  }
  if (mesh.triangles.empty()) throw InputError(source, "has no triangles");

  // Positions that no kept triangle uses go: the box and the diameter describe the
  // surface that is rendered, and the pose metrics sample the same vertices.
  std::vector<std::uint32_t> compact(mesh.positions.size(), UINT32_MAX);
  std::vector<Eigen::Vector3f> used;
  for (Triangle& tri : mesh.triangles) {
    for (std::uint32_t& v : tri) {
      if (compact[v] == UINT32_MAX) {
        compact[v] = std::uint32_t(used.size());
        used.push_back(mesh.positions[v]);
      }
      v = compact[v];
    }
  }
  mesh.positions = std::move(used);

  if (file_normals != nullptr) {
    mesh.corner_normals = std::move(kept_file_normals);
    for (size_t c = 0; c < mesh.corner_normals.size(); ++c) {
      Eigen::Vector3f& n = mesh.corner_normals[c];
      const float length = n.norm();
      // A zero or broken file normal falls back to its triangle's own.
      n = (std::isfinite(length) && length > 0.0f) ? Eigen::Vector3f(n / length)
                                                   : mesh.face_normals[c / 3];
    }
  } else {
    mesh.corner_normals = crease_normals(mesh, options.crease_degrees);
  }

  for (const Eigen::Vector3f& p : mesh.positions) mesh.bounds.extend(p);
  mesh.diameter = point_set_diameter(mesh.positions);
  return mesh;
}

// ---------------------------------------------------------------- exact diameter

struct Box {
  Eigen::Vector3d lo, hi;
};

struct Node {
  Box box;
  std::uint32_t begin, end;  // range of the ordered point indices
  std::int32_t left = -1, right = -1;
};

double max_distance2(const Box& a, const Box& b) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double d = std::max(a.hi[i] - b.lo[i], b.hi[i] - a.lo[i]);
    sum += d * d;
  }
  return sum;
}

class DiameterSearch {
 public:
  explicit DiameterSearch(const std::vector<Eigen::Vector3f>& points) {
    points_.reserve(points.size());
    for (const auto& p : points) points_.push_back(p.cast<double>());
    order_.resize(points_.size());
    std::iota(order_.begin(), order_.end(), 0u);
    build(0, std::uint32_t(points_.size()));
  }

  double run() {
    best2_ = double_sweep();
    visit(0, 0);
    return std::sqrt(best2_);
  }

 private:
  static constexpr std::uint32_t kLeafSize = 8;

  std::int32_t build(std::uint32_t begin, std::uint32_t end) {
    Node node;
    node.begin = begin;
    node.end = end;
    node.box.lo = node.box.hi = points_[order_[begin]];
    for (std::uint32_t i = begin; i < end; ++i) {
      node.box.lo = node.box.lo.cwiseMin(points_[order_[i]]);
      node.box.hi = node.box.hi.cwiseMax(points_[order_[i]]);
    }
    const std::int32_t id = std::int32_t(nodes_.size());
    nodes_.push_back(node);
    if (end - begin > kLeafSize) {
      int axis;
      (node.box.hi - node.box.lo).maxCoeff(&axis);
      const std::uint32_t mid = begin + (end - begin) / 2;
      std::nth_element(
          order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
          [&](std::uint32_t a, std::uint32_t b) { return points_[a][axis] < points_[b][axis]; });
      const std::int32_t left = build(begin, mid);
      const std::int32_t right = build(mid, end);
      nodes_[id].left = left;
      nodes_[id].right = right;
    }
    return id;
  }

  // A lower bound to start from: the farthest point from the farthest point from an
  // arbitrary one, repeated while it grows. Often already the diameter.
  double double_sweep() const {
    std::uint32_t from = 0;
    double best = 0.0;
    for (int round = 0; round < 4; ++round) {
      std::uint32_t far = from;
      double far2 = 0.0;
      for (std::uint32_t i = 0; i < points_.size(); ++i) {
        const double d2 = (points_[i] - points_[from]).squaredNorm();
        if (d2 > far2) far2 = d2, far = i;
      }
      if (far2 <= best) break;
      best = far2;
      from = far;
    }
    return best;
  }

  void visit(std::int32_t a, std::int32_t b) {
    const Node& na = nodes_[a];
    const Node& nb = nodes_[b];
    if (max_distance2(na.box, nb.box) <= best2_) return;
    const bool a_leaf = na.left < 0, b_leaf = nb.left < 0;
    if (a_leaf && b_leaf) {
      for (std::uint32_t i = na.begin; i < na.end; ++i) {
        for (std::uint32_t j = (a == b ? i + 1 : nb.begin); j < nb.end; ++j) {
          best2_ = std::max(best2_, (points_[order_[i]] - points_[order_[j]]).squaredNorm());
        }
      }
      return;
    }
    if (a == b) {
      visit(na.left, na.right);
      visit(na.left, na.left);
      visit(na.right, na.right);
      return;
    }
    // Open the larger box; visit the more promising child pair first so that the bound
    // rises early.
    const double size_a = (na.box.hi - na.box.lo).squaredNorm();
    const double size_b = (nb.box.hi - nb.box.lo).squaredNorm();
    const bool open_a = !a_leaf && (b_leaf || size_a >= size_b);
    const std::int32_t keep = open_a ? b : a;
    const Node& opened = open_a ? na : nb;
    std::int32_t first = opened.left, second = opened.right;
    if (max_distance2(nodes_[second].box, nodes_[keep].box) >
        max_distance2(nodes_[first].box, nodes_[keep].box)) {
      std::swap(first, second);
    }
    visit(first, keep);
    visit(second, keep);
  }

  std::vector<Eigen::Vector3d> points_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
  double best2_ = 0.0;
};

}  // namespace

float point_set_diameter(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0.0f;
  return static_cast<float>(DiameterSearch(points).run());
}

Mesh make_mesh(const std::string& source, std::vector<Eigen::Vector3f> positions,
               std::vector<Triangle> triangles, const MeshOptions& options) {
  return build_mesh(source, positions, triangles, nullptr, options);
}

Mesh load_mesh(const std::string& path, const MeshOptions& options) {
  std::error_code error;
  if (!fs::exists(path, error)) throw InputError(path, "does not exist");
  if (!fs::is_regular_file(path, error)) throw InputError(path, "is not a file");
  const std::string ext = lower_extension(path);
  if (ext != ".stl" && ext != ".ply" && ext != ".obj") {
    throw InputError(path, "is not a mesh file this reader knows (expected .stl, .ply or .obj)");
  }
  if (fs::file_size(path, error) == 0) throw InputError(path, "is empty");

  std::string bytes;
  {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError(path, "cannot be opened");
    std::ostringstream content;
    content << file.rdbuf();
    if (!file.good() && !file.eof()) throw InputError(path, "cannot be read");
    bytes = std::move(content).str();
  }
  // Our own readers, not Assimp (mesh_files.h says why). An STL's normals are one per
  // facet: no vertex normals, so the crease-angle ones are computed as for a file
  // without any.
  const mesh_files::RawMesh raw = mesh_files::read_mesh(path, bytes, ext);
  const bool use_file_normals =
      !raw.corner_normals.empty() && raw.corner_normals.size() == 3 * raw.triangles.size();
  return build_mesh(path, raw.positions, raw.triangles, use_file_normals ? &raw.corner_normals : nullptr,
                    options);
}

}  // namespace flexsight

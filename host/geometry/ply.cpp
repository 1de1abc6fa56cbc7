#include "host/geometry/ply.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

std::string ply_header(const PointCloud& cloud, PlyFormat format) {
  std::ostringstream header;
  header << "ply\n"
         << "format " << (format == PlyFormat::ascii ? "ascii" : "binary_little_endian")
         << " 1.0\n"
         << "comment FlexSight point cloud, unit " << cloud.unit
         << ", left camera frame (x right, y down, z forward)\n"
         << "element vertex " << cloud.size() << "\n"
         << "property float x\nproperty float y\nproperty float z\n"
         << "property float nx\nproperty float ny\nproperty float nz\n"
         << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (!cloud.confidence.empty()) header << "property float confidence\n";
  header << "end_header\n";
  return header.str();
}

// Little-endian whatever the host, like the PFM writer.
char* put_float(char* out, float value) {
  io_detail::encode_float_le(value, out);
  return out + 4;
}

void write_binary_vertices(std::ofstream& out, const PointCloud& cloud) {
  const bool with_confidence = !cloud.confidence.empty();
  const size_t stride = ply_vertex_bytes(with_confidence);
  std::vector<char> block;
  constexpr size_t kVerticesPerBlock = 4096;
  for (size_t begin = 0; begin < cloud.size(); begin += kVerticesPerBlock) {
    const size_t end = std::min(cloud.size(), begin + kVerticesPerBlock);
    block.resize((end - begin) * stride);
    char* cursor = block.data();
    for (size_t i = begin; i < end; ++i) {
      for (int k = 0; k < 3; ++k) cursor = put_float(cursor, cloud.points[i][k]);
      for (int k = 0; k < 3; ++k) cursor = put_float(cursor, cloud.normals[i][k]);
      for (int k = 0; k < 3; ++k) *cursor++ = static_cast<char>(cloud.colors[i][k]);
      if (with_confidence) cursor = put_float(cursor, cloud.confidence[i]);
    }
    out.write(block.data(), static_cast<std::streamsize>(block.size()));
  }
}

void write_ascii_vertices(std::ofstream& out, const PointCloud& cloud) {
  char line[256];
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    const Eigen::Vector3f& n = cloud.normals[i];
    const cv::Vec3b& c = cloud.colors[i];
    // %.9g round-trips a float exactly.
    int length = std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g %.9g %.9g %d %d %d", p[0],
                               p[1], p[2], n[0], n[1], n[2], c[0], c[1], c[2]);
    if (!cloud.confidence.empty()) {
      length += std::snprintf(line + length, sizeof line - length, " %.9g", cloud.confidence[i]);
    }
    out.write(line, length);
    out.put('\n');
  }
}

}  // namespace

size_t ply_vertex_bytes(bool with_confidence) { return 6 * 4 + 3 + (with_confidence ? 4 : 0); }

void write_ply(const std::string& path, const PointCloud& cloud, PlyFormat format) {
  const bool consistent = cloud.normals.size() == cloud.size() &&
                          cloud.colors.size() == cloud.size() &&
                          (cloud.confidence.empty() || cloud.confidence.size() == cloud.size());
  if (!consistent) throw InputError(path, "point cloud attributes differ in length");
  const std::string header = ply_header(cloud, format);
  write_atomically(path, [&](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "cannot be opened for writing");
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    if (format == PlyFormat::ascii) {
      write_ascii_vertices(out, cloud);
    } else {
      write_binary_vertices(out, cloud);
    }
    out.close();
    if (!out) throw InputError(path, "cannot be written (write error)");
  });
}

}  // namespace flexsight

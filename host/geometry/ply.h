#pragma once
// PLY point clouds (vertices only), as Open3D, PCL, MeshLab and CloudCompare read them.
#include <string>

#include "host/geometry/point_cloud.h"

namespace flexsight {

enum class PlyFormat { binary_little_endian, ascii };

// Vertex properties, in this order: float x y z, float nx ny nz, uchar red green blue,
// and float confidence when the cloud has confidences. Coordinates are in cloud.unit
// (stated in a comment line), left camera frame: x right, y down, z forward. Written
// under a temporary name and renamed. Throws InputError naming the file on failure.
void write_ply(const std::string& path, const PointCloud& cloud,
               PlyFormat format = PlyFormat::binary_little_endian);

// Bytes of one vertex in the binary format (27, or 31 with confidence).
size_t ply_vertex_bytes(bool with_confidence);

}  // namespace flexsight

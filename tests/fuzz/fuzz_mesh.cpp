// The mesh loader (host/render/mesh.h load_mesh: STL binary and ASCII, PLY ASCII and
// binary, OBJ, read by host/render/mesh_files.h, then our joining, normals, box and
// diameter). The input's first byte picks the extension (its value modulo 3: .stl, .ply,
// .obj); the rest is the file.
#include <cmath>

#include "host/render/mesh.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* names[] = {"mesh.stl", "mesh.ply", "mesh.obj"};
  const std::string path = fuzz::write_file(names[data[0] % 3], data + 1, size - 1);
  fuzz::expect_input_error_only([&] {
    const flexsight::Mesh mesh = flexsight::load_mesh(path);
    if (mesh.triangles.empty() || mesh.corner_normals.size() != 3 * mesh.triangles.size() ||
        !std::isfinite(mesh.diameter)) {
      std::abort();
    }
    for (const auto& triangle : mesh.triangles) {
      for (const auto index : triangle) {
        if (index >= mesh.positions.size()) std::abort();
      }
    }
  });
  return 0;
}

// The reader of a mesh file by its extension; each format's own is mesh_stl.cpp,
// mesh_ply.cpp or mesh_obj.cpp.
#include "host/render/mesh_files.h"

#include "host/render/mesh_file_text.h"

namespace flexsight::mesh_files {

RawMesh read_mesh(const std::string& path, const std::string& bytes, const std::string& extension) {
  if (extension == ".stl") return read_stl(path, bytes);
  if (extension == ".ply") return read_ply(path, bytes);
  if (extension == ".obj") return read_obj(path, bytes);
  detail::fail(path, "is not a mesh file this reader knows (expected .stl, .ply or .obj)");
}

}  // namespace flexsight::mesh_files

#pragma once
// The CAD parts a synthetic data set is made of: every mesh file of a folder, each with
// the object id its annotations carry, and the render scenes the generator reuses for
// them (scene_pool.h).
#include <memory>
#include <string>
#include <vector>

#include "host/render/mesh.h"
#include "host/synth/scene_pool.h"

namespace flexsight {

struct LibraryPart {
  int obj_id = 0;    // the id written to the annotations (PartAnnotation::obj_id)
  std::string name;  // the file name (or the name given in memory), for messages
  std::shared_ptr<const Mesh> mesh;
};

class PartLibrary {
 public:
  // Every .stl, .ply and .obj file (extension in any letter case) directly in `folder`,
  // sorted by file name (byte order), read with load_mesh. Object ids: when every file
  // name holds a number, its last run of digits (obj_05.stl -> 5, obj_000005.ply -> 5,
  // the T-LESS and BOP names); otherwise 1..N in sorted order, so that a folder of
  // named parts (bracket.stl, hinge.obj) still gets stable ids. Throws InputError
  // naming the folder when it is missing, not a folder, or holds no mesh file, or when
  // two files give the same number; load_mesh's InputError naming the file for a mesh
  // that cannot be read or has no triangles.
  static PartLibrary load_folder(const std::string& folder, const MeshOptions& options = {});

  // Parts given in memory (test shapes). Throws std::invalid_argument for no part, a
  // part without a mesh or triangles, or two parts with the same obj_id.
  explicit PartLibrary(std::vector<LibraryPart> parts);
  ~PartLibrary();
  PartLibrary(PartLibrary&&) noexcept;
  PartLibrary& operator=(PartLibrary&&) noexcept;

  int size() const { return static_cast<int>(parts_.size()); }
  const LibraryPart& part(int index) const { return parts_.at(index); }
  // The index of the part with this obj_id, -1 if none.
  int index_of(int obj_id) const;
  // The render scenes of these parts (thread-safe).
  const ScenePool& scenes() const { return *pool_; }

 private:
  std::vector<LibraryPart> parts_;
  std::unique_ptr<ScenePool> pool_;
};

// The parts of `library` with these obj_ids, in the library's order: a bin or a data set
// made of some parts only. InputError naming `option` for an id that no file of `folder`
// (where the library was read) gives.
PartLibrary select_parts(const PartLibrary& library, const std::vector<int>& obj_ids, const std::string& option,
                         const std::string& folder);

// The object id a file name without its extension gives: its last run of digits
// ("obj_000005" -> 5), -1 when it has none or more than nine.
int object_id_from_name(const std::string& stem);

}  // namespace flexsight

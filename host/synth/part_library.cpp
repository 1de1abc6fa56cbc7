#include "host/synth/part_library.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "host/io/folder_listing.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

// Ids from the names when all have one, 1..N otherwise; see load_folder.
std::vector<int> object_ids(const std::string& folder, const std::vector<fs::path>& files) {
  std::vector<int> ids;
  for (const fs::path& file : files) ids.push_back(object_id_from_name(file.stem().string()));
  if (std::find(ids.begin(), ids.end(), -1) != ids.end()) {
    for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i) + 1;
    return ids;
  }
  std::map<int, size_t> first;
  for (size_t i = 0; i < ids.size(); ++i) {
    const auto [it, inserted] = first.emplace(ids[i], i);
    if (!inserted) {
      throw InputError(folder, files[it->second].filename().string() + " and " +
                                   files[i].filename().string() + " both give object id " +
                                   std::to_string(ids[i]));
    }
  }
  return ids;
}

}  // namespace

int object_id_from_name(const std::string& stem) {
  const size_t end = stem.find_last_of("0123456789");
  if (end == std::string::npos) return -1;
  size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  // Leading zeros do not count; a number too long for an int is not an id.
  const size_t first = stem.find_first_not_of('0', begin);
  if (first == std::string::npos || first > end) return 0;
  if (end - first + 1 > 9) return -1;
  return std::stoi(stem.substr(first, end - first + 1));
}

PartLibrary PartLibrary::load_folder(const std::string& folder, const MeshOptions& options) {
  const std::vector<fs::path> files =
      files_with_extension(folder, {".stl", ".ply", ".obj"}, "mesh file");
  const std::vector<int> ids = object_ids(folder, files);
  std::vector<LibraryPart> parts;
  for (size_t i = 0; i < files.size(); ++i) {
    parts.push_back({ids[i], files[i].filename().string(),
                     std::make_shared<const Mesh>(load_mesh(files[i].string(), options))});
  }
  return PartLibrary(std::move(parts));
}

PartLibrary::PartLibrary(std::vector<LibraryPart> parts) : parts_(std::move(parts)) {
  if (parts_.empty()) throw std::invalid_argument("PartLibrary: no part");
  std::vector<std::shared_ptr<const Mesh>> meshes;
  for (const LibraryPart& part : parts_) {
    if (part.mesh == nullptr || part.mesh->triangles.empty()) {
      throw std::invalid_argument("PartLibrary: part " + part.name + " has no triangles");
    }
    if (index_of(part.obj_id) != static_cast<int>(meshes.size())) {
      throw std::invalid_argument("PartLibrary: object id " + std::to_string(part.obj_id) +
                                  " given twice");
    }
    meshes.push_back(part.mesh);
  }
  pool_ = std::make_unique<ScenePool>(std::move(meshes));
}

PartLibrary::~PartLibrary() = default;
PartLibrary::PartLibrary(PartLibrary&&) noexcept = default;
PartLibrary& PartLibrary::operator=(PartLibrary&&) noexcept = default;

PartLibrary select_parts(const PartLibrary& library, const std::vector<int>& obj_ids, const std::string& option,
                         const std::string& folder) {
  for (int id : obj_ids) {
    if (library.index_of(id) < 0) {
      throw InputError("option " + option, "object " + std::to_string(id) + " has no CAD model in " + folder);
    }
  }
  std::vector<LibraryPart> chosen;
  for (int i = 0; i < library.size(); ++i) {
    const LibraryPart& part = library.part(i);
    if (std::find(obj_ids.begin(), obj_ids.end(), part.obj_id) != obj_ids.end()) chosen.push_back(part);
  }
  return PartLibrary(std::move(chosen));
}

int PartLibrary::index_of(int obj_id) const {
  for (size_t i = 0; i < parts_.size(); ++i) {
    if (parts_[i].obj_id == obj_id) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace flexsight

#pragma once
// The files of a folder chosen by their extension (images, meshes), in a fixed order so a
// run reads them the same way on every machine.
#include <filesystem>
#include <string>
#include <vector>

namespace flexsight {

// Whether `path`'s extension, in any letter case, is one of `extensions` (".png", ...).
bool has_extension(const std::filesystem::path& path, const std::vector<std::string>& extensions);

// The regular files directly in `folder` whose extension is one of `extensions`, sorted by
// name. Throws InputError when the folder does not exist, is not a folder, cannot be listed,
// or holds none; `what` names the files in that last message ("mesh file").
std::vector<std::filesystem::path> files_with_extension(const std::string& folder,
                                                        const std::vector<std::string>& extensions,
                                                        const std::string& what);

// The same through `folder` and its subfolders, sorted by path, none being no error; `keep`
// can pass over some of them (a mask beside its image).
std::vector<std::filesystem::path> files_with_extension_below(
    const std::string& folder, const std::vector<std::string>& extensions,
    bool (*keep)(const std::filesystem::path&) = nullptr);

}  // namespace flexsight

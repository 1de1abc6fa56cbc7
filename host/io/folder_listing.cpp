#include "host/io/folder_listing.h"

#include <algorithm>
#include <cctype>

#include "host/io/input_error.h"

namespace flexsight {

namespace fs = std::filesystem;

namespace {

// ".jpg, .jpeg or .png"
std::string extension_list(const std::vector<std::string>& extensions) {
  std::string text;
  for (std::size_t i = 0; i < extensions.size(); ++i) {
    if (i > 0) text += i + 1 == extensions.size() ? " or " : ", ";
    text += extensions[i];
  }
  return text;
}

}  // namespace

bool has_extension(const fs::path& path, const std::vector<std::string>& extensions) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::find(extensions.begin(), extensions.end(), extension) != extensions.end();
}

std::vector<fs::path> files_with_extension(const std::string& folder,
                                           const std::vector<std::string>& extensions,
                                           const std::string& what) {
  std::error_code error;
  if (!fs::exists(folder, error)) throw InputError(folder, "does not exist");
  if (!fs::is_directory(folder, error)) throw InputError(folder, "is not a folder");
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    if (entry.is_regular_file(error) && has_extension(entry.path(), extensions)) {
      files.push_back(entry.path());
    }
  }
  if (error) throw InputError(folder, "cannot be listed (" + error.message() + ")");
  if (files.empty()) {
    throw InputError(folder, "holds no " + what + " (" + extension_list(extensions) + ")");
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return a.filename().string() < b.filename().string();
  });
  return files;
}

std::vector<fs::path> files_with_extension_below(const std::string& folder,
                                                 const std::vector<std::string>& extensions,
                                                 bool (*keep)(const fs::path&)) {
  std::error_code error;
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder, error)) {
    if (entry.is_regular_file() && has_extension(entry.path(), extensions) &&
        (keep == nullptr || keep(entry.path()))) {
      files.push_back(entry.path());
    }
  }
  if (error) throw InputError(folder, "cannot be listed: " + error.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace flexsight

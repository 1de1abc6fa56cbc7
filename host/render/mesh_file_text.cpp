#include "host/render/mesh_file_text.h"

#include "host/io/input_error.h"

namespace flexsight::mesh_files::detail {

void fail(const std::string& path, const std::string& problem) {
  throw InputError(path, problem);
}

std::string shown(std::string_view token) {
  std::string out;
  for (char c : token.substr(0, 24)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (token.size() > 24) out += "...";
  return "'" + out + "'";
}

void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  for (size_t i = 0; i < line.size();) {
    while (i < line.size() && is_space(line[i])) ++i;
    const size_t begin = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > begin) words.push_back(line.substr(begin, i - begin));
  }
}

}  // namespace flexsight::mesh_files::detail

#include "host/io/object_ids.h"

#include <algorithm>
#include <cctype>

#include "host/io/input_error.h"

namespace flexsight {

std::vector<int> parse_object_ids(const std::string& text, const std::string& option) {
  const std::string subject = "option " + option;
  if (text.empty()) throw InputError(subject, "expected object ids separated by commas (e.g. 5,12), got an empty list");
  std::vector<int> ids;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string entry = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const bool digits = !entry.empty() && entry.size() <= 9 &&
                        std::all_of(entry.begin(), entry.end(), [](unsigned char c) { return std::isdigit(c); });
    if (!digits) {
      throw InputError(subject, "expected object ids separated by commas (e.g. 5,12), got '" + entry + "' in '" +
                                    text + "'");
    }
    const int id = std::stoi(entry);
    if (id < 1) throw InputError(subject, "object ids start at 1, got " + entry + " in '" + text + "'");
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) {
      throw InputError(subject, "object " + std::to_string(id) + " is given twice in '" + text + "'");
    }
    ids.push_back(id);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::string object_ids_text(const std::vector<int>& obj_ids) {
  std::string text;
  for (int id : obj_ids) text += (text.empty() ? "" : ",") + std::to_string(id);
  return text;
}

}  // namespace flexsight

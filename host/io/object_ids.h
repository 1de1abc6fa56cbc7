#pragma once
// Lists of object ids as options give them ("5,12": the parts a cell handles, the parts a
// bin is made of).
#include <string>
#include <vector>

namespace flexsight {

// "5,12,3" into {3, 5, 12}: ascending, each a whole number from 1. InputError naming
// `option` for an empty list or entry, an entry that is not a number, 0 or a negative
// id, or an id given twice.
std::vector<int> parse_object_ids(const std::string& text, const std::string& option);

// {3, 5, 12} as "3,5,12", the form parse_object_ids reads.
std::string object_ids_text(const std::vector<int>& obj_ids);

}  // namespace flexsight

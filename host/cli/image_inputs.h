#pragma once
// The images a command runs over, from its positional arguments: image files and folders
// of images (`flexsight detect IMAGE...`).
#include <string>
#include <vector>

namespace flexsight {

// Every argument that is a folder becomes its .png, .jpg and .jpeg files (any case, not
// its subfolders'); the others stay as given. The whole list is then sorted by path, so a
// shell glob and a folder give the same order. Throws InputError naming the argument for
// one that does not exist, a folder without images, or a file OpenCV has no decoder for
// (judged by its first bytes: cheap, so that every input is checked before the first
// image is processed; the decode itself can still fail later).
std::vector<std::string> list_input_images(const std::vector<std::string>& arguments);

}  // namespace flexsight

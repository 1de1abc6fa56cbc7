#pragma once
// The file `flexsight pose-templates` writes and the pose estimator reads: a template
// set in one little-endian binary file (docs/pose.md gives the layout). Binary because a
// set of 23 parts x 600 views x 128 points is ~20 MB of numbers that are read at every
// start: parsing them as text would take longer than the search they serve.
#include <string>

#include "host/pose/edge_template.h"

namespace flexsight {

// Written atomically (a failed write leaves `path` as it was).
void write_template_set(const std::string& path, const TemplateSet& set);

// Throws InputError naming `path` for a missing or unreadable file, a file that is not a
// template set (magic), another format version, a truncated file or values out of range.
TemplateSet read_template_set(const std::string& path);

}  // namespace flexsight

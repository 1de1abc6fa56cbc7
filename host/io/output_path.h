#pragma once
// Where a command will write, checked before its first unit of work: a run that would
// only learn at the end that its output cannot be written wastes the work and, worse,
// may have replaced nothing while saying so late.
#include <string>

namespace flexsight {

// InputError naming `path` unless a file can be created or replaced at `path`: its
// folder exists, is a folder and is writable (outputs are renamed into place, so the
// folder's permission is the one that counts), and `path` itself is no folder. Nothing is
// created. An empty `path` (an output not asked for) passes.
void check_output_file(const std::string& path);

}  // namespace flexsight

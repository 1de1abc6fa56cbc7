#pragma once
// One exception type for everything a user can get wrong about the files and options
// they hand us. The message always names the file (or option) and the problem, so the
// CLI can print it as is and exit non-zero.
#include <stdexcept>
#include <string>

namespace flexsight {

class InputError : public std::runtime_error {
 public:
  // `what` reads "<subject>: <problem>", e.g. "left.png: cannot be decoded as an image".
  InputError(const std::string& subject, const std::string& problem);
};

}  // namespace flexsight

#include "host/io/input_error.h"

namespace flexsight {

InputError::InputError(const std::string& subject, const std::string& problem)
    : std::runtime_error(subject + ": " + problem) {}

}  // namespace flexsight

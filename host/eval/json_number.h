#pragma once
// Numbers as the reports write them in JSON, which has no NaN or infinity.
#include <cmath>
#include <nlohmann/json.hpp>

namespace flexsight {

// `value`, or null where it is undefined (NaN, infinity).
inline nlohmann::ordered_json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace flexsight

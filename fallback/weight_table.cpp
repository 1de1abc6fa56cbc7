#include "fallback/weight_table.h"

#include <cmath>

#include "kernels/pms_math.h"

namespace flexsight {

std::vector<float> make_support_weight_table(float gamma) {
  std::vector<float> weights(PMS_WEIGHT_TABLE_SIZE);
  for (int k = 0; k < PMS_WEIGHT_TABLE_SIZE; ++k) {
    // Double precision then one rounding: the same float on every machine.
    weights[k] = static_cast<float>(std::exp(-static_cast<double>(k) / gamma));
  }
  return weights;
}

}  // namespace flexsight

#include "fallback/stereo/weight_table.h"

#include "kernels/stereo/pms_math.h"

namespace flexsight {

std::vector<float> make_support_weight_table(float gamma, float gamma_distance) {
  std::vector<float> weights(PMS_WEIGHT_TABLE_SIZE);
  for (int k = 0; k < PMS_COLOR_WEIGHT_COUNT; ++k) {
    // Double precision then one rounding: the same float on every machine.
    weights[k] = static_cast<float>(std::exp(-static_cast<double>(k) / gamma));
  }
  for (int dy = 0; dy < PMS_DISTANCE_WEIGHT_SIDE; ++dy) {
    for (int dx = 0; dx < PMS_DISTANCE_WEIGHT_SIDE; ++dx) {
      const double distance = std::sqrt(static_cast<double>(dx * dx + dy * dy));
      weights[PMS_COLOR_WEIGHT_COUNT + dy * PMS_DISTANCE_WEIGHT_SIDE + dx] =
          static_cast<float>(std::exp(-distance / gamma_distance));
    }
  }
  return weights;
}

}  // namespace flexsight

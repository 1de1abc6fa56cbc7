#pragma once
// exp() is the one transcendental of the matcher, and its last bit differs between
// libraries and devices. Both paths therefore read the support weights from this table,
// built once on the host and uploaded to the device as is.
#include <cmath>
#include <vector>

namespace flexsight {

// PMS_WEIGHT_TABLE_SIZE floats (layout in kernels/stereo/pms_math.h), each computed in double
// and rounded once to float: exp(-k / gamma) for the colour distances k in 0..765, then
// exp(-sqrt(dx^2 + dy^2) / gamma_distance) for |dx|, |dy| in 0..50. An infinite
// gamma_distance makes the distance factors exactly 1 (colour-only weights, as in
// Bleyer et al.).
std::vector<float> make_support_weight_table(float gamma, float gamma_distance = INFINITY);

}  // namespace flexsight

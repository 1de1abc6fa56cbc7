#pragma once
// exp() is the one transcendental of the matcher, and its last bit differs between
// libraries and devices. Both paths therefore read the support weights from this table,
// built once on the host and uploaded to the device as is.
#include <vector>

namespace flexsight {

// weights[k] = exp(-k / gamma) rounded to float, for k in 0..PMS_WEIGHT_TABLE_SIZE-1.
std::vector<float> make_support_weight_table(float gamma);

}  // namespace flexsight

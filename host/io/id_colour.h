#pragma once
// One bright colour per id (a category, an object), the same in every picture, so one part
// type keeps one colour across images and tools.
#include <opencv2/core.hpp>

namespace flexsight {

// A colour of a 12-colour palette (RGB), chosen by `id` modulo 12; negative ids wrap too.
cv::Scalar id_colour(int id);

}  // namespace flexsight

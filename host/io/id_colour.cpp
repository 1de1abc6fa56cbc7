#include "host/io/id_colour.h"

namespace flexsight {

cv::Scalar id_colour(int id) {
  static const cv::Scalar kPalette[] = {{230, 25, 75},   {60, 180, 75},  {255, 225, 25},
                                        {0, 130, 200},   {245, 130, 48}, {145, 30, 180},
                                        {70, 240, 240},  {240, 50, 230}, {210, 245, 60},
                                        {250, 190, 212}, {0, 128, 128},  {220, 190, 255}};
  const int count = sizeof kPalette / sizeof kPalette[0];
  return kPalette[((id % count) + count) % count];
}

}  // namespace flexsight

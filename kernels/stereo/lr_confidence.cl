/* C(p) = 1 / (1 + |d(p) - d_other(p')|) for every pixel of one view
 * (reference: lr_confidence). */
#include "postprocess_math.h"
#include "pms_kernel_support.h"

__kernel void lr_confidence(const __global float* disparity,
                            const __global float* other_disparity, int width, int height,
                            int view, __global float* confidence) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  float direction = view == PMS_VIEW_LEFT ? -1.0f : 1.0f;
  confidence[y * width + x] =
      pms_confidence(disparity, other_disparity, width, x, y, direction);
}

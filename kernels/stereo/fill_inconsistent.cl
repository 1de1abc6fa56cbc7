/* Inconsistent pixels take the background plane of the nearest consistent pixels on
 * their row; consistent pixels copy theirs (reference: fill_inconsistent, which starts
 * from a copy of `planes`, so the fourth component is always copied). */
#include "postprocess_math.h"
#include "pms_kernel_support.h"

__kernel void fill_inconsistent(const __global float* planes, const __global uchar* consistent,
                                int width, int height, float max_extrapolation,
                                __global float* filled) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  int index = y * width + x;
  float abc[3];
  if (consistent[index]) {
    pms_load_plane(planes, index, abc);
  } else {
    pms_fill_pixel(planes, consistent, width, x, y, max_extrapolation, abc);
  }
  filled[4 * index] = abc[0];
  filled[4 * index + 1] = abc[1];
  filled[4 * index + 2] = abc[2];
  filled[4 * index + 3] = planes[4 * index + 3];
}

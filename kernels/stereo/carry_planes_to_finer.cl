/* Planes of the next finer level: fine pixel (x, y) takes coarse pixel (x / 2, y / 2),
 * clamped for odd sizes (reference: carry_planes_to_finer). Costs are left to
 * evaluate_costs; the fourth component is written as 0 like PlaneField::resize. */
#include "pms_kernel_support.h"

__kernel void carry_planes_to_finer(const __global float* coarse, int coarse_width,
                                    int coarse_height, __global float* fine, int fine_width,
                                    int fine_height) {
  int x, y;
  if (!pms_dense_pixel(fine_width, fine_height, &x, &y)) return;
  float abc_coarse[3];
  float abc_fine[3];
  pms_load_plane(coarse, pms_coarse_pixel(x, y, coarse_width, coarse_height), abc_coarse);
  pms_carry_plane_to_finer(abc_coarse, abc_fine);
  int index = y * fine_width + x;
  fine[4 * index] = abc_fine[0];
  fine[4 * index + 1] = abc_fine[1];
  fine[4 * index + 2] = abc_fine[2];
  fine[4 * index + 3] = 0.0f;
}

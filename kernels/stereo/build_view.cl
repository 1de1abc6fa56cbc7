/* Pyramid levels on the device (fallback/stereo/image_pyramid.cpp): the host uploads the
 * level-0 colour, downsample_color makes each coarser colour, and compute_gradient
 * follows as a second launch because it reads the neighbours' colours. Before a level's
 * PatchMatch, pack_match_samples lays each view out for the cost kernels' reads of it
 * as the other view (a device-only layout, no reference counterpart). */
#include "pms_kernel_support.h"

/* Coarse pixel (x, y) of the next level: 2x2 box average with rounding. */
__kernel void downsample_color(const __global float* fine, int fine_width, int fine_height,
                               __global float* coarse, int coarse_width, int coarse_height) {
  int x, y;
  if (!pms_dense_pixel(coarse_width, coarse_height, &x, &y)) return;
  pms_downsample_pixel(fine, fine_width, fine_height, x, y, coarse + 4 * (y * coarse_width + x));
}

/* Grey-value gradient (gx, gy) of pixel (x, y), and its census (shape: PmsCensusShape's
 * three fields) in the colour's fourth component (the neighbours' colours are read from
 * components 0..2 only). */
__kernel void compute_gradient(__global float* color, int width, int height,
                               __global float* gradient, int census_half_rows,
                               int census_half_cols, int census_half_row_length) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  PmsCensusShape shape;
  shape.half_rows = census_half_rows;
  shape.half_cols = census_half_cols;
  shape.half_row_length = census_half_row_length;
  pms_gradient_pixel(color, width, height, x, y, gradient + 2 * (y * width + x));
  color[4 * (y * width + x) + 3] = pms_census_pixel(color, width, height, x, y, shape);
}

/* Match record (pms_match_record) of pixel (x, y). The buffer holds PMS_MATCH_RECORD
 * floats per pixel and 4 more, which the last pixel zeroes: the cost kernels load 16
 * floats from each record's start. */
__kernel void pack_match_samples(const __global float* color, const __global float* gradient,
                                 int width, int height, __global float* match) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  pms_match_record(color, gradient, width, x, y, match + PMS_MATCH_RECORD * (y * width + x));
  if (x == width - 1 && y == height - 1) {
    __global float* tail = match + PMS_MATCH_RECORD * width * height;
    tail[0] = tail[1] = tail[2] = tail[3] = 0.0f;
  }
}

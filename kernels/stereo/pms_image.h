/*
 * Per-pixel preparation of the images the matching cost reads, shared by the reference
 * path (fallback/stereo/image_pyramid.cpp) and the kernels (build_view.cl): the
 * pyramid's 2x2 average, the grey value, the census and the gradient, and the
 * other view's match records of the lane cost. Same rules as pms_math.h.
 */
#ifndef FLEXSIGHT_PMS_IMAGE_H
#define FLEXSIGHT_PMS_IMAGE_H

#include "../common/portability.h"

/* ------------------------------------------------------------- image preparation */

/* 2x2 box average with rounding, integer-exact; odd sizes repeat the last row/column.
 * Writes the 3 colour channels of coarse pixel (x, y). */
FS_INLINE void pms_downsample_pixel(const FS_GLOBAL float* fine, int fine_width,
                                     int fine_height, int x, int y, FS_GLOBAL float* out) {
  int x0 = 2 * x;
  int y0 = 2 * y;
  int x1 = x0 + 1 < fine_width ? x0 + 1 : x0;
  int y1 = y0 + 1 < fine_height ? y0 + 1 : y0;
  for (int ch = 0; ch < 3; ++ch) {
    float s = fine[4 * (y0 * fine_width + x0) + ch] + fine[4 * (y0 * fine_width + x1) + ch] +
              fine[4 * (y1 * fine_width + x0) + ch] + fine[4 * (y1 * fine_width + x1) + ch];
    out[ch] = FS_FLOOR((s + 2.0f) * 0.25f);
  }
  out[3] = 0.0f;
}

/* Grey value scaled by 3 (r + g + b), exact in float. */
FS_INLINE float pms_grey3(const FS_GLOBAL float* color, int index) {
  return color[4 * index] + color[4 * index + 1] + color[4 * index + 2];
}

/* The census's neighbourhood: the (2 half_rows + 1) x (2 half_cols + 1) rectangle
 * around the pixel, whose centre row reaches half_row_length pixels to each side
 * (>= half_cols). 5x5 (2, 2, 2) is the default; a surface that slopes along the rows
 * shears the rows above and below between the views, which a census of the centre row
 * only (0, 12, 12: 1x25) does not see. At most PMS_CENSUS_MAX_BITS bits. */
typedef struct {
  int half_rows;
  int half_cols;
  int half_row_length;
} PmsCensusShape;

/* A bit string stays an exact integer in a float up to 2^24. */
#define PMS_CENSUS_MAX_BITS 24

FS_INLINE int pms_census_bit_count(PmsCensusShape shape) {
  return (2 * shape.half_rows + 1) * (2 * shape.half_cols + 1) - 1 +
         2 * (shape.half_row_length - shape.half_cols);
}

/* Census of the grey value r + g + b over `shape`: bit k is set when the k-th neighbour
 * (row by row, left to right, centre left out, coordinates clamped at the border) is
 * darker than the centre. An exact float integer; it goes in the colour's fourth
 * component. */
FS_INLINE float pms_census_pixel(const FS_GLOBAL float* color, int width, int height, int x,
                                  int y, PmsCensusShape shape) {
  float centre = pms_grey3(color, y * width + x);
  fs_u32 bits = 0U;
  fs_u32 bit = 1U;
  for (int dy = -shape.half_rows; dy <= shape.half_rows; ++dy) {
    int qy = y + dy < 0 ? 0 : (y + dy > height - 1 ? height - 1 : y + dy);
    int reach = dy == 0 ? shape.half_row_length : shape.half_cols;
    for (int dx = -reach; dx <= reach; ++dx) {
      if (dx == 0 && dy == 0) continue;
      int qx = x + dx < 0 ? 0 : (x + dx > width - 1 ? width - 1 : x + dx);
      if (pms_grey3(color, qy * width + qx) < centre) bits |= bit;
      bit <<= 1;
    }
  }
  return (float)bits;
}

/* Central-difference gradient of the grey value (r + g + b) / 3, border pixels use a
 * one-sided neighbour (clamped coordinates). */
FS_INLINE void pms_gradient_pixel(const FS_GLOBAL float* color, int width, int height, int x,
                                   int y, FS_GLOBAL float* out) {
  int xl = x > 0 ? x - 1 : x;
  int xr = x + 1 < width ? x + 1 : x;
  int yu = y > 0 ? y - 1 : y;
  int yd = y + 1 < height ? y + 1 : y;
  const float scale = 1.0f / 6.0f;
  out[0] = (pms_grey3(color, y * width + xr) - pms_grey3(color, y * width + xl)) * scale;
  out[1] = (pms_grey3(color, yd * width + x) - pms_grey3(color, yu * width + x)) * scale;
}

/* The other view's samples of pms_plane_cost at pixel (x, y) as one record, for the
 * OpenCL path's vector loads (pms_load_match_samples in pms_kernel_support.h): with
 * x1 = min(x + 1, width - 1), the colour at x, its census, the colour steps to x1, the
 * census at x1, the gradient at x and its steps to x1. Each step is the m1 - m0 that
 * pms_plane_cost computes, so m0 + t * step has the same bits. */
#define PMS_MATCH_RECORD 12
FS_INLINE void pms_match_record(const FS_GLOBAL float* color, const FS_GLOBAL float* grad,
                                 int width, int x, int y, FS_GLOBAL float* out) {
  const FS_GLOBAL float* c0 = color + 4 * (y * width + x);
  const FS_GLOBAL float* c1 = color + 4 * (y * width + (x + 1 < width ? x + 1 : x));
  const FS_GLOBAL float* g0 = grad + 2 * (y * width + x);
  const FS_GLOBAL float* g1 = grad + 2 * (y * width + (x + 1 < width ? x + 1 : x));
  out[0] = c0[0];
  out[1] = c0[1];
  out[2] = c0[2];
  out[3] = c0[3];
  out[4] = c1[0] - c0[0];
  out[5] = c1[1] - c0[1];
  out[6] = c1[2] - c0[2];
  out[7] = c1[3];
  out[8] = g0[0];
  out[9] = g0[1];
  out[10] = g1[0] - g0[0];
  out[11] = g1[1] - g0[1];
}

#endif /* FLEXSIGHT_PMS_IMAGE_H */

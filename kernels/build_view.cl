/* Pyramid levels on the device (fallback/image_pyramid.cpp): the host uploads the
 * level-0 colour, downsample_color makes each coarser colour, and compute_gradient
 * follows as a second launch because it reads the neighbours' colours. */
#include "pms_kernel_support.h"

/* Coarse pixel (x, y) of the next level: 2x2 box average with rounding. */
__kernel void downsample_color(const __global float* fine, int fine_width, int fine_height,
                               __global float* coarse, int coarse_width, int coarse_height) {
  int x, y;
  if (!pms_dense_pixel(coarse_width, coarse_height, &x, &y)) return;
  pms_downsample_pixel(fine, fine_width, fine_height, x, y, coarse + 4 * (y * coarse_width + x));
}

/* Grey-value gradient (gx, gy) of pixel (x, y), and its census in the colour's fourth
 * component (the neighbours' colours are read from components 0..2 only). */
__kernel void compute_gradient(__global float* color, int width, int height,
                               __global float* gradient) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  pms_gradient_pixel(color, width, height, x, y, gradient + 2 * (y * width + x));
  color[4 * (y * width + x) + 3] = pms_census_pixel(color, width, height, x, y);
}

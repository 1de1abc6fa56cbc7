#pragma once
// Post-processing of the finest level (Bleyer et al. 2011, Sec. 3.3), scalar C++, one
// function per kernel: left/right check, filling of inconsistent pixels with the
// background plane, a weighted median over the filled pixels, and a small weighted median
// over every pixel.
#include <cstdint>
#include <vector>

#include "fallback/stereo/image_pyramid.h"

namespace flexsight {

// 1 where the disparity of `view` and the other view's disparity it points at agree.
std::vector<std::uint8_t> left_right_check(const std::vector<float>& disparity,
                                           const std::vector<float>& other_disparity, int width,
                                           int height, int view, float tolerance,
                                           int threads);

// Planes where inconsistent pixels took the lower (background) plane of the nearest
// consistent pixels on their row, its disparity there at most `max_extrapolation` from
// the source pixel's own (pms_fill_pixel); consistent pixels keep theirs.
std::vector<float> fill_inconsistent(const std::vector<float>& planes,
                                     const std::vector<std::uint8_t>& consistent, int width,
                                     int height, float max_extrapolation, int threads);

// For every inconsistent pixel, the weighted median of the consistent pixels'
// disparities in a window (radius, step) that are at most `background_margin` above the
// pixel's filled disparity, weights from `weights` indexed by the colour difference to
// the centre; a window without such pixels keeps the filled value. Consistent pixels are
// copied.
std::vector<float> weighted_median_filled(const std::vector<float>& disparity,
                                          const std::vector<std::uint8_t>& consistent,
                                          const ViewImage& image, const float* weights,
                                          int radius, int step, float background_margin,
                                          int threads);

// The weighted median of every pixel's window (radius, step 1) over all disparities.
std::vector<float> weighted_median_all(const std::vector<float>& disparity,
                                       const ViewImage& image, const float* weights, int radius,
                                       int threads);

// 1 for every pixel of a segment of at least min_size pixels, 0 in the smaller ones,
// where a segment joins 4-neighbours whose disparities differ by at most max_step, or
// with follow_slopes whose step continues a neighbouring step (pms_segment_pair_joined);
// min_size 0 keeps every pixel. The refill of the small segments takes it as
// fill_inconsistent's and weighted_median_filled's `consistent`.
std::vector<std::uint8_t> large_segment_mask(const std::vector<float>& disparity, int width,
                                             int height, float max_step, int min_size,
                                             bool follow_slopes = false);

// mask[i] becomes 0 wherever other[i] is 0 (the kernels' mask_and).
void mask_and(std::vector<std::uint8_t>& mask, const std::vector<std::uint8_t>& other);

// The flat plane (0, 0, d) of every disparity (pms_flat_plane), for fill_inconsistent.
std::vector<float> flat_planes(const std::vector<float>& disparity);

}  // namespace flexsight

#pragma once
// Per-pixel confidence of the final disparity, in [0, 1]:
//
//   C(p) = C_lr(p) * C_match(p)
//   C_lr(p)    = 1 / (1 + |d_L(p) - d_R(p - d_L(p))|)   the paper's left/right agreement,
//                from the raw disparities of the finest level (0 where p' leaves the image)
//   C_match(p) = clamp((m_max - m(p)) / (kMatchSpread m_max), 0, 1)
//                m(p) = the final plane's matching cost divided by the sum of its support
//                weights, i.e. the weighted mean dissimilarity; m_max = (1 - alpha) tau_col
//                + alpha tau_grad + census_weight * census_cap, its ceiling
//
// Why the spread: without the census term the truncations saturate for most window
// pixels even when the plane is right (tau_grad = 2 is small next to image gradients):
// on MiddEval3 correct pixels had m around 0.85 m_max and wrong ones above 0.95 m_max,
// so the top quarter of the range is mapped onto [0, 1]. With the default census weight
// the census dominates m and stays far below its 24-bit ceiling, so C_match is 1 almost
// everywhere and C is mostly C_lr (Teddy: C >= 0.5 keeps 86 % of the pixels at 2.1 %
// bad-2, against 4.6 % for all).
//
// Pixels that fail the left/right check (filled by post-processing) have C_lr <= 1/2
// at the default tolerance of 1 px, so a threshold above 0.5 keeps only matched pixels;
// C_match then ranks those by how well the window matched.
#include <opencv2/core.hpp>

#include "fallback/stereo_params.h"
#include "host/stereo_pipeline.h"

namespace flexsight {

// Fraction of the dissimilarity ceiling that C_match spreads over (see above).
constexpr float kMatchSpread = 0.25f;

// `result` from run_stereo or the OpenCL matcher on `left_rgb8` with `params`.
cv::Mat confidence_map(const StereoResult& result, const cv::Mat& left_rgb8,
                       const StereoParams& params);

}  // namespace flexsight

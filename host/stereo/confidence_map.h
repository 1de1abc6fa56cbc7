#pragma once
// Per-pixel confidence of the final disparity, in [0, 1]:
//
//   C(p) = A(p) * C_match(p)
//   C_lr(p)    = 1 / (1 + |d_L(p) - d_R(p - d_L(p))|)   the paper's left/right agreement,
//                from the raw disparities of the finest level (0 where p' leaves the image)
//   A(p)       = mean of C_lr over the 7x7 pixels around p where C_lr(p) > 1/2,
//                min(C_lr(p), that mean) elsewhere
//   C_match(p) = clamp((m_max - m(p)) / (kMatchSpread m_max), 0, 1)
//                m(p) = the final plane's matching cost divided by the sum of its support
//                weights, i.e. the weighted mean dissimilarity; m_max = (1 - alpha) tau_col
//                + alpha tau_grad + census_weight * census_cap, its ceiling
//
// Why the neighbourhood: wrong planes come in patches whose rims fail the left/right
// check, and pixels next to an occlusion or a depth edge are the ones a window matcher
// gets wrong; a pixel that agrees with the other view but sits among pixels that do not
// is less sure than one in a consistent area. Ranked by C, the most confident k/20 of
// the pixels of the 15 MiddEval3 training scenes (quarter resolution, defaults, seed 1)
// have an average bad-2 of 2.85 % over k = 1..20 (sparsification AUC) against 4.99 %
// without the neighbourhood (C_lr * C_match). The gate keeps what the threshold 1/2
// means: pixels that fail the check (C_lr <= 1/2 at the default 1-px tolerance) stay at
// or below it.
//
// Why the spread of C_match: without the census term the truncations saturate for most
// window pixels even when the plane is right (tau_grad = 2 is small next to image
// gradients): on MiddEval3 correct pixels had m around 0.85 m_max and wrong ones above
// 0.95 m_max, so the top quarter of the range is mapped onto [0, 1]. With the default
// census weight the census dominates m and stays far below its ceiling, so C_match is 1
// almost everywhere; m itself ranks worse than C_lr across scenes (lighting raises it
// everywhere on PianoL), so it is not rescaled.
#include <opencv2/core.hpp>

#include "host/stereo/stereo_params.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {

// Fraction of the dissimilarity ceiling that C_match spreads over (see above).
constexpr float kMatchSpread = 0.25f;
// Side of the square over which the left/right agreement is averaged (see above).
constexpr int kAgreementWindow = 7;

// `result` from run_stereo or the OpenCL matcher on `left_rgb8` with `params`.
cv::Mat confidence_map(const StereoResult& result, const cv::Mat& left_rgb8,
                       const StereoParams& params);

}  // namespace flexsight

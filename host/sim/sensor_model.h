#pragma once
// What a varied bin's camera does to the radiance that reaches it (bin_variation.h's
// CameraLook): a slight defocus, vignetting, exposure and gain, and the sensor's shot
// and read noise, in linear units before the sRGB encoding (where a real sensor adds
// them: noise is larger in bright regions in electrons, and the encoding stretches the
// dark levels).
#include <cstdint>
#include <opencv2/core.hpp>

#include "host/sim/bin_variation.h"

namespace flexsight {

// `radiance` linear RGB (CV_32FC3) -> linear RGB after the camera. With full_well_e 0 no
// exposure, gain or noise is applied (the caller adds the fixed Gaussian noise). The
// noise is a function of (noise_key, value index) only.
cv::Mat apply_camera_look(const cv::Mat& radiance, const CameraLook& look, std::uint64_t noise_key);

}  // namespace flexsight

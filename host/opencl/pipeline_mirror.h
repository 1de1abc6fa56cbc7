#pragma once
// The rules of host/stereo_pipeline.cpp that live in its anonymous namespace, repeated
// for the OpenCL scheduler: they decide the bytes of the result, so they must stay
// identical (the pipeline tests compare the two paths byte for byte and catch a
// divergence). Moving them into a shared header of host/ would remove this copy.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "fallback/stereo_params.h"

namespace flexsight::opencl {

// Throws InputError as run_stereo does.
void validate_inputs(const cv::Mat& left, const cv::Mat& right, const StereoParams& params);

// Disparity range of a level: ndisp halves (rounding up) with each level, at least 2.
int level_ndisp(int ndisp, int level);

// Random-generator iteration key: unique per (level, iteration); 0 is the initialisation.
std::uint32_t iteration_key(int level, int iteration);

// The level-0 colour of ViewImage (r, g, b, 0 per pixel) from an RGB8 image.
std::vector<float> color_floats(const cv::Mat& rgb8);

cv::Mat to_mat(const std::vector<float>& values, int width, int height, int channels);

// Planes (4 floats per pixel) as a CV_32FC3 of (a, b, c).
cv::Mat planes_to_mat(const std::vector<float>& planes, int width, int height);

}  // namespace flexsight::opencl

// The camera's noise and blur: the noise has the asked sigma, zero mean, no correlation
// between neighbouring values, and is a function of its key; the blur leaves a flat
// picture flat.
#include <gtest/gtest.h>

#include <cmath>

#include "host/synth/camera_effects.h"
#include "tests/render/render_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

TEST(SynthCameraEffects, NoiseIsGaussianOfTheAskedSigmaAndKeyed) {
  const cv::Mat grey(301, 257, CV_8UC3, cv::Scalar(128, 128, 128));
  for (double sigma : {1.5, 4.0}) {
    cv::Mat noisy = grey.clone();
    apply_camera_effects(noisy, 0.0, sigma, 42);
    cv::Mat values;
    noisy.reshape(1, 1).convertTo(values, CV_64F, 1.0, -128.0);
    const int n = values.cols;
    double mean = 0.0, variance = 0.0, lag = 0.0;
    for (int i = 0; i < n; ++i) mean += values.at<double>(i) / n;
    for (int i = 0; i < n; ++i) variance += std::pow(values.at<double>(i) - mean, 2) / n;
    for (int i = 1; i < n; ++i) {
      lag += (values.at<double>(i) - mean) * (values.at<double>(i - 1) - mean) / (n - 1);
    }
    EXPECT_NEAR(mean, 0.0, 0.02) << sigma;
    // Rounding to whole levels adds 1/12 to the variance.
    EXPECT_NEAR(std::sqrt(variance), std::sqrt(sigma * sigma + 1.0 / 12.0), 0.03 * sigma) << sigma;
    EXPECT_LT(std::abs(lag / variance), 0.01) << sigma;

    cv::Mat again = grey.clone();
    apply_camera_effects(again, 0.0, sigma, 42);
    EXPECT_TRUE(same_mat_bytes(again, noisy));
    apply_camera_effects(again = grey.clone(), 0.0, sigma, 43);
    EXPECT_FALSE(same_mat_bytes(again, noisy));
  }
}

TEST(SynthCameraEffects, NoiseSaturatesAndZeroChangesNothing) {
  cv::Mat black(10, 10, CV_8UC3, cv::Scalar(0, 0, 0));
  apply_camera_effects(black, 0.0, 6.0, 1);
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(black.reshape(1), &lo, &hi);
  EXPECT_EQ(lo, 0.0);
  EXPECT_GT(hi, 0.0);
  const cv::Mat flat(20, 30, CV_8UC3, cv::Scalar(10, 200, 90));
  cv::Mat same = flat.clone();
  apply_camera_effects(same, 0.8, 0.0, 1);
  EXPECT_TRUE(same_mat_bytes(same, flat));
}

// Same seed, same bytes, whatever the number of threads; another seed, other bytes.
#include <gtest/gtest.h>

#include "host/io/image_io.h"
#include "host/stereo/stereo_pipeline.h"
#include "tests/common/test_support.h"

using namespace flexsight;
using testing_support::same_bytes;

namespace {

StereoParams quick_params(StereoMethod method, int threads) {
  StereoParams p;
  p.method = method;
  p.ndisp = 32;
  p.window = 15;
  p.coarsest_width = 40;
  p.threads = threads;
  return p;
}

void expect_same_result(const StereoResult& a, const StereoResult& b) {
  EXPECT_TRUE(same_bytes(a.raw_left, b.raw_left));
  EXPECT_TRUE(same_bytes(a.raw_right, b.raw_right));
  EXPECT_TRUE(same_bytes(a.planes_left, b.planes_left));
  EXPECT_TRUE(same_bytes(a.cost_left, b.cost_left));
  EXPECT_TRUE(same_bytes(a.disparity, b.disparity));
}

class ThreadCountInvariance : public ::testing::TestWithParam<StereoMethod> {};

}  // namespace

TEST_P(ThreadCountInvariance, OneTwoAndThreeThreadsGiveTheSameBytes) {
  testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoResult one = run_stereo(crop.left, crop.right, quick_params(GetParam(), 1));
  StereoResult two = run_stereo(crop.left, crop.right, quick_params(GetParam(), 2));
  StereoResult three = run_stereo(crop.left, crop.right, quick_params(GetParam(), 3));
  expect_same_result(one, two);
  expect_same_result(one, three);
}

INSTANTIATE_TEST_SUITE_P(Methods, ThreadCountInvariance,
                         ::testing::Values(StereoMethod::PPMS, StereoMethod::PMS),
                         [](const auto& info) { return std::string(method_name(info.param)); });

TEST(Determinism, TheSeedDecidesTheRandomPlanes) {
  testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams p = quick_params(StereoMethod::PPMS, 2);
  StereoResult first = run_stereo(crop.left, crop.right, p);
  StereoResult again = run_stereo(crop.left, crop.right, p);
  p.seed = 2;
  StereoResult other = run_stereo(crop.left, crop.right, p);
  expect_same_result(first, again);
  EXPECT_FALSE(same_bytes(first.raw_left, other.raw_left));
}

// The counter-based generator: a pure function of its key, well spread, in [0, 1).
#include <gtest/gtest.h>

#include <set>

#include "kernels/stereo/pms_math.h"

// The value is the hash chain of the key fields in this order (seed, pixel, iteration and
// view, trial): every stereo result depends on it, so the chain is pinned field by field.
TEST(CounterRandom, IsTheHashChainOfItsKeyFields) {
  const fs_u32 seeded = fs_hash(7U ^ 0x9e3779b9U);
  const fs_u32 at_pixel = fs_hash(seeded ^ 1234U);
  const fs_u32 at_iteration = fs_hash(at_pixel ^ (3U * 2U + 0U));
  EXPECT_EQ(pms_random_u32(7, 0, 1234, 3, 5), fs_hash(at_iteration ^ 5U));
  EXPECT_EQ(pms_random_u32(7, 1, 1234, 3, 5), fs_hash(fs_hash(at_pixel ^ (3U * 2U + 1U)) ^ 5U));
}

TEST(CounterRandom, EveryKeyFieldChangesTheValue) {
  const fs_u32 base = pms_random_u32(7, 0, 1234, 3, 5);
  EXPECT_NE(base, pms_random_u32(8, 0, 1234, 3, 5));
  EXPECT_NE(base, pms_random_u32(7, 1, 1234, 3, 5));
  EXPECT_NE(base, pms_random_u32(7, 0, 1235, 3, 5));
  EXPECT_NE(base, pms_random_u32(7, 0, 1234, 4, 5));
  EXPECT_NE(base, pms_random_u32(7, 0, 1234, 3, 6));
}

TEST(CounterRandom, KnownValueOfTheHash) {
  // lowbias32 of 1, computed by hand from its definition: pins the function so a
  // change to it (which would change every result) cannot go unnoticed.
  fs_u32 x = 1;
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  EXPECT_EQ(fs_hash(1), x);
  EXPECT_NE(fs_hash(1), 1u);
}

TEST(CounterRandom, UniformInUnitIntervalWithSaneMoments) {
  const int n = 200000;
  double sum = 0, sum_sq = 0;
  float lo = 1, hi = 0;
  std::set<fs_u32> distinct;
  for (int i = 0; i < n; ++i) {
    fs_u32 bits = pms_random_u32(1, 0, static_cast<fs_u32>(i), 0, 0);
    if (i < 10000) distinct.insert(bits);
    float u = fs_u32_to_unit(bits);
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum += u;
    sum_sq += static_cast<double>(u) * u;
  }
  double mean = sum / n, var = sum_sq / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_NEAR(var, 1.0 / 12.0, 0.002);
  EXPECT_LT(lo, 0.001f);
  EXPECT_GT(hi, 0.999f);
  EXPECT_GT(distinct.size(), 9990u);  // collisions among 10^4 32-bit values are rare
}

TEST(CounterRandom, UnitConversionIsExact) {
  EXPECT_EQ(fs_u32_to_unit(0u), 0.0f);
  EXPECT_EQ(fs_u32_to_unit(0x80000000u), 0.5f);
  EXPECT_EQ(fs_u32_to_unit(0xffffffffu), 16777215.0f / 16777216.0f);
}

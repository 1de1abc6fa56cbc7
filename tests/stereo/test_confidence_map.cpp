// The confidence map on the real fixture: in [0, 1], and it ranks pixels so that the
// confident ones are far more often right.
#include <gtest/gtest.h>

#include "host/eval/confidence_depth_metrics.h"
#include "host/eval/metrics.h"
#include "host/stereo/confidence_map.h"
#include "host/io/pfm.h"
#include "kernels/stereo/postprocess_math.h"
#include "tests/common/test_support.h"

using namespace flexsight;

namespace {

// The fixture matched once with the defaults, and its confidence map.
struct FixtureRun {
  StereoPair pair;
  cv::Mat truth;
  StereoResult result;
  cv::Mat confidence;
};

const FixtureRun& fixture_run() {
  static const FixtureRun run = [] {
    const std::string dir = testing_support::fixture_dir();
    FixtureRun r;
    r.pair = load_stereo_pair(dir + "/im0.png", dir + "/im1.png");
    r.truth = read_pfm(dir + "/disp0GT.pfm");
    StereoParams params;
    params.ndisp = 32;
    r.result = run_stereo(r.pair.left, r.pair.right, params);
    r.confidence = confidence_map(r.result, r.pair.left, params);
    return r;
  }();
  return run;
}

}  // namespace

TEST(ConfidenceMap, ConfidentPixelsAreMoreOftenRight) {
  const FixtureRun& run = fixture_run();
  const StereoPair& pair = run.pair;
  const cv::Mat& truth = run.truth;
  const StereoResult& result = run.result;
  const cv::Mat& confidence = run.confidence;
  ASSERT_EQ(confidence.size(), pair.left.size());
  double low, high;
  cv::minMaxLoc(confidence, &low, &high);
  EXPECT_GE(low, 0.0);
  EXPECT_LE(high, 1.0);

  // bad-2 among all pixels with ground truth, and among those with C >= 0.5.
  int known = 0, bad = 0, confident = 0, confident_bad = 0;
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      const float t = truth.at<float>(y, x);
      if (!std::isfinite(t)) continue;
      const bool wrong = std::abs(result.disparity.at<float>(y, x) - t) > 2.0f;
      ++known;
      bad += wrong;
      if (confidence.at<float>(y, x) >= 0.5f) {
        ++confident;
        confident_bad += wrong;
      }
    }
  }
  const double bad_share = double(bad) / known;
  const double confident_bad_share = double(confident_bad) / confident;
  // Measured with the defaults: most pixels pass 0.5 (the bound asks for a quarter),
  // with about half the bad-2 of all pixels, 1.72 % against 3.49 % (0.49x). The finest
  // level's iteration after the check-and-fill (refill_iterations) makes some wrong
  // pixels consistent, which is why the bound is 0.55x and not lower; the figures
  // behind it are in docs/tuning-log.md, "Test fixture history".
  EXPECT_GE(double(confident) / known, 0.25);
  EXPECT_LE(confident_bad_share, 0.55 * bad_share)
      << "bad-2 " << bad_share << ", of confident pixels " << confident_bad_share;
}

// The neighbourhood term: ranked by C, the most confident pixels of the fixture are
// right more often than ranked by the pixel's own left/right agreement, and the pixels
// that fail the check (agreement <= 1/2) stay at or below 1/2.
TEST(ConfidenceMap, NeighbourhoodAgreementRanksBetterThanThePixelsOwn) {
  const FixtureRun& run = fixture_run();
  const cv::Mat& truth = run.truth;
  const StereoResult& result = run.result;
  const cv::Mat& confidence = run.confidence;
  const int width = truth.cols;
  std::vector<float> own_rank, map_rank;
  std::vector<bool> wrong;
  int failing = 0, above_half = 0;
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < width; ++x) {
      const float own = pms_confidence(result.raw_left.ptr<float>(),
                                       result.raw_right.ptr<float>(), width, x, y, -1.0f);
      if (own <= 0.5f) {
        ++failing;
        above_half += confidence.at<float>(y, x) > 0.5f;
      }
      const float t = truth.at<float>(y, x);
      if (!std::isfinite(t)) continue;
      own_rank.push_back(own);
      map_rank.push_back(confidence.at<float>(y, x));
      wrong.push_back(std::abs(result.disparity.at<float>(y, x) - t) > 2.0f);
    }
  }
  EXPECT_GT(failing, 0);
  EXPECT_EQ(above_half, 0) << "of " << failing << " pixels that fail the check";
  const double own_area = sparsification_auc_percent(own_rank, wrong);
  const double map_area = sparsification_auc_percent(map_rank, wrong);
  // Measured: 0.61 % against 1.65 % (0.37x).
  EXPECT_LT(map_area, 0.6 * own_area) << "map " << map_area << ", own agreement " << own_area;
}

// COCO run-length encoding (host/dataset/coco_rle.h): strings worked out by hand from
// pycocotools' algorithm (tests/dataset/coco_pycocotools_check.py checks the same table
// against pycocotools itself), round trips of random masks of awkward sizes, the box and
// area against the mask's, and malformed strings.
#include <gtest/gtest.h>

#include <random>

#include "host/dataset/coco_rle.h"
#include "host/dataset/gt_info.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

// A mask from rows of '0'/'1'.
cv::Mat mask_of(const std::vector<std::string>& rows) {
  cv::Mat mask(static_cast<int>(rows.size()), static_cast<int>(rows[0].size()), CV_8UC1);
  for (int y = 0; y < mask.rows; ++y) {
    for (int x = 0; x < mask.cols; ++x) mask.at<uchar>(y, x) = rows[y][x] == '1' ? 255 : 0;
  }
  return mask;
}

// A one-column mask (h x 1) of runs zeros, ones, zeros, ...
cv::Mat column_of_runs(const std::vector<int>& runs) {
  std::vector<std::string> rows;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    for (int k = 0; k < runs[i]; ++k) rows.push_back(i % 2 ? "1" : "0");
  }
  return mask_of(rows);
}

struct KnownRle {
  const char* name;
  cv::Mat mask;
  std::vector<std::uint32_t> counts;
  std::string text;
};

// Worked by hand: column-major runs starting with zeros; each count as 5-bit groups
// plus 48, 0x20 = more; from index 3 on, the difference to the count two before.
std::vector<KnownRle> known_rles() {
  return {
      // Columns 000, 110, 001, 100 -> runs 3, 2, 3, 2, 2; index 3: 2 - 2 = 0 -> '0';
      // index 4: 2 - 3 = -1 -> group 31 with the sign bit, no more -> 31 + 48 = 'O'.
      {"3x4", mask_of({"0101", "0100", "0010"}), {3, 2, 3, 2, 2}, "3230O"},
      {"all zero 2x3", mask_of({"000", "000"}), {6}, "6"},
      {"all set 2x2", mask_of({"11", "11"}), {0, 4}, "04"},
      // 35 = 3 + 32: group 3 with "more" (3 + 32 + 48 = 'S'), then 1 -> '1'.
      {"35 zeros, 5 set", column_of_runs({35, 5}), {35, 5}, "S15"},
      // 44 = 12 + 32: 12 + 32 + 48 = 92, a backslash, which JSON must escape.
      {"44 zeros, 6 set", column_of_runs({44, 6}), {44, 6}, "\\16"},
      // index 3: 2 - 5 = -3 -> 29 with the sign bit set -> 29 + 48 = 'M'.
      {"negative difference", column_of_runs({1, 5, 3, 2}), {1, 5, 3, 2}, "153M"},
  };
}

}  // namespace

TEST(CocoRle, KnownStringsWorkedOutByHand) {
  for (const KnownRle& known : known_rles()) {
    SCOPED_TRACE(known.name);
    const CocoRle rle = rle_encode(known.mask);
    EXPECT_EQ(rle.height, known.mask.rows);
    EXPECT_EQ(rle.width, known.mask.cols);
    EXPECT_EQ(rle.counts, known.counts);
    EXPECT_EQ(rle_counts_to_string(rle.counts), known.text);
    EXPECT_EQ(rle_counts_from_string(known.text, "test"), known.counts);
    EXPECT_TRUE(cv::countNonZero(rle_decode(rle) != known.mask) == 0);
  }
}

TEST(CocoRle, RandomMasksRoundTripWithPycocotoolsBoxAndArea) {
  std::mt19937 random(20240611);
  const std::vector<cv::Size> sizes{{1, 1}, {1, 17}, {23, 1}, {31, 19}, {64, 3}, {130, 97}};
  for (const cv::Size& size : sizes) {
    for (int density : {0, 3, 50, 97, 100}) {
      SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height) + " at " +
                   std::to_string(density) + "%");
      cv::Mat mask(size, CV_8UC1);
      // Blobs of random length in raster order, so runs of many lengths occur.
      for (int i = 0; i < mask.rows * mask.cols;) {
        const int length = 1 + static_cast<int>(random() % 40);
        const uchar value = static_cast<int>(random() % 100) < density ? 255 : 0;
        for (int k = 0; k < length && i < mask.rows * mask.cols; ++k, ++i) {
          mask.at<uchar>(i / mask.cols, i % mask.cols) = value;
        }
      }
      const CocoRle rle = rle_encode(mask);
      const std::string text = rle_counts_to_string(rle.counts);
      CocoRle back{rle.height, rle.width, rle_counts_from_string(text, "test")};
      EXPECT_EQ(back.counts, rle.counts);
      EXPECT_EQ(cv::countNonZero(rle_decode(back) != mask), 0);
      EXPECT_EQ(rle_area(rle), static_cast<std::uint64_t>(cv::countNonZero(mask)));
      const BopBox box = mask_box(mask);
      const cv::Rect rle_rect = rle_box(rle);
      if (box.empty()) {
        EXPECT_EQ(rle_rect, cv::Rect());
      } else {
        EXPECT_EQ(rle_rect, cv::Rect(box.x, box.y, box.width, box.height));
      }
    }
  }
}

TEST(CocoRle, NonZeroValuesOtherThan255AreSet) {
  const cv::Mat mask = (cv::Mat_<uchar>(2, 2) << 0, 1, 7, 0);
  EXPECT_EQ(rle_encode(mask).counts, (std::vector<std::uint32_t>{1, 2, 1}));
}

TEST(CocoRle, MalformedStringsAreInputErrors) {
  EXPECT_TRUE(throws_input_error([] { rle_counts_from_string("3 2", "f.json"); }, "f.json",
                                 "character ' '"));
  EXPECT_TRUE(throws_input_error([] { rle_counts_from_string("3p", "f.json"); }, "f.json",
                                 "character 'p'"));
  // 'S' says another group follows, and none does.
  EXPECT_TRUE(throws_input_error([] { rle_counts_from_string("3S", "f.json"); }, "f.json",
                                 "ends inside a count"));
  // A first count of -1.
  EXPECT_TRUE(
      throws_input_error([] { rle_counts_from_string("O", "f.json"); }, "f.json", "out of range"));
  EXPECT_TRUE(throws_input_error(
      [] {
        rle_decode(CocoRle{2, 2, {1, 2}});
      },
      "rle", "counts sum to 3"));
}

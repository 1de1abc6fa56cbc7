#pragma once
// COCO's run-length encoding of binary masks, exactly as pycocotools' maskUtils.encode
// and decode (its maskApi.c) define it, so that COCO tools read our masks unchanged.
//
// The mask is read in column-major order (down the first column, then the next); counts
// are the lengths of the alternating runs, starting with a run of zeros (0 when the first
// pixel is set). The compressed string writes each count as 5-bit groups, least
// significant first, one character per group: 0x20 marks "more groups follow", 0x10 is
// the sign bit of the last group, and 48 is added to make the character printable
// ('0'..'o'). From the fourth count on (index i > 2) the difference to the count two
// places before is written instead of the count, which keeps alternating runs of similar
// length short.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace flexsight {

struct CocoRle {
  int height = 0;
  int width = 0;
  std::vector<std::uint32_t> counts;  // run lengths, summing to height * width
};

// The runs of a CV_8UC1 mask (non-zero = set). Throws InputError ("rle: ...") for
// another type.
CocoRle rle_encode(const cv::Mat& mask);

// The CV_8UC1 mask (255 set, 0 not) of `rle`. Throws InputError ("rle: ...") when the
// counts do not sum to height * width.
cv::Mat rle_decode(const CocoRle& rle);

// Set pixels (pycocotools' maskUtils.area) and tight box [x, y, w, h]
// (maskUtils.toBbox; all 0 for an empty mask).
std::uint64_t rle_area(const CocoRle& rle);
cv::Rect rle_box(const CocoRle& rle);

// The compressed "counts" string of pycocotools (rleToString).
std::string rle_counts_to_string(const std::vector<std::uint32_t>& counts);

// The counts of a compressed string (rleFrString). Throws InputError naming `subject`
// for a character outside '0'..'o', a string that ends inside a count, or a count that
// would be negative or too large.
std::vector<std::uint32_t> rle_counts_from_string(const std::string& text,
                                                  const std::string& subject);

}  // namespace flexsight

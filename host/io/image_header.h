#pragma once
// An image's size read from its file's header, without decoding the pixels, so that a
// command can check every image of a data set against its annotations before the first
// unit of work.
#include <opencv2/core.hpp>
#include <string>

namespace flexsight {

// Width x height of the image at `path`: from the IHDR chunk of a PNG, the frame header
// (SOFn) of a JPEG; any other format is decoded whole (imread_unchanged). Throws
// InputError naming `path` for a missing or unreadable file, a header that is cut short
// or holds a zero size, and a file no decoder reads.
cv::Size image_size_from_header(const std::string& path);

}  // namespace flexsight

#pragma once
// A PNG's chunk structure checked before OpenCV decodes it: libpng reports a truncated
// or damaged file on stderr with its own "libpng error: ..." line beside ours, so such a
// file is refused here, with the file and the problem in our one line, and never reaches
// the decoder.
#include <string>

namespace flexsight {

// Nothing for bytes that are not a PNG (no PNG signature: another decoder's business).
// For a PNG: InputError naming `path` (where `bytes` came from) when a chunk runs past
// the end of the file, a chunk's CRC does not match its bytes, the first chunk is not
// IHDR, or the file ends before IEND.
void check_png_structure(const std::string& path, const std::string& bytes);

// The same for the file at `path`, read whole.
void check_png_structure(const std::string& path);

}  // namespace flexsight

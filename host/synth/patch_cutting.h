#pragma once
// Segmented patches of parts cut from a BOP folder with mask_visib (`flexsight synth
// patches`), for the semi-synthetic generator (patch_library.h reads them back).
#include <cstdint>
#include <string>

#include "host/dataset/bop_reader.h"
#include "host/io/progress_bar.h"

namespace flexsight {

// Writes a patch of every part of `reader`'s images at least `min_visible` visible with
// at least `min_pixels` visible pixels into `folder` (patch_file_name's layout), and
// returns how many; `progress` advances per image. InputError naming `source` for an
// image without mask_visib/.
std::int64_t cut_patches(const BopReader& reader, const std::string& source, const std::string& folder,
                         double min_visible, double min_pixels, ProgressBar& progress);

}  // namespace flexsight

#include "host/sim/bin_writer.h"

#include <filesystem>
#include <fstream>

#include "host/dataset/bop_layout.h"
#include "host/dataset/bop_writer.h"
#include "host/io/atomic_file.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/middeval3_files.h"
#include "host/io/pfm.h"

namespace flexsight {

void write_bin_folder(const std::string& folder, const StereoRig& rig, const BinViews& views) {
  namespace fs = std::filesystem;
  auto file = [&](const char* name) { return folder + "/" + name; };
  write_atomically(file(middeval3::kCalib), [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << rig.calib_text() << projector_calib_text(views.projector);
    if (!out.flush()) throw InputError(file(middeval3::kCalib), "cannot be written");
  });
  write_image(file(middeval3::kLeftImage), views.im0);
  write_image(file(middeval3::kRightImage), views.im1);
  write_image(file(middeval3::kLeftPassive), views.im0_passive);
  write_image(file(middeval3::kRightPassive), views.im1_passive);
  write_pfm(file(middeval3::kLeftTruth), views.disp0);
  write_pfm(file(middeval3::kRightTruth), views.disp1);
  write_image(file(middeval3::kNonoccMask), views.nocc0);
  write_image(file(kProjectorPatternFile), views.pattern);

  // The BOP writer lays out a split folder (root/<scene>/...); the bin folder is the
  // scene folder itself, so its one scene is written aside and moved up.
  const std::string aside = folder + "/.bop";
  BopWriterOptions options;
  options.rgb_format = BopWriterOptions::RgbFormat::png;
  BopWriter writer(aside, options);
  writer.write(views.left);
  writer.finish();
  const fs::path scene = fs::path(aside) / bop_layout::scene_dir(views.left.scene_id);
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(scene)) entries.push_back(entry.path());
  for (const fs::path& entry : entries) fs::rename(entry, fs::path(folder) / entry.filename());
  fs::remove_all(aside);
}

}  // namespace flexsight

#include "host/sim/bin_writer.h"

#include <filesystem>
#include <fstream>

#include "host/dataset/bop_layout.h"
#include "host/dataset/bop_writer.h"
#include "host/io/atomic_file.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"

namespace flexsight {

void write_bin_folder(const std::string& folder, const StereoRig& rig, const BinViews& views) {
  namespace fs = std::filesystem;
  write_atomically(folder + "/calib.txt", [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << rig.calib_text();
    if (!out.flush()) throw InputError(folder + "/calib.txt", "cannot be written");
  });
  write_image(folder + "/im0.png", views.im0);
  write_image(folder + "/im1.png", views.im1);
  write_image(folder + "/im0_passive.png", views.im0_passive);
  write_image(folder + "/im1_passive.png", views.im1_passive);
  write_pfm(folder + "/disp0GT.pfm", views.disp0);
  write_pfm(folder + "/disp1GT.pfm", views.disp1);
  write_image(folder + "/mask0nocc.png", views.nocc0);

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

// flexsight synth full: the paper's full-synthetic images, CAD parts rendered at random
// poses, materials and lights over background photographs (host/synth/full_synthetic.h).
#include <iostream>
#include <nlohmann/json.hpp>

#include "host/cli/arguments.h"
#include "host/cli/synth_commands.h"
#include "host/cli/synth_run_options.h"
#include "host/cli/synth_settings_options.h"
#include "host/dataset/coco_writer.h"
#include "host/dataset/detection_data.h"
#include "host/io/input_error.h"
#include "host/synth/background_library.h"
#include "host/synth/full_synthetic.h"
#include "host/synth/part_library.h"

namespace flexsight {
namespace {

void print_help() {
  FullSyntheticSettings defaults;
  std::cout << "usage: flexsight synth full --count N -o OUT_DIR [options]\n"
               "  --cad DIR             the parts: STL, PLY, OBJ in mm, ids from the file names\n"
               "                        (default " << default_cad_dir() << ")\n"
               "  --backgrounds DIR     photographs behind the parts (default\n"
               "                        " << default_backgrounds_dir() << ")\n"
               "  --size WxH            image size (default 300x300)\n"
            << synth_options_help()
            << "The distributions (defaults; docs/synth.md says why):\n"
            << settings_options_help(full_synthetic_setting_options(defaults));
}

}  // namespace

int run_synth_full_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const std::string cad_option = take_option(args, "--cad");
  const std::string backgrounds_option = take_option(args, "--backgrounds");
  FullSyntheticSettings settings;
  take_size_option(args, settings.width, settings.height);
  take_settings_options(args, full_synthetic_setting_options(settings));
  SynthRunOptions run = take_synth_run_options(args);
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("synth full", "unexpected argument '" + args[0] + "'");
  settings.store_depth = run.dataset.bop.write_depth;
  settings.store_masks = true;  // the COCO file's visible masks come from them
  settings.check();

  // Every input is read before the first image is made: a bad mesh or background
  // folder fails now, not an hour into the run.
  const std::string cad = cad_option.empty() ? default_cad_dir() : cad_option;
  const std::string backgrounds_dir =
      backgrounds_option.empty() ? default_backgrounds_dir() : backgrounds_option;
  const PartLibrary parts = PartLibrary::load_folder(cad);
  const BackgroundLibrary backgrounds(backgrounds_dir);
  for (int i = 0; i < backgrounds.size(); ++i) backgrounds.load(i);

  for (int i = 0; i < parts.size(); ++i) {
    const int id = parts.part(i).obj_id;
    run.dataset.categories.push_back({id, default_category_name(id), "part"});
  }
  // What makes the images, for dataset_info.json: shards of one data set must agree on
  // it (the merge checks), and a user can tell later how a data set was made.
  run.dataset.settings = {{"generator", "full"},
                          {"count", run.count},
                          {"seed", run.seed},
                          {"cad", cad},
                          {"backgrounds", backgrounds_dir},
                          {"settings", settings_json(full_synthetic_setting_options(settings),
                                                     settings.width, settings.height)}};
  run_synthesis(
      run,
      [&](std::int64_t index) {
        return render_full_synthetic(settings, parts, backgrounds, run.seed, index);
      },
      "images");
  std::cerr << "wrote " << shard_end_image(run) - shard_first_image(run)
            << " full-synthetic images to " << run.output << "\n";
  return 0;
}

}  // namespace flexsight

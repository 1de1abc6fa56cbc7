// flexsight synth semi: the paper's semi-synthetic images, segmented part patches
// pasted on background photographs (host/synth/semi_synthetic.h).
#include <algorithm>
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
#include "host/synth/patch_library.h"
#include "host/synth/semi_synthetic.h"

namespace flexsight {
namespace {

void print_help() {
  SemiSyntheticSettings defaults;
  std::cout << "usage: flexsight synth semi --patches DIR --count N -o OUT_DIR [options]\n"
               "  --patches DIR         segmented parts: RGBA PNGs (or X.png + X_mask.png) in\n"
               "                        folders named by object id (what synth patches writes);\n"
               "                        real photographs of the parts are what the method wants\n"
               "  --backgrounds DIR     photographs behind the parts (default\n"
               "                        " << default_backgrounds_dir() << ")\n"
               "  --size WxH            image size (default 300x300)\n"
            << synth_options_help()
            << "The distributions (defaults; docs/synth.md says why):\n"
            << settings_options_help(semi_synthetic_setting_options(defaults));
}

}  // namespace

int run_synth_semi_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const std::string patches_dir = take_option(args, "--patches");
  const std::string backgrounds_option = take_option(args, "--backgrounds");
  SemiSyntheticSettings settings;
  take_size_option(args, settings.width, settings.height);
  take_settings_options(args, semi_synthetic_setting_options(settings));
  SynthRunOptions run = take_synth_run_options(args);
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("synth semi", "unexpected argument '" + args[0] + "'");
  if (patches_dir.empty()) throw InputError("option --patches", "a folder of patches is required");
  // Pasted images have no depth (depth/ would hold nothing but zeros).
  run.dataset.bop.write_depth = false;
  settings.store_masks = true;  // the COCO file's visible masks come from them
  settings.check();

  const std::string backgrounds_dir =
      backgrounds_option.empty() ? default_backgrounds_dir() : backgrounds_option;
  const std::vector<Patch> patches = load_patch_library(patches_dir);
  const BackgroundLibrary backgrounds(backgrounds_dir);
  for (int i = 0; i < backgrounds.size(); ++i) backgrounds.load(i);

  std::vector<int> ids;
  for (const Patch& patch : patches) ids.push_back(patch.obj_id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (int id : ids) run.dataset.categories.push_back({id, default_category_name(id), "part"});
  run.dataset.settings = {{"generator", "semi"},
                          {"count", run.count},
                          {"seed", run.seed},
                          {"patches", patches_dir},
                          {"patch_count", patches.size()},
                          {"backgrounds", backgrounds_dir},
                          {"settings", settings_json(semi_synthetic_setting_options(settings),
                                                     settings.width, settings.height)}};
  run_synthesis(
      run,
      [&](std::int64_t index) {
        return render_semi_synthetic(settings, patches, backgrounds, run.seed, index);
      },
      "images");
  std::cerr << "wrote " << shard_end_image(run) - shard_first_image(run)
            << " semi-synthetic images to " << run.output << "\n";
  return 0;
}

}  // namespace flexsight

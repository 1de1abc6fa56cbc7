// flexsight synth bin: bins of T-LESS parts dropped with rigid-body physics, seen by the
// active stereo rig (room light and a red dot projector), one MiddEval3 + BOP scene
// folder per bin (host/sim/, docs/sim.md).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "host/cli/arguments.h"
#include "host/cli/synth_commands.h"
#include "host/cli/synth_settings_options.h"
#include "host/dataset/detection_data.h"
#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/object_ids.h"
#include "host/io/progress_bar.h"
#include "host/io/staged_folder.h"
#include "host/sim/bin_scene.h"
#include "host/sim/bin_writer.h"
#include "host/synth/part_library.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

std::vector<SettingOption> bin_setting_options(BinSimSettings& s) {
  return {
      {"baseline", &s.rig.baseline_mm, nullptr, "between the camera centres, mm"},
      {"distance", &s.rig.volume.distance, nullptr, "from the cameras to the volume's centroid, mm"},
      {"focal", &s.rig.focal_px, nullptr, "focal length, pixels (0: fill the views with the volume)"},
      {"wall-thickness", &s.bin.wall_thickness_mm, nullptr, "bin walls, mm"},
      {"floor-thickness", &s.bin.floor_thickness_mm, nullptr, "bin floor, mm"},
      {"min-parts", nullptr, &s.min_parts, "fewest parts dropped per bin"},
      {"max-parts", nullptr, &s.max_parts, "most parts dropped per bin"},
      {"dots", nullptr, &s.projector.dots, "projector dots"},
      {"projector-fov", &s.projector.fov_degrees, nullptr, "projector field of view (square), degrees"},
      {"dot-size", &s.projector.dot_sigma_degrees, nullptr, "dot radius (Gaussian sigma), degrees"},
      {"noise", &s.noise_sigma, nullptr, "camera noise sigma, grey levels"},
      {"room-light", &s.room_light, nullptr, "ceiling light strength"},
      {"ambient", &s.ambient, nullptr, "ambient light"},
  };
}

// "AxBxC" (mm) into three numbers.
void take_triple_option(std::vector<std::string>& args, const std::string& name, double& a,
                        double& b, double& c) {
  const std::string text = take_option(args, name);
  if (text.empty()) return;
  double values[3];
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lfx%lfx%lf%c", &values[0], &values[1], &values[2], &tail) != 3) {
    throw InputError("option " + name, "expected LxWxH in mm (e.g. 500x340x120), got '" + text + "'");
  }
  a = values[0];
  b = values[1];
  c = values[2];
}

void print_help() {
  BinSimSettings defaults;
  std::cout
      << "usage: flexsight synth bin --count N -o OUT_DIR [options]\n"
         "  -o OUT_DIR            where the bins go: OUT_DIR/bin000, bin001, ... (OUT_DIR is\n"
         "                        made when missing; its parent must exist)\n"
         "  --count N             bins to make (required)\n"
         "  --seed S              every bin is a function of (seed, bin index) (default 1)\n"
         "  --cad DIR             the parts: STL, PLY, OBJ in mm (default " << default_cad_dir() << ")\n"
         "  --parts IDS           the parts the bins are made of: object ids separated by\n"
         "                        commas (e.g. 5 or 5,12; default: every part of --cad)\n"
         "  --parts MIN..MAX      (the older form, with '..') parts dropped per bin, as\n"
         "                        --min-parts and --max-parts (default 10..20)\n"
         "  --size WxH            image size of both cameras (default 1280x960)\n"
         "  --volume XxYxZ        working volume, mm (default 600x400x400)\n"
         "  --bin LxWxH           bin: inner floor and wall height, mm (default 500x340x120)\n"
         "  --pile sparse|dense   sparse: 10..20 parts in one wave; dense: 30..80 in waves of 10,\n"
         "                        each settled before the next (default sparse)\n"
         "  --vary LIST           draw per bin (recorded in sim_info.json): all, none, or a list of\n"
         "                        material, lights, projector, camera, optics (default none)\n"
         "  --noise-level LO..HI  with --vary camera: where the bins' shot and read noise fall in\n"
         "                        the drawn range, 0 least .. 1 most (default 0..1)\n"
         "  --pattern-seed S      layout of the projector's dots (default 1)\n"
         "  --projector-power P   radiance of a dot (default 2.5)\n"
         "  --threads N           threads per bin (default: all; same bytes for any N)\n"
         "  --overwrite           replace bin folders that exist\n"
         "Settings (defaults; docs/sim.md says why):\n"
      << settings_options_help(bin_setting_options(defaults));
}

std::string bin_name(std::int64_t index, std::int64_t count) {
  // Three digits at least, as many as the last bin needs: names sort in bin order.
  const std::size_t digits = std::max<std::size_t>(3, std::to_string(count - 1).size());
  const std::string number = std::to_string(index);
  return "bin" + std::string(digits - std::min(digits, number.size()), '0') + number;
}

struct SynthBinOptions {
  BinSimSettings settings;
  std::string output;
  bool overwrite = false;
  std::int64_t count = 0;
  std::uint32_t seed = 1;
  std::string cad;  // empty: default_cad_dir()
  std::vector<int> part_ids;  // --parts IDS: the bins are made of these parts only; empty: all
};

// --parts MIN..MAX (the older form, with '..') into the settings; --parts IDS otherwise.
void set_parts_option(const std::string& parts_text, SynthBinOptions& options) {
  const std::size_t dots = parts_text.find("..");
  if (dots == std::string::npos) {
    options.part_ids = parse_object_ids(parts_text, "--parts");
    return;
  }
  BinSimSettings& settings = options.settings;
  settings.min_parts = int(parse_whole_number("--parts", parts_text.substr(0, dots), 1, 200));
  settings.max_parts = int(parse_whole_number("--parts", parts_text.substr(dots + 2), 1, 200));
}

// --noise-level LO..HI into the settings (checked by BinSimSettings::check).
void set_noise_level(const std::string& text, BinSimSettings& settings) {
  const std::size_t dots = text.find("..");
  char* end = nullptr;
  const std::string lo = dots == std::string::npos ? "" : text.substr(0, dots);
  const std::string hi = dots == std::string::npos ? "" : text.substr(dots + 2);
  settings.noise_level_min = std::strtod(lo.c_str(), &end);
  const bool lo_ok = !lo.empty() && *end == 0;
  settings.noise_level_max = std::strtod(hi.c_str(), &end);
  if (!lo_ok || hi.empty() || *end != 0) {
    throw InputError("option --noise-level", "expected LO..HI (e.g. 0..1), got '" + text + "'");
  }
}

SynthBinOptions parse_synth_bin_options(std::vector<std::string> args) {
  SynthBinOptions options;
  BinSimSettings& settings = options.settings;
  options.output = take_option(args, "-o");
  options.overwrite = take_flag(args, "--overwrite");
  const std::string count_text = take_option(args, "--count");
  const std::string seed_text = take_option(args, "--seed");
  options.cad = take_option(args, "--cad");
  const bool parts_given = std::find(args.begin(), args.end(), "--parts") != args.end();
  const std::string parts_text = take_option(args, "--parts");
  const std::string pattern_seed_text = take_option(args, "--pattern-seed");
  const std::string threads_text = take_option(args, "--threads");
  const std::string pile_text = take_option(args, "--pile");
  const std::string vary_text = take_option(args, "--vary");
  const std::string noise_level_text = take_option(args, "--noise-level");
  // Before the options that may narrow the dense pile's part count.
  if (pile_text == "dense") {
    use_dense_pile(settings);
  } else if (!pile_text.empty() && pile_text != "sparse") {
    throw InputError("option --pile", "expected sparse or dense, got '" + pile_text + "'");
  }

  const double power = take_number_option(args, "--projector-power", settings.projector.power);
  take_size_option(args, settings.rig.width, settings.rig.height);
  take_triple_option(args, "--volume", settings.rig.volume.width, settings.rig.volume.height,
                     settings.rig.volume.depth);
  take_triple_option(args, "--bin", settings.bin.length_mm, settings.bin.width_mm,
                     settings.bin.wall_height_mm);
  take_settings_options(args, bin_setting_options(settings));
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("synth bin", "unexpected argument '" + args[0] + "'");

  if (options.output.empty()) throw InputError("option -o", "an output folder is required");
  if (count_text.empty()) throw InputError("option --count", "the number of bins is required");
  options.count = parse_whole_number("--count", count_text, 1, 1000000);
  options.seed = static_cast<std::uint32_t>(
      seed_text.empty() ? 1 : parse_whole_number("--seed", seed_text, 0, 4294967295LL));
  if (!pattern_seed_text.empty()) {
    settings.projector.pattern_seed =
        static_cast<std::uint32_t>(parse_whole_number("--pattern-seed", pattern_seed_text, 0, 4294967295LL));
  }
  if (!threads_text.empty()) settings.threads = int(parse_whole_number("--threads", threads_text, 0, 4096));
  if (parts_given) set_parts_option(parts_text, options);
  if (!vary_text.empty()) settings.vary = parse_vary_list(vary_text);
  if (!noise_level_text.empty()) set_noise_level(noise_level_text, settings);
  settings.projector.power = float(power);
  settings.check();
  return options;
}

// Where the bins go, checked before any work: nothing is written on bad input.
void check_bin_folders(const SynthBinOptions& options) {
  const std::string& output = options.output;
  const fs::path root(output);
  std::error_code ec;
  if (fs::exists(root, ec) && !fs::is_directory(root, ec)) {
    throw InputError("option -o", output + " exists and is not a folder");
  }
  const fs::path parent = root.has_parent_path() ? root.parent_path() : fs::path(".");
  if (!fs::exists(root, ec) && !fs::is_directory(parent.empty() ? fs::path(".") : parent, ec)) {
    throw InputError("option -o", "the parent folder of " + output + " does not exist");
  }
  for (std::int64_t i = 0; i < options.count; ++i) {
    const fs::path bin = root / bin_name(i, options.count);
    if (fs::exists(bin, ec) && !options.overwrite &&
        !(fs::is_directory(bin, ec) && fs::is_empty(bin, ec))) {
      throw InputError("option -o", bin.string() + " exists and is not empty (use --overwrite)");
    }
  }
}

// What made the bin and how the physics went (no timings: same seed, same bytes).
void write_sim_info(const std::string& folder, const SynthBinOptions& options, const std::string& cad,
                    std::int64_t index, const BinViews& views) {
  const BinSimSettings& settings = options.settings;
  BinSimSettings named = settings;  // a copy: bin_setting_options takes settings it may write
  nlohmann::json info = {{"generator", "synth bin"},
                         {"seed", options.seed},
                         {"bin_index", index},
                         {"cad", cad},
                         {"parts_dropped", views.physics.dropped},
                         {"parts_removed", views.physics.removed},
                         {"parts_in_bin", views.parts.size()},
                         {"physics_steps", views.physics.steps},
                         {"at_rest", views.physics.at_rest},
                         {"pattern_seed", settings.projector.pattern_seed},
                         {"settings", settings_json(bin_setting_options(named), settings.rig.width,
                                                    settings.rig.height)}};
  // Only when used: the default bins' files stay as they were.
  if (!options.part_ids.empty()) info["part_ids"] = options.part_ids;
  if (settings.pile == BinPile::dense) info["pile"] = "dense";
  if (settings.vary != 0) info["variation"] = variation_json(views.variation);
  write_atomically(folder + "/sim_info.json", [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << info.dump(2) << "\n";
    if (!out.flush()) throw InputError(folder + "/sim_info.json", "cannot be written");
  });
}

}  // namespace

int run_synth_bin_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const SynthBinOptions options = parse_synth_bin_options(std::move(args));
  check_bin_folders(options);
  const std::string cad = options.cad.empty() ? default_cad_dir() : options.cad;
  const PartLibrary parts = options.part_ids.empty()
                                ? PartLibrary::load_folder(cad)
                                : select_parts(PartLibrary::load_folder(cad), options.part_ids, "--parts", cad);
  const BinSimulator simulator(options.settings, parts);

  const fs::path root(options.output);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) throw InputError("option -o", options.output + " cannot be created (" + ec.message() + ")");
  ProgressBar progress(options.count, "bins");
  double physics_ms = 0.0, render_ms = 0.0;
  std::int64_t part_count = 0;
  for (std::int64_t i = 0; i < options.count; ++i) {
    StagedFolder staged((root / bin_name(i, options.count)).string(), options.overwrite);
    const BinViews views = simulator.simulate(options.seed, i);
    write_bin_folder(staged.path(), simulator.rig(), views);
    write_sim_info(staged.path(), options, cad, i, views);
    staged.commit();
    physics_ms += views.physics_ms;
    render_ms += views.render_ms;
    part_count += static_cast<std::int64_t>(views.parts.size());
    progress.advance();
  }
  progress.finish();
  std::fprintf(stderr,
               "wrote %lld bins to %s: %.1f parts per bin, %.2f s physics + %.2f s rendering per bin\n",
               static_cast<long long>(options.count), options.output.c_str(), double(part_count) / options.count,
               physics_ms / 1000.0 / options.count, render_ms / 1000.0 / options.count);
  return 0;
}

}  // namespace flexsight

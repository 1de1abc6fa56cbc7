// flexsight pose-templates: the edge templates of every CAD part of a folder, made once
// per model set and read by `flexsight pose` (host/pose/edge_template.h).
#include <chrono>
#include <filesystem>
#include <iostream>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/progress_bar.h"
#include "host/pose/template_file.h"
#include "host/synth/part_library.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight pose-templates CAD_DIR -o TEMPLATES [options]\n"
               "  CAD_DIR            the parts: STL, PLY, OBJ in mm, ids from the file names\n"
               "  -o TEMPLATES       the template file (binary; read by flexsight pose)\n"
               "  --views N          viewpoints on the sphere (default 600)\n"
               "  --in-plane N       rotations about the optical axis the search tries\n"
               "                     (default 40: 9 degrees apart)\n"
               "  --points N         edge points kept per view (default 128)\n"
               "  --crease DEG       an edge where the surface turns by more (default 35)\n"
               "  --threads N        threads (default: all cores)\n";
}

int take_whole_option(std::vector<std::string>& args, const std::string& name, int fallback,
                      int lo, int hi) {
  const std::string text = take_option(args, name);
  if (text.empty()) return fallback;
  return static_cast<int>(parse_whole_number(name, text, lo, hi));
}

}  // namespace

int run_pose_templates_command(std::vector<std::string> args) {
  if (auto code = usage_exit_code(args, print_help)) return *code;
  const std::string output = take_option(args, "-o");
  TemplateParams params;
  params.views = take_whole_option(args, "--views", params.views, 1, 100000);
  params.in_plane_steps = take_whole_option(args, "--in-plane", params.in_plane_steps, 1, 360);
  params.points_per_view = take_whole_option(args, "--points", params.points_per_view, 4, 4096);
  params.crease_degrees = static_cast<float>(take_number_option(args, "--crease", params.crease_degrees));
  if (!(params.crease_degrees > 0.0f && params.crease_degrees < 180.0f)) {
    throw InputError("option --crease", "expected an angle in (0, 180) degrees");
  }
  const int threads = take_whole_option(args, "--threads", 0, 1, 1024);
  reject_unknown_options(args);
  if (args.size() != 1) throw InputError("pose-templates", "expected one CAD folder, got " + std::to_string(args.size()) + " arguments");
  if (output.empty()) throw InputError("option -o", "missing: the template file to write");
  if (std::filesystem::is_directory(output)) throw InputError(output, "is a folder; -o names the template file");
  check_output_file(output);
  params.check();
  const PartLibrary library = PartLibrary::load_folder(args[0]);

  const auto start = std::chrono::steady_clock::now();
  TemplateSet set;
  set.params = params;
  ProgressBar progress(library.size(), "parts");
  for (int i = 0; i < library.size(); ++i) {
    const LibraryPart& part = library.part(i);
    set.parts.push_back(make_part_templates(*part.mesh, part.obj_id, part.name, params, threads));
    progress.advance();
  }
  progress.finish();
  write_template_set(output, set);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "pose-templates: " << library.size() << " parts x " << params.views << " views x up to "
            << params.points_per_view << " edge points -> " << output << " ("
            << std::filesystem::file_size(output) / 1024 << " KB, " << seconds << " s)\n";
  return 0;
}

}  // namespace flexsight

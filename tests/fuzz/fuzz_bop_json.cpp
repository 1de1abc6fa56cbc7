// A BOP scene's JSON files (host/dataset/bop_json.h read_bop_scene_json). The input is
// scene_camera.json, scene_gt.json and scene_gt_info.json cut at NUL bytes (which JSON
// text never holds); a third part absent means no scene_gt_info.json.
#include <filesystem>

#include "host/dataset/bop_json.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> parts = fuzz::split(data, size, '\0');
  static const std::string scene = fuzz::scratch_dir() + "/scene";
  std::filesystem::create_directories(scene);
  const char* names[] = {"scene_camera.json", "scene_gt.json", "scene_gt_info.json"};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string path = scene + "/" + names[i];
    if (i < parts.size()) {
      fuzz::write_file(std::string("scene/") + names[i], parts[i]);
    } else {
      std::filesystem::remove(path);
    }
  }
  for (const bool require_depth_scale : {true, false}) {
    fuzz::expect_input_error_only([&] { flexsight::read_bop_scene_json(scene, require_depth_scale); });
  }
  return 0;
}

// The BOP challenge's pose results CSV (host/dataset/bop_pose_results.h). What reads
// must write back and read again as the same records.
#include "host/dataset/bop_pose_results.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("results.csv", data, size);
  fuzz::expect_input_error_only([&] {
    const auto records = flexsight::read_bop_pose_results(path);
    const std::string again_path = fuzz::scratch_dir() + "/again.csv";
    flexsight::write_bop_pose_results(again_path, records);
    const auto again = flexsight::read_bop_pose_results(again_path);
    if (again.size() != records.size()) std::abort();
    for (std::size_t i = 0; i < records.size(); ++i) {
      const auto& a = records[i];
      const auto& b = again[i];
      if (a.scene_id != b.scene_id || a.im_id != b.im_id || a.obj_id != b.obj_id || a.score != b.score ||
          a.R != b.R || a.t != b.t || a.time_s != b.time_s) {
        std::abort();
      }
    }
  });
  return 0;
}

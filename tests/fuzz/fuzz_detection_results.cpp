// A detection results file, COCO or BOP form (host/eval/detection_results_reader.h),
// read against the ground truth of the committed fixture tests/data/detect/tless_synth_8
// both as a COCO file and as a BOP scene (FLEXSIGHT_FUZZ_TRUTH_DIR).
#include "host/eval/detection_results_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const flexsight::DetectionGroundTruth coco_truth(FLEXSIGHT_FUZZ_TRUTH_DIR "/coco_instances.json");
  static const flexsight::DetectionGroundTruth bop_truth(FLEXSIGHT_FUZZ_TRUTH_DIR "/000000");
  const std::string path = fuzz::write_file("results.json", data, size);
  for (const auto* truth : {&coco_truth, &bop_truth}) {
    fuzz::expect_input_error_only([&] {
      const flexsight::DetectionResults results = flexsight::read_detection_results(path, *truth);
      if (results.per_image.size() != truth->images().size()) std::abort();
    });
  }
  return 0;
}

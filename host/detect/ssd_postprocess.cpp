#include "host/detect/ssd_postprocess.h"

#include <climits>

#include "fallback/detect/reference_stage_set.h"
#include "host/detect/ssd_schedule.h"
#include "host/io/input_error.h"

namespace flexsight {

void validate_ssd_inputs(const SsdOutputs& outputs, size_t anchor_floats,
                         const SsdPostprocessParams& params) {
  params.check();
  if (outputs.box_encodings == nullptr || outputs.class_logits == nullptr) {
    throw InputError("SSD outputs", "the box encodings or class logits are missing");
  }
  if (outputs.anchors <= 0 || outputs.classes <= 0) {
    throw InputError("SSD outputs", "need at least one anchor and one foreground class, got " +
                                        std::to_string(outputs.anchors) + " anchors and " +
                                        std::to_string(outputs.classes) + " classes");
  }
  // The kernels index with int: logits (N x (C + 1)), scores and the mask must fit.
  const long long top_k = params.top_k_per_class;
  if (static_cast<long long>(outputs.anchors) * (outputs.classes + 1) > INT_MAX / 4 ||
      outputs.classes * top_k * SSD_MASK_WORDS(top_k) > INT_MAX / 4) {
    throw InputError("SSD outputs", "too many anchors x classes for 32-bit indices");
  }
  if (anchor_floats != 4 * static_cast<size_t>(outputs.anchors)) {
    throw InputError("anchors", "there are " + std::to_string(anchor_floats / 4) +
                                    " anchors, the model outputs " +
                                    std::to_string(outputs.anchors) + " boxes");
  }
}

std::vector<Detection> ssd_postprocess_reference(const SsdOutputs& outputs,
                                                 const std::vector<float>& anchors,
                                                 const SsdPostprocessParams& params) {
  validate_ssd_inputs(outputs, anchors.size(), params);
  ReferenceSsdStages stages;
  const size_t n = static_cast<size_t>(outputs.anchors);
  const std::vector<float> encodings = stages.upload(outputs.box_encodings, 4 * n, "encodings");
  const std::vector<float> logits =
      stages.upload(outputs.class_logits, n * (outputs.classes + 1), "logits");
  SsdSchedule<ReferenceSsdStages> schedule(stages);
  return detections_from_records(
      schedule.run(encodings, logits, anchors, outputs.anchors, outputs.classes, params));
}

}  // namespace flexsight

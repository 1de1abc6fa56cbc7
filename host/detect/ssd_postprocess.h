#pragma once
// SSD post-processing on the reference path, and the input checks both paths share.
// The OpenCL path: opencl_ssd_postprocessor.h; the backend choice between them:
// ssd_postprocessor.h.
#include <vector>

#include "host/detect/detection.h"
#include "host/detect/ssd_params.h"

namespace flexsight {

// Throws InputError before any work: params.check()'s, and ("SSD outputs", ...) for
// missing arrays, no anchors or classes, or ("anchors", ...) when `anchor_floats` is not
// 4 floats per output row.
void validate_ssd_inputs(const SsdOutputs& outputs, size_t anchor_floats,
                         const SsdPostprocessParams& params);

// Decoding, scores, per-class NMS and the overall cut (host/detect/ssd_schedule.h) on
// the scalar reference stages: the detections, best first (score, then class, then
// anchor). `anchors`: N x 4 (ycenter, xcenter, height, width), ssd_anchors.h.
std::vector<Detection> ssd_postprocess_reference(const SsdOutputs& outputs,
                                                 const std::vector<float>& anchors,
                                                 const SsdPostprocessParams& params);

}  // namespace flexsight

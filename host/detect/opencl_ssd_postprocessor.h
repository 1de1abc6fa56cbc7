#pragma once
// The OpenCL path of SSD post-processing: the one schedule (ssd_schedule.h) over the
// kernels of kernels/detect/, giving ssd_postprocess_reference's detections byte for
// byte on a device with IEEE single precision and correctly rounded division.
#include <memory>
#include <string>
#include <vector>

#include "host/detect/ssd_postprocess.h"
#include "host/runtime/cl_context.h"
#include "host/runtime/kernel_timing.h"

namespace flexsight::opencl {

class OpenClSsdPostprocessor {
 public:
  // Builds the kernels on `context`, which other modules of the process may share
  // (host/runtime/shared_context.h), and uploads the model's anchors (N x 4, ycenter,
  // xcenter, height, width) once: InputError("anchors", ...) unless 4 floats each.
  // Throws OpenClError "building the kernels on #0 ...:
  // <log>" when they do not build. `profile`: record every kernel launch's time.
  OpenClSsdPostprocessor(std::shared_ptr<Context> context, const std::vector<float>& anchors,
                         bool profile = false);
  ~OpenClSsdPostprocessor();
  OpenClSsdPostprocessor(const OpenClSsdPostprocessor&) = delete;
  OpenClSsdPostprocessor& operator=(const OpenClSsdPostprocessor&) = delete;

  // As ssd_postprocess_reference with the anchors given above: same validation
  // (InputError), same detections. The intermediate buffers are kept for the next run
  // of the same shape. A failing OpenCL call throws OpenClError starting "running SSD
  // post-processing on #0 ...".
  std::vector<Detection> run(const SsdOutputs& outputs, const SsdPostprocessParams& params);

  int anchor_count() const;
  // Per-kernel device times of the last run (empty unless `profile`).
  std::vector<KernelTiming> kernel_timings() const;
  std::string device_description() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace flexsight::opencl

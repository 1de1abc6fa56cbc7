#pragma once
// SSD post-processing on the process's backend (host/runtime/compute_backend.h): the
// kernels on the shared OpenCL context when there is one, the reference path
// otherwise, with the same detections either way. This is what a detect command
// calls, once per frame, after the network:
//
//   ComputeBackend backend(options);                       // --device auto|opencl|reference
//   SsdPostprocessor post(backend, read_anchor_file(path, rows));
//   std::vector<Detection> found = post.run({encodings, logits, rows, classes}, params);
#include <memory>
#include <string>
#include <vector>

#include "host/detect/ssd_postprocess.h"
#include "host/runtime/compute_backend.h"

namespace flexsight {

class SsdPostprocessor {
 public:
  // Builds the kernels on `backend`'s context (which must outlive this) and uploads the
  // anchors (N x 4). Under opencl a kernel that does not build is an InputError
  // ("--device opencl: building the kernels on ...: <log>"); under auto the reference
  // path runs, with a notice.
  SsdPostprocessor(ComputeBackend& backend, std::vector<float> anchors);
  ~SsdPostprocessor();
  SsdPostprocessor(const SsdPostprocessor&) = delete;
  SsdPostprocessor& operator=(const SsdPostprocessor&) = delete;

  // "OpenCL path on #0 <device> (...)" or "reference path": where the next run() goes.
  std::string planned() const;

  // The detections of one image's outputs, best first. Inputs are validated first
  // (InputError). An OpenCL failure during the run throws InputError under opencl and
  // reruns on the reference path, with a notice, under auto. `ran_on_device` (when
  // given) tells which path produced the result.
  std::vector<Detection> run(const SsdOutputs& outputs, const SsdPostprocessParams& params,
                             bool* ran_on_device = nullptr);

 private:
  struct Device;
  ComputeBackend& backend_;
  std::vector<float> anchors_;
  std::unique_ptr<Device> device_;
};

}  // namespace flexsight

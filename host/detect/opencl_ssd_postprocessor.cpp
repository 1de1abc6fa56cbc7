#include "host/detect/opencl_ssd_postprocessor.h"

#include "host/detect/opencl_ssd_stages.h"
#include "host/detect/ssd_schedule.h"
#include "host/io/input_error.h"

namespace flexsight::opencl {
namespace {

// `buffer` with room for `count` floats, holding `values` (reallocated when the size
// changes: the same model gives the same sizes frame after frame).
void write_input(Context& context, Buffer<float>& buffer, const float* values, size_t count,
                 const char* what) {
  if (buffer.size() != count) buffer = Buffer<float>(context, count, what);
  buffer.write(values, count);
}

}  // namespace

struct OpenClSsdPostprocessor::State {
  std::shared_ptr<Context> context;
  KernelProfiler profiler;
  OpenClSsdStages stages;
  SsdSchedule<OpenClSsdStages> schedule;
  std::vector<float> host_anchors;  // for validate_ssd_inputs' count
  Buffer<float> anchors, encodings, logits;

  State(std::shared_ptr<Context> shared, const std::vector<float>& anchor_values, bool profile)
      : context(std::move(shared)), stages(*context, profile ? &profiler : nullptr),
        schedule(stages), host_anchors(anchor_values),
        anchors(*context, anchor_values, "anchors") {}
};

OpenClSsdPostprocessor::OpenClSsdPostprocessor(std::shared_ptr<Context> context,
                                               const std::vector<float>& anchors,
                                               bool profile) {
  if (anchors.empty() || anchors.size() % 4 != 0) {
    throw InputError("anchors", "need 4 floats per anchor, got " +
                                    std::to_string(anchors.size()) + " floats");
  }
  const std::string device = context->device().description();
  try {
    state_ = std::make_unique<State>(std::move(context), anchors, profile);
  } catch (const OpenClError& error) {
    throw OpenClError("building the kernels on " + device + ": " + error.what(), error.status());
  }
}

OpenClSsdPostprocessor::~OpenClSsdPostprocessor() = default;

int OpenClSsdPostprocessor::anchor_count() const {
  return static_cast<int>(state_->host_anchors.size() / 4);
}

std::vector<KernelTiming> OpenClSsdPostprocessor::kernel_timings() const {
  return state_->profiler.summary();
}

std::string OpenClSsdPostprocessor::device_description() const {
  return state_->context->device().description();
}

std::vector<Detection> OpenClSsdPostprocessor::run(const SsdOutputs& outputs,
                                                   const SsdPostprocessParams& params) {
  validate_ssd_inputs(outputs, state_->host_anchors.size(), params);
  State& s = *state_;
  try {
    s.profiler.clear();
    const size_t n = static_cast<size_t>(outputs.anchors);
    write_input(*s.context, s.encodings, outputs.box_encodings, 4 * n, "box encodings");
    write_input(*s.context, s.logits, outputs.class_logits, n * (outputs.classes + 1),
                "class logits");
    return detections_from_records(s.schedule.run(s.encodings, s.logits, s.anchors,
                                                  outputs.anchors, outputs.classes, params));
  } catch (const OpenClError& error) {
    throw OpenClError("running SSD post-processing on " + device_description() + ": " +
                          error.what(),
                      error.status());
  }
}

}  // namespace flexsight::opencl

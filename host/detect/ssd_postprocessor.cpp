#include "host/detect/ssd_postprocessor.h"

#include "host/io/input_error.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/detect/opencl_ssd_postprocessor.h"
#endif

namespace flexsight {

#if defined(FLEXSIGHT_HAVE_OPENCL)
struct SsdPostprocessor::Device {
  std::unique_ptr<opencl::OpenClSsdPostprocessor> postprocessor;
};
#else
struct SsdPostprocessor::Device {};
#endif

SsdPostprocessor::SsdPostprocessor(ComputeBackend& backend, std::vector<float> anchors)
    : backend_(backend), anchors_(std::move(anchors)), device_(std::make_unique<Device>()) {
  if (anchors_.empty() || anchors_.size() % 4 != 0) {
    throw InputError("anchors", "need 4 floats per anchor, got " +
                                    std::to_string(anchors_.size()) + " floats");
  }
#if defined(FLEXSIGHT_HAVE_OPENCL)
  device_->postprocessor = backend_.build_part<opencl::OpenClSsdPostprocessor>(
      [this](const std::shared_ptr<opencl::Context>& context) {
        return std::make_unique<opencl::OpenClSsdPostprocessor>(context, anchors_,
                                                                backend_.options().profile);
      });
#endif
}

SsdPostprocessor::~SsdPostprocessor() = default;

std::string SsdPostprocessor::planned() const {
#if defined(FLEXSIGHT_HAVE_OPENCL)
  if (device_->postprocessor) return backend_.description();
#endif
  return "reference path";
}

std::vector<Detection> SsdPostprocessor::run(const SsdOutputs& outputs,
                                             const SsdPostprocessParams& params,
                                             bool* ran_on_device) {
  // Bad input is the user's, whichever path would run: report it before choosing.
  validate_ssd_inputs(outputs, anchors_.size(), params);
  bool device_ready = false;
#if defined(FLEXSIGHT_HAVE_OPENCL)
  device_ready = device_->postprocessor != nullptr;
#endif
  return backend_.run(
      device_ready,
      [&] {
#if defined(FLEXSIGHT_HAVE_OPENCL)
        return device_->postprocessor->run(outputs, params);
#else
        return std::vector<Detection>();
#endif
      },
      [&] { return ssd_postprocess_reference(outputs, anchors_, params); }, ran_on_device);
}

}  // namespace flexsight

#include "host/stereo/stereo_backend.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/stereo/opencl_matcher.h"
#endif

namespace flexsight {

#if defined(FLEXSIGHT_HAVE_OPENCL)

struct StereoBackend::Impl {
  std::unique_ptr<ComputeBackend> owned;  // when constructed from options
  ComputeBackend* compute = nullptr;
  std::unique_ptr<opencl::OpenClMatcher> matcher;  // null: the reference path
  std::vector<opencl::KernelTiming> kernel_timings;
  size_t peak_device_bytes = 0;
};

StereoBackend::StereoBackend(ComputeBackend& compute) : impl_(std::make_unique<Impl>()) {
  impl_->compute = &compute;
  const bool profile = compute.options().profile;
  impl_->matcher = compute.build_part<opencl::OpenClMatcher>(
      [profile](const std::shared_ptr<opencl::Context>& context) {
        return std::make_unique<opencl::OpenClMatcher>(context, profile);
      });
}

std::string StereoBackend::planned() const {
  return impl_->matcher ? "OpenCL path on " + impl_->matcher->device_description()
                        : "reference path";
}

StereoResult StereoBackend::run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                                const StereoParams& params, const ProgressCallback& progress,
                                std::string* used) {
  impl_->kernel_timings.clear();
  impl_->peak_device_bytes = 0;
  bool on_device = false;
  StereoResult result = impl_->compute->run(
      impl_->matcher != nullptr,
      [&] {
        StereoResult device_result = impl_->matcher->run(left_rgb8, right_rgb8, params, progress);
        if (impl_->compute->options().profile) {
          impl_->kernel_timings = impl_->matcher->kernel_timings();
        }
        impl_->peak_device_bytes = impl_->matcher->peak_buffer_bytes();
        return device_result;
      },
      [&] { return run_stereo(left_rgb8, right_rgb8, params, progress); }, &on_device);
  if (used) *used = on_device ? planned() : "reference path";
  return result;
}

std::vector<opencl::KernelTiming> StereoBackend::kernel_timings() const {
  return impl_->kernel_timings;
}

size_t StereoBackend::peak_device_bytes() const { return impl_->peak_device_bytes; }

#else  // no OpenCL SDK when this build was configured: the reference path only

struct StereoBackend::Impl {
  std::unique_ptr<ComputeBackend> owned;
};

StereoBackend::StereoBackend(ComputeBackend&) : impl_(std::make_unique<Impl>()) {}

std::string StereoBackend::planned() const { return "reference path"; }

StereoResult StereoBackend::run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                                const StereoParams& params, const ProgressCallback& progress,
                                std::string* used) {
  if (used) *used = "reference path";
  return run_stereo(left_rgb8, right_rgb8, params, progress);
}

std::vector<opencl::KernelTiming> StereoBackend::kernel_timings() const { return {}; }

size_t StereoBackend::peak_device_bytes() const { return 0; }

#endif

StereoBackend::StereoBackend(const BackendOptions& options)
    : StereoBackend(std::make_unique<ComputeBackend>(options)) {}

StereoBackend::StereoBackend(std::unique_ptr<ComputeBackend> owned) : StereoBackend(*owned) {
  impl_->owned = std::move(owned);
}

StereoBackend::~StereoBackend() = default;

}  // namespace flexsight

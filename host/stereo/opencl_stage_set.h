#pragma once
// The OpenCL path as a stage set of the matcher's one schedule
// (host/stereo/patchmatch_schedule.h): the stages of OpenClStages, plus what the
// schedule needs to hold a run's data on the device: the pyramid (built there),
// buffers named for error messages, and each level's inputs with the other view's
// match records.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "host/stereo/opencl_stages.h"

namespace flexsight::opencl {

// What a level's stages read (DeviceLevel), owning the match records it points to.
struct OpenClLevel : DeviceLevel {
  OpenClLevel() = default;
  OpenClLevel(const OpenClLevel&) = delete;  // DeviceLevel::match points into it
  OpenClLevel& operator=(const OpenClLevel&) = delete;
  Buffer<float> match_records[2];
};

class OpenClStageSet : public OpenClStages {
 public:
  template <class T>
  using Array = Buffer<T>;
  using View = DeviceView;
  using Field = DeviceField;
  using Level = OpenClLevel;

  using OpenClStages::OpenClStages;

  // Level 0 from the host colour, then downsampled on the device, gradients and census
  // computed there.
  std::vector<View> build_pyramid(const cv::Mat& rgb8, int levels, int view,
                                  PmsCensusShape census);
  template <class T>
  Array<T> array(size_t count, const char* what) {
    return Buffer<T>(context(), count, what);
  }
  Array<float> upload(const std::vector<float>& values, const char* what) {
    return Buffer<float>(context(), values, what);
  }
  Array<std::uint8_t> upload(const std::vector<std::uint8_t>& values, const char* what) {
    return Buffer<std::uint8_t>(context(), values, what);
  }
  std::vector<float> download(const Array<float>& values) { return values.read(); }
  Field field(int width, int height, int view);
  Field planes_field(int width, int height, Array<float> planes) {
    return {width, height, std::move(planes), Buffer<float>()};
  }
  // The level's images and weights, and each view's match records packed for the cost
  // kernels.
  void prepare_level(Level& in, const View& left, const View& right,
                     const Array<float>& weights, const PmsCostParams& cost, int ndisp,
                     std::uint32_t seed);
  void finish() { context().finish(); }
};

}  // namespace flexsight::opencl

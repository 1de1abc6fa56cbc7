#pragma once
// The device-side counterparts of the reference's ViewImage, PlaneField and
// LevelInputs (fallback/), with the same layouts, so a stage's inputs and outputs can
// be copied between the two paths as they are.
#include <cstddef>
#include <cstdint>

#include "fallback/stereo/patchmatch_reference.h"
#include "host/runtime/cl_buffer.h"

namespace flexsight::opencl {

// The size of a level, what the buffers of a DeviceView or a DeviceField hold per pixel
// of. Both stay aggregates, initialised as {width, height, buffer, buffer}.
struct DeviceGrid {
  int width = 0;
  int height = 0;
  int pixels() const { return width * height; }
};

struct DeviceView : DeviceGrid {
  Buffer<float> color;     // 4 floats per pixel
  Buffer<float> gradient;  // 2 floats per pixel
};

struct DeviceField : DeviceGrid {
  Buffer<float> planes;  // 4 floats per pixel
  Buffer<float> cost;    // 1 float per pixel
};

// Floats of a view's match records (pack_match_samples): PMS_MATCH_RECORD per pixel and
// the 4 that the cost kernels' 16-float loads read past the last record.
inline size_t match_record_floats(size_t pixels) { return PMS_MATCH_RECORD * pixels + 4; }

struct DeviceLevel {
  const DeviceView* views[2] = {nullptr, nullptr};  // PMS_VIEW_LEFT, PMS_VIEW_RIGHT
  // Each view's match records, read when it is the other view of a cost.
  const Buffer<float>* match[2] = {nullptr, nullptr};
  const Buffer<float>* weights = nullptr;            // support weight table
  PmsCostParams cost{};
  int ndisp = 0;
  std::uint32_t seed = 0;
  float max_disparity() const { return static_cast<float>(ndisp - 1); }
};

}  // namespace flexsight::opencl

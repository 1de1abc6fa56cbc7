#pragma once
// One method per kernel of kernels/, each the device twin of a reference function of
// fallback/ with the same meaning of its arguments. The scheduler (opencl_matcher.cpp)
// and the tests (which compare every stage with its reference byte for byte) both call
// these. Outputs are allocated by the caller and must hold at least the pixels of the
// stage; nothing past them is written.
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "host/stereo/device_level.h"
#include "host/runtime/kernel_profiler.h"

namespace flexsight::opencl {

class OpenClStages {
 public:
  // Pixels per work item of the cost kernels (PMS_LANES of pms_lanes.h): they
  // evaluate that many pixels' costs together in OpenCL vector types, which a CPU driver
  // compiles to SIMD code where it could not vectorise across work items. 1, 4, 8 or 16;
  // the result is the same bytes whatever the count (tested). 1 is for GPUs, which
  // vectorise across work items in hardware and need as many of them as there are
  // pixels (FLEXSIGHT_CL_LANES selects it without a rebuild).
  static constexpr int kDefaultCostLanes = 8;
  static constexpr bool supports_cost_lanes(int lanes) {
    return lanes == 1 || lanes == 4 || lanes == 8 || lanes == 16;
  }
  // Spatial candidates propagate_spatial costs in one pass over the window
  // (PMS_SPATIAL_GROUP): their own view's samples are loaded once for all of them. 1 to
  // 8, same bytes whatever the count (tested). 8, the candidates of the near rings and
  // of the far ones alike, is the fastest (docs/tuning-log.md has the times).
  static constexpr int kDefaultSpatialGroup = 8;

  // Builds the programs (or takes them from the context's cache). `profiler` (may be
  // null) receives the event of every launch.
  explicit OpenClStages(Context& context, KernelProfiler* profiler = nullptr,
                        int cost_lanes = kDefaultCostLanes,
                        int spatial_group = kDefaultSpatialGroup);

  Context& context() { return context_; }

  // fallback/stereo/image_pyramid.cpp: downsample's colour part, then compute_gradient.
  void downsample_color(const DeviceView& fine, DeviceView& coarse);
  void compute_gradient(DeviceView& view, PmsCensusShape census = kSquareCensus);
  // The view's match records (match_record_floats of its pixels), which the cost
  // kernels read when it is the other view; no reference counterpart.
  void pack_match_samples(const DeviceView& view, Buffer<float>& match);

  // fallback/stereo/patchmatch_reference.cpp. `field` (and `fine`) must have their size set.
  void init_random_planes(const DeviceLevel& in, int view, std::uint32_t iteration,
                          DeviceField& field);
  // `unchanged` (may be null): pixels where it is nonzero keep their cost (reference).
  void evaluate_costs(const DeviceLevel& in, int view, DeviceField& field,
                      const Buffer<std::uint8_t>* unchanged = nullptr);
  void propagate_spatial(const DeviceLevel& in, int view, int parity,
                         const SearchSchedule& schedule, const Buffer<float>* confidence,
                         DeviceField& field);
  void propagate_view(const DeviceLevel& in, int view, int parity,
                      const SearchSchedule& schedule, const Buffer<float>* confidence,
                      const DeviceField& other, DeviceField& field);
  void refine_random(const DeviceLevel& in, int view, int parity, std::uint32_t iteration,
                     const SearchSchedule& schedule, const Buffer<float>* confidence,
                     DeviceField& field);
  void carry_planes_to_finer(const DeviceField& coarse, DeviceField& fine);
  void plane_disparities(const DeviceField& field, Buffer<float>& disparity);
  void lr_confidence(const Buffer<float>& disparity, const Buffer<float>& other_disparity,
                     int width, int height, int view, Buffer<float>& confidence);
  void upsample_nearest(const Buffer<float>& coarse, int coarse_width, int coarse_height,
                        Buffer<float>& fine, int fine_width, int fine_height);

  // fallback/stereo/postprocess_reference.cpp.
  void left_right_check(const Buffer<float>& disparity, const Buffer<float>& other_disparity,
                        int width, int height, int view, float tolerance,
                        Buffer<std::uint8_t>& consistent);
  void fill_inconsistent(const Buffer<float>& planes, const Buffer<std::uint8_t>& consistent,
                         int width, int height, float max_extrapolation,
                         Buffer<float>& filled);
  void weighted_median_filled(const Buffer<float>& disparity,
                              const Buffer<std::uint8_t>& consistent, const DeviceView& image,
                              const Buffer<float>& weights, int radius, int step,
                              float background_margin, Buffer<float>& filtered);
  void weighted_median_all(const Buffer<float>& disparity, const DeviceView& image,
                           const Buffer<float>& weights, int radius, Buffer<float>& filtered);
  // large_segment_mask and flat_planes (small_segments.cl). The mask takes a few
  // merge/flatten rounds, each ending in a blocking read of one flag.
  void large_segment_mask(const Buffer<float>& disparity, int width, int height,
                          float max_step, bool follow_slopes, int min_size,
                          Buffer<std::uint8_t>& large);
  void flat_planes(const Buffer<float>& disparity, int width, int height, Buffer<float>& planes);
  void mask_and(const Buffer<std::uint8_t>& other, int width, int height,
                Buffer<std::uint8_t>& mask);

 private:
  // A kernel of small_segments.cl (the small-segment mask, flat planes, mask_and).
  Kernel small_segments_kernel(const char* name);
  // Sets the leading arguments of the cost kernels (PMS_COST_KERNEL_ARGS), then `rest`.
  template <typename... Rest>
  void set_cost_args(Kernel& kernel, const DeviceLevel& in, int view, const Rest&... rest);
  void launch(Kernel& kernel, size_t width, size_t height);
  void launch_checkerboard(Kernel& kernel, int width, int height);
  void launch_dense_lanes(Kernel& kernel, int width, int height);
  // A kernel of weighted_median.cl whose windows have side x side samples.
  Kernel& median_kernel(const std::string& name, int side);

  size_t lane_items(size_t pixels) const;
  // The pixels of `parity` that are not confident, row by row, into unsure_list_ and
  // unsure_counts_ (list_unsure_pixels.cl); returns the list's row stride.
  int list_unsure_pixels(const Buffer<float>& confidence, int width, int height, int parity,
                         float confident_threshold);

  Context& context_;
  KernelProfiler* profiler_;
  int cost_lanes_;
  Kernel downsample_color_, compute_gradient_, pack_match_samples_, init_random_planes_,
      evaluate_costs_, propagate_spatial_, propagate_view_, refine_random_, carry_planes_to_finer_,
      plane_disparities_, lr_confidence_, list_unsure_pixels_, upsample_nearest_,
      left_right_check_, fill_inconsistent_, segment_init_, segment_merge_, segment_flatten_,
      segment_count_, segment_large_mask_, flat_planes_, mask_and_;
  // The work list of the unsure pixels' extra search steps, reused between launches.
  Buffer<int> unsure_list_;
  Buffer<int> unsure_counts_;
  // The kernels of weighted_median.cl by name and PMS_MEDIAN_MAX_SAMPLES (window samples).
  std::map<std::pair<std::string, int>, Kernel> weighted_median_;
};

}  // namespace flexsight::opencl

#include "host/stereo/opencl_stages.h"

#include "generated/stereo_kernel_sources.h"

#include <algorithm>
#include <stdexcept>

namespace flexsight::opencl {
namespace {

namespace src = kernel_sources::stereo;

int checked_lanes(int lanes) {
  if (!OpenClStages::supports_cost_lanes(lanes)) {
    throw std::invalid_argument("cost lanes must be 1, 4, 8 or 16, got " +
                                std::to_string(lanes));
  }
  return lanes;
}

// The build option that specialises the cost kernels for `lanes` pixels per work item.
std::string lanes_option(int lanes) { return "-DPMS_LANES=" + std::to_string(lanes); }

std::string spatial_option(int lanes, int group) {
  if (group < 1 || group > 8) {
    throw std::invalid_argument("spatial candidate group must be 1 to 8, got " +
                                std::to_string(group));
  }
  return lanes_option(lanes) + " -DPMS_SPATIAL_GROUP=" + std::to_string(group);
}

void require_view(const DeviceView& view, const char* stage) {
  require_size(view.color, 4LL * view.pixels(), stage);
  require_size(view.gradient, 2LL * view.pixels(), stage);
}

void require_field(const DeviceField& field, const char* stage) {
  require_size(field.planes, 4LL * field.pixels(), stage);
  require_size(field.cost, field.pixels(), stage);
}

// The level's two views and the field have one size (the reference assumes it too).
void require_level(const DeviceLevel& in, const DeviceField& field, const char* stage) {
  for (const DeviceView* view : in.views) {
    require_view(*view, stage);
    if (view->width != field.width || view->height != field.height) {
      throw std::invalid_argument(std::string(stage) + ": views and field differ in size");
    }
  }
  for (const Buffer<float>* match : in.match) {
    if (match == nullptr) throw std::invalid_argument(std::string(stage) + ": no match records");
    require_size(*match, static_cast<long long>(match_record_floats(field.pixels())), stage);
  }
  require_size(*in.weights, PMS_WEIGHT_TABLE_SIZE, stage);
  require_field(field, stage);
}

}  // namespace

OpenClStages::OpenClStages(Context& context, KernelProfiler* profiler, int cost_lanes,
                           int spatial_group)
    : context_(context), profiler_(profiler), cost_lanes_(checked_lanes(cost_lanes)),
      downsample_color_(Kernel(context_, src::build_view, "downsample_color")),
      compute_gradient_(Kernel(context_, src::build_view, "compute_gradient")),
      pack_match_samples_(Kernel(context_, src::build_view, "pack_match_samples")),
      init_random_planes_(Kernel(context_, src::init_random_planes, "init_random_planes",
                                      lanes_option(cost_lanes_))),
      evaluate_costs_(
          Kernel(context_, src::evaluate_costs, "evaluate_costs", lanes_option(cost_lanes_))),
      propagate_spatial_(
          Kernel(context_, src::propagate_spatial, "propagate_spatial",
                      spatial_option(cost_lanes_, spatial_group))),
      propagate_view_(
          Kernel(context_, src::propagate_view, "propagate_view", lanes_option(cost_lanes_))),
      refine_random_(Kernel(context_, src::refine_random, "refine_random", lanes_option(cost_lanes_))),
      carry_planes_to_finer_(Kernel(context_, src::carry_planes_to_finer, "carry_planes_to_finer")),
      plane_disparities_(Kernel(context_, src::plane_disparities, "plane_disparities")),
      lr_confidence_(Kernel(context_, src::lr_confidence, "lr_confidence")),
      list_unsure_pixels_(Kernel(context_, src::list_unsure_pixels, "list_unsure_pixels")),
      upsample_nearest_(Kernel(context_, src::upsample_nearest, "upsample_nearest")),
      left_right_check_(Kernel(context_, src::left_right_check, "left_right_check")),
      fill_inconsistent_(Kernel(context_, src::fill_inconsistent, "fill_inconsistent")),
      segment_init_(small_segments_kernel("segment_init")),
      segment_merge_(small_segments_kernel("segment_merge")),
      segment_flatten_(small_segments_kernel("segment_flatten")),
      segment_count_(small_segments_kernel("segment_count")),
      segment_large_mask_(small_segments_kernel("segment_large_mask")),
      flat_planes_(small_segments_kernel("flat_planes")),
      mask_and_(small_segments_kernel("mask_and")) {}

Kernel OpenClStages::small_segments_kernel(const char* name) {
  return Kernel(context_, src::small_segments, name);
}

template <typename... Rest>
void OpenClStages::set_cost_args(Kernel& kernel, const DeviceLevel& in, int view,
                                 const Rest&... rest) {
  const DeviceView& ref = *in.views[view];
  kernel.set_args(ref.color, ref.gradient, *in.match[1 - view], *in.weights, ref.width,
                  ref.height, in.cost, view, rest...);
}

void OpenClStages::launch(Kernel& kernel, size_t width, size_t height) {
  launch_profiled(kernel, width, height, profiler_);
}

size_t OpenClStages::lane_items(size_t pixels) const {
  const size_t lanes = static_cast<size_t>(cost_lanes_);
  return (pixels + lanes - 1) / lanes;
}

// One work item per cost_lanes_ pixels of the parity: half a row, rounded up.
void OpenClStages::launch_checkerboard(Kernel& kernel, int width, int height) {
  launch(kernel, lane_items((static_cast<size_t>(width) + 1) / 2), height);
}

// One work item per cost_lanes_ consecutive pixels of a row.
void OpenClStages::launch_dense_lanes(Kernel& kernel, int width, int height) {
  launch(kernel, lane_items(static_cast<size_t>(width)), height);
}

void OpenClStages::downsample_color(const DeviceView& fine, DeviceView& coarse) {
  require_size(fine.color, 4LL * fine.pixels(), "downsample_color");
  require_size(coarse.color, 4LL * coarse.pixels(), "downsample_color");
  downsample_color_.set_args(fine.color, fine.width, fine.height, coarse.color, coarse.width,
                             coarse.height);
  launch(downsample_color_, coarse.width, coarse.height);
}

void OpenClStages::compute_gradient(DeviceView& view, PmsCensusShape census) {
  require_view(view, "compute_gradient");
  compute_gradient_.set_args(view.color, view.width, view.height, view.gradient,
                             census.half_rows, census.half_cols, census.half_row_length);
  launch(compute_gradient_, view.width, view.height);
}

void OpenClStages::pack_match_samples(const DeviceView& view, Buffer<float>& match) {
  require_view(view, "pack_match_samples");
  require_size(match, static_cast<long long>(match_record_floats(view.pixels())),
               "pack_match_samples");
  pack_match_samples_.set_args(view.color, view.gradient, view.width, view.height, match);
  launch(pack_match_samples_, view.width, view.height);
}

void OpenClStages::init_random_planes(const DeviceLevel& in, int view, std::uint32_t iteration,
                                      DeviceField& field) {
  require_level(in, field, "init_random_planes");
  set_cost_args(init_random_planes_, in, view, in.seed, iteration, in.max_disparity(),
                field.planes, field.cost);
  launch_dense_lanes(init_random_planes_, field.width, field.height);
}

void OpenClStages::evaluate_costs(const DeviceLevel& in, int view, DeviceField& field,
                                  const Buffer<std::uint8_t>* unchanged) {
  require_level(in, field, "evaluate_costs");
  if (unchanged) require_size(*unchanged, field.pixels(), "evaluate_costs");
  set_cost_args(evaluate_costs_, in, view, unchanged, field.planes, field.cost);
  launch_dense_lanes(evaluate_costs_, field.width, field.height);
}

int OpenClStages::list_unsure_pixels(const Buffer<float>& confidence, int width, int height,
                                     int parity, float confident_threshold) {
  const int stride = (width + 1) / 2;
  const size_t entries = static_cast<size_t>(stride) * height;
  if (unsure_list_.size() < entries) unsure_list_ = Buffer<int>(context_, entries, "unsure pixels");
  if (unsure_counts_.size() < static_cast<size_t>(height)) {
    unsure_counts_ = Buffer<int>(context_, height, "unsure pixel counts");
  }
  list_unsure_pixels_.set_args(confidence, width, height, parity, confident_threshold, stride,
                               unsure_list_, unsure_counts_);
  launch(list_unsure_pixels_, height, 1);
  return stride;
}

// The reference's per-pixel rule (pms_spatial_candidate_tried) as two launches with the
// same order per pixel: every pixel of the parity tries the near candidates, then the
// unsure ones the rest. Launching the far candidates over a list keeps confident lanes
// from riding along idle beside an unsure one. With schedule.unsure_only the confident
// pixels try none: one launch of every candidate over the list.
void OpenClStages::propagate_spatial(const DeviceLevel& in, int view, int parity,
                                     const SearchSchedule& schedule,
                                     const Buffer<float>* confidence, DeviceField& field) {
  require_level(in, field, "propagate_spatial");
  if (confidence) require_size(*confidence, field.pixels(), "propagate_spatial");
  const Buffer<int>* every_pixel = nullptr;
  const int near = !confidence           ? PMS_SPATIAL_CANDIDATES
                   : schedule.unsure_only ? 0
                                          : std::clamp(schedule.confident_spatial_candidates, 0,
                                                       PMS_SPATIAL_CANDIDATES);
  if (near > 0) {
    set_cost_args(propagate_spatial_, in, view, parity, 0, near, every_pixel, every_pixel, 0,
                  field.planes, field.cost);
    launch_checkerboard(propagate_spatial_, field.width, field.height);
  }
  if (near < PMS_SPATIAL_CANDIDATES) {
    const int stride = list_unsure_pixels(*confidence, field.width, field.height, parity,
                                          schedule.confident_threshold);
    const Buffer<int>* unsure = &unsure_list_;
    const Buffer<int>* counts = &unsure_counts_;
    set_cost_args(propagate_spatial_, in, view, parity, near, PMS_SPATIAL_CANDIDATES, unsure,
                  counts, stride, field.planes, field.cost);
    launch_checkerboard(propagate_spatial_, field.width, field.height);
  }
}

// Every pixel of the parity, or with schedule.unsure_only the unsure ones of the list.
void OpenClStages::propagate_view(const DeviceLevel& in, int view, int parity,
                                  const SearchSchedule& schedule,
                                  const Buffer<float>* confidence, const DeviceField& other,
                                  DeviceField& field) {
  require_level(in, field, "propagate_view");
  require_field(other, "propagate_view");
  if (confidence) require_size(*confidence, field.pixels(), "propagate_view");
  if (confidence && schedule.unsure_only) {
    const int stride = list_unsure_pixels(*confidence, field.width, field.height, parity,
                                          schedule.confident_threshold);
    const Buffer<int>* unsure = &unsure_list_;
    const Buffer<int>* counts = &unsure_counts_;
    set_cost_args(propagate_view_, in, view, parity, other.planes, unsure, counts, stride,
                  field.planes, field.cost);
  } else {
    const Buffer<int>* every_pixel = nullptr;
    set_cost_args(propagate_view_, in, view, parity, other.planes, every_pixel, every_pixel, 0,
                  field.planes, field.cost);
  }
  launch_checkerboard(propagate_view_, field.width, field.height);
}

// The reference's per-pixel rule (confident pixels skip the trials wider than
// confident_max_range, which come first) as two launches with the same order per pixel:
// the unsure pixels of the parity try the wide trials, then every pixel the rest. With
// schedule.unsure_only every trial is "wide": the unsure pixels try them all, the
// confident ones none.
void OpenClStages::refine_random(const DeviceLevel& in, int view, int parity,
                                 std::uint32_t iteration, const SearchSchedule& schedule,
                                 const Buffer<float>* confidence, DeviceField& field) {
  require_level(in, field, "refine_random");
  if (confidence) require_size(*confidence, field.pixels(), "refine_random");
  const Buffer<int>* every_pixel = nullptr;
  const int trials = pms_search_trial_count(schedule.initial_range, schedule.min_range);
  const int wide = !confidence           ? 0
                   : schedule.unsure_only ? trials
                                          : pms_search_wide_trial_count(
                                                schedule.initial_range, trials,
                                                schedule.confident_max_range);
  if (wide > 0) {
    const int stride = list_unsure_pixels(*confidence, field.width, field.height, parity,
                                          schedule.confident_threshold);
    const Buffer<int>* unsure = &unsure_list_;
    const Buffer<int>* counts = &unsure_counts_;
    set_cost_args(refine_random_, in, view, parity, in.seed, iteration, in.max_disparity(),
                  schedule.initial_range, schedule.normal_range, 0, wide, unsure, counts,
                  stride, field.planes, field.cost);
    launch_checkerboard(refine_random_, field.width, field.height);
  }
  if (wide < trials) {
    set_cost_args(refine_random_, in, view, parity, in.seed, iteration, in.max_disparity(),
                  schedule.initial_range, schedule.normal_range, wide, trials, every_pixel,
                  every_pixel, 0, field.planes, field.cost);
    launch_checkerboard(refine_random_, field.width, field.height);
  }
}

void OpenClStages::carry_planes_to_finer(const DeviceField& coarse, DeviceField& fine) {
  require_size(coarse.planes, 4LL * coarse.pixels(), "carry_planes_to_finer");
  require_size(fine.planes, 4LL * fine.pixels(), "carry_planes_to_finer");
  carry_planes_to_finer_.set_args(coarse.planes, coarse.width, coarse.height, fine.planes,
                                  fine.width, fine.height);
  launch(carry_planes_to_finer_, fine.width, fine.height);
}

void OpenClStages::plane_disparities(const DeviceField& field, Buffer<float>& disparity) {
  require_size(field.planes, 4LL * field.pixels(), "plane_disparities");
  require_size(disparity, field.pixels(), "plane_disparities");
  plane_disparities_.set_args(field.planes, field.width, field.height, disparity);
  launch(plane_disparities_, field.width, field.height);
}

void OpenClStages::lr_confidence(const Buffer<float>& disparity,
                                 const Buffer<float>& other_disparity, int width, int height,
                                 int view, Buffer<float>& confidence) {
  const long long pixels = 1LL * width * height;
  require_size(disparity, pixels, "lr_confidence");
  require_size(other_disparity, pixels, "lr_confidence");
  require_size(confidence, pixels, "lr_confidence");
  lr_confidence_.set_args(disparity, other_disparity, width, height, view, confidence);
  launch(lr_confidence_, width, height);
}

void OpenClStages::upsample_nearest(const Buffer<float>& coarse, int coarse_width,
                                    int coarse_height, Buffer<float>& fine, int fine_width,
                                    int fine_height) {
  require_size(coarse, 1LL * coarse_width * coarse_height, "upsample_nearest");
  require_size(fine, 1LL * fine_width * fine_height, "upsample_nearest");
  upsample_nearest_.set_args(coarse, coarse_width, coarse_height, fine, fine_width, fine_height);
  launch(upsample_nearest_, fine_width, fine_height);
}

void OpenClStages::left_right_check(const Buffer<float>& disparity,
                                    const Buffer<float>& other_disparity, int width, int height,
                                    int view, float tolerance, Buffer<std::uint8_t>& consistent) {
  const long long pixels = 1LL * width * height;
  require_size(disparity, pixels, "left_right_check");
  require_size(other_disparity, pixels, "left_right_check");
  require_size(consistent, pixels, "left_right_check");
  left_right_check_.set_args(disparity, other_disparity, width, height, view, tolerance,
                             consistent);
  launch(left_right_check_, width, height);
}

void OpenClStages::fill_inconsistent(const Buffer<float>& planes,
                                     const Buffer<std::uint8_t>& consistent, int width,
                                     int height, float max_extrapolation,
                                     Buffer<float>& filled) {
  const long long pixels = 1LL * width * height;
  require_size(planes, 4 * pixels, "fill_inconsistent");
  require_size(consistent, pixels, "fill_inconsistent");
  require_size(filled, 4 * pixels, "fill_inconsistent");
  fill_inconsistent_.set_args(planes, consistent, width, height, max_extrapolation, filled);
  launch(fill_inconsistent_, width, height);
}

void OpenClStages::weighted_median_filled(const Buffer<float>& disparity,
                                          const Buffer<std::uint8_t>& consistent,
                                          const DeviceView& image, const Buffer<float>& weights,
                                          int radius, int step, float background_margin,
                                          Buffer<float>& filtered) {
  const long long pixels = image.pixels();
  require_size(disparity, pixels, "weighted_median_filled");
  require_size(consistent, pixels, "weighted_median_filled");
  require_size(image.color, 4 * pixels, "weighted_median_filled");
  require_size(weights, PMS_WEIGHT_TABLE_SIZE, "weighted_median_filled");
  require_size(filtered, pixels, "weighted_median_filled");
  if (radius < 0 || step < 1) throw std::invalid_argument("weighted_median_filled: bad window");
  Kernel& kernel = median_kernel("weighted_median_filled", 2 * (radius / step) + 1);
  kernel.set_args(disparity, consistent, image.color, weights, image.width, image.height, radius,
                  step, background_margin, filtered);
  launch(kernel, image.width, image.height);
}

void OpenClStages::weighted_median_all(const Buffer<float>& disparity, const DeviceView& image,
                                       const Buffer<float>& weights, int radius,
                                       Buffer<float>& filtered) {
  const long long pixels = image.pixels();
  require_size(disparity, pixels, "weighted_median_all");
  require_size(image.color, 4 * pixels, "weighted_median_all");
  require_size(weights, PMS_WEIGHT_TABLE_SIZE, "weighted_median_all");
  require_size(filtered, pixels, "weighted_median_all");
  if (radius < 0) throw std::invalid_argument("weighted_median_all: bad window");
  Kernel& kernel = median_kernel("weighted_median_all", 2 * radius + 1);
  kernel.set_args(disparity, image.color, weights, image.width, image.height, radius, filtered);
  // Built with PMS_LANES = cost_lanes_: one work item per that many pixels of a row.
  launch_dense_lanes(kernel, image.width, image.height);
}

void OpenClStages::large_segment_mask(const Buffer<float>& disparity, int width, int height,
                                      float max_step, bool follow_slopes, int min_size,
                                      Buffer<std::uint8_t>& large) {
  const long long pixels = 1LL * width * height;
  require_size(disparity, pixels, "large_segment_mask");
  require_size(large, pixels, "large_segment_mask");
  Buffer<int> labels(context_, static_cast<size_t>(pixels), "segment labels");
  Buffer<int> counts(context_, static_cast<size_t>(pixels), "segment sizes");
  Buffer<int> changed(context_, 1, "segment merge flag");
  segment_init_.set_args(width, height, labels, counts);
  launch(segment_init_, width, height);
  segment_merge_.set_args(disparity, width, height, max_step, follow_slopes ? 1 : 0, labels,
                          changed);
  segment_flatten_.set_args(width, height, labels);
  // Every round that reports a change links at least one root under another, so this
  // ends; how many rounds depends on the order the device runs the work items in.
  for (;;) {
    changed.fill(0);
    launch(segment_merge_, width, height);
    launch(segment_flatten_, width, height);
    if (changed.read()[0] == 0) break;
  }
  segment_count_.set_args(width, height, labels, counts);
  launch(segment_count_, width, height);
  segment_large_mask_.set_args(width, height, labels, counts, min_size, large);
  launch(segment_large_mask_, width, height);
}

void OpenClStages::flat_planes(const Buffer<float>& disparity, int width, int height,
                               Buffer<float>& planes) {
  const long long pixels = 1LL * width * height;
  require_size(disparity, pixels, "flat_planes");
  require_size(planes, 4 * pixels, "flat_planes");
  flat_planes_.set_args(disparity, width, height, planes);
  launch(flat_planes_, width, height);
}

void OpenClStages::mask_and(const Buffer<std::uint8_t>& other, int width, int height,
                            Buffer<std::uint8_t>& mask) {
  const long long pixels = 1LL * width * height;
  require_size(other, pixels, "mask_and");
  require_size(mask, pixels, "mask_and");
  mask_and_.set_args(other, width, height, mask);
  launch(mask_and_, width, height);
}

Kernel& OpenClStages::median_kernel(const std::string& name, int side) {
  // The kernel's private sample arrays hold exactly one window (see the reference).
  const int samples = side * side;
  const auto key = std::make_pair(name, samples);
  auto found = weighted_median_.find(key);
  if (found == weighted_median_.end()) {
    found = weighted_median_
                .emplace(key, Kernel(context_, src::weighted_median, name.c_str(),
                                          "-DPMS_MEDIAN_MAX_SAMPLES=" +
                                              std::to_string(samples) + " " +
                                              lanes_option(cost_lanes_)))
                .first;
  }
  return found->second;
}

}  // namespace flexsight::opencl

#pragma once
// The reference path as a stage set of the matcher's one schedule
// (host/stereo/patchmatch_schedule.h): every stage of patchmatch_reference.h and
// postprocess_reference.h with the signatures of the OpenCL stages (outputs last,
// allocated by the caller), over std::vector and the host images. Nothing here
// computes; it adapts.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "fallback/stereo/image_pyramid.h"
#include "fallback/stereo/patchmatch_reference.h"
#include "fallback/stereo/postprocess_reference.h"

namespace flexsight {

class ReferenceStageSet {
 public:
  template <class T>
  using Array = std::vector<T>;
  using View = ViewImage;
  using Field = PlaneField;
  using Level = LevelInputs;

  // `threads`: OpenMP threads of every stage (at least 1).
  explicit ReferenceStageSet(int threads) : threads_(threads) {}

  std::vector<View> build_pyramid(const cv::Mat& rgb8, int levels, int /*view*/,
                                  PmsCensusShape census) {
    return flexsight::build_pyramid(rgb8, levels, census);
  }
  template <class T>
  Array<T> array(size_t count, const char* /*what*/) {
    return Array<T>(count);
  }
  Array<float> upload(std::vector<float> values, const char* /*what*/) { return values; }
  Array<std::uint8_t> upload(std::vector<std::uint8_t> values, const char* /*what*/) { return values; }
  std::vector<float> download(const Array<float>& values) { return values; }
  Field field(int width, int height, int /*view*/) {
    Field field;
    field.resize(width, height);
    return field;
  }
  Field planes_field(int width, int height, Array<float> planes) {
    Field field;
    field.width = width;
    field.height = height;
    field.planes = std::move(planes);
    return field;
  }
  void prepare_level(Level& in, const View& left, const View& right,
                     const Array<float>& weights, const PmsCostParams& cost, int ndisp,
                     std::uint32_t seed) {
    in.views[PMS_VIEW_LEFT] = &left;
    in.views[PMS_VIEW_RIGHT] = &right;
    in.weights = weights.data();
    in.cost = cost;
    in.ndisp = ndisp;
    in.seed = seed;
    in.threads = threads_;
  }
  void finish() {}

  // patchmatch_reference.h
  void init_random_planes(const Level& in, int view, std::uint32_t iteration, Field& field) {
    flexsight::init_random_planes(in, view, iteration, field);
  }
  void evaluate_costs(const Level& in, int view, Field& field,
                      const Array<std::uint8_t>* unchanged) {
    flexsight::evaluate_costs(in, view, field, unchanged);
  }
  void propagate_spatial(const Level& in, int view, int parity, const SearchSchedule& schedule,
                         const Array<float>* confidence, Field& field) {
    flexsight::propagate_spatial(in, view, parity, schedule, confidence, field);
  }
  void propagate_view(const Level& in, int view, int parity, const SearchSchedule& schedule,
                      const Array<float>* confidence, const Field& other, Field& field) {
    flexsight::propagate_view(in, view, parity, schedule, confidence, other, field);
  }
  void refine_random(const Level& in, int view, int parity, std::uint32_t iteration,
                     const SearchSchedule& schedule, const Array<float>* confidence,
                     Field& field) {
    flexsight::refine_random(in, view, parity, iteration, schedule, confidence, field);
  }
  void carry_planes_to_finer(const Field& coarse, Field& fine) {
    flexsight::carry_planes_to_finer(coarse, fine);
  }
  void plane_disparities(const Field& field, Array<float>& disparity) {
    disparity = flexsight::plane_disparities(field, threads_);
  }
  void lr_confidence(const Array<float>& disparity, const Array<float>& other_disparity,
                     int width, int height, int view, Array<float>& confidence) {
    confidence =
        flexsight::lr_confidence(disparity, other_disparity, width, height, view, threads_);
  }
  void upsample_nearest(const Array<float>& coarse, int coarse_width, int coarse_height,
                        Array<float>& fine, int fine_width, int fine_height) {
    fine = flexsight::upsample_nearest(coarse, coarse_width, coarse_height, fine_width,
                                       fine_height);
  }

  // postprocess_reference.h
  void left_right_check(const Array<float>& disparity, const Array<float>& other_disparity,
                        int width, int height, int view, float tolerance,
                        Array<std::uint8_t>& consistent) {
    consistent = flexsight::left_right_check(disparity, other_disparity, width, height, view,
                                             tolerance, threads_);
  }
  void fill_inconsistent(const Array<float>& planes, const Array<std::uint8_t>& consistent,
                         int width, int height, float max_extrapolation,
                         Array<float>& filled) {
    filled = flexsight::fill_inconsistent(planes, consistent, width, height, max_extrapolation,
                                          threads_);
  }
  void weighted_median_filled(const Array<float>& disparity,
                              const Array<std::uint8_t>& consistent, const View& image,
                              const Array<float>& weights, int radius, int step,
                              float background_margin, Array<float>& filtered) {
    filtered = flexsight::weighted_median_filled(disparity, consistent, image, weights.data(),
                                                 radius, step, background_margin, threads_);
  }
  void weighted_median_all(const Array<float>& disparity, const View& image,
                           const Array<float>& weights, int radius, Array<float>& filtered) {
    filtered =
        flexsight::weighted_median_all(disparity, image, weights.data(), radius, threads_);
  }
  void large_segment_mask(const Array<float>& disparity, int width, int height, float max_step,
                          bool follow_slopes, int min_size, Array<std::uint8_t>& large) {
    large = flexsight::large_segment_mask(disparity, width, height, max_step, min_size,
                                          follow_slopes);
  }
  void flat_planes(const Array<float>& disparity, int /*width*/, int /*height*/,
                   Array<float>& planes) {
    planes = flexsight::flat_planes(disparity);
  }
  void mask_and(const Array<std::uint8_t>& other, int /*width*/, int /*height*/,
                Array<std::uint8_t>& mask) {
    flexsight::mask_and(mask, other);
  }

 private:
  int threads_;
};

}  // namespace flexsight

#pragma once
// The PatchMatch Stereo stages of one pyramid level, scalar C++, one function per
// kernel of kernels/. Every stage writes only the pixels it owns (one view, and for
// the checkerboard stages one parity) and reads nothing another pixel of the same call
// writes, so the result is the same for any number of threads.
#include <cstdint>
#include <vector>

#include "fallback/stereo/image_pyramid.h"
#include "kernels/stereo/pms_math.h"

namespace flexsight {

// Planes (a, b, c, unused) and the matching cost of each pixel's plane, for one view.
struct PlaneField {
  int width = 0;
  int height = 0;
  std::vector<float> planes;
  std::vector<float> cost;
  void resize(int w, int h);
  int pixels() const { return width * height; }
};

// What every stage of one level reads besides the planes.
struct LevelInputs {
  const ViewImage* views[2] = {nullptr, nullptr};  // PMS_VIEW_LEFT, PMS_VIEW_RIGHT
  const float* weights = nullptr;                  // support weight table
  PmsCostParams cost{};
  int ndisp = 0;                // disparity range of this level: [0, ndisp - 1]
  std::uint32_t seed = 0;
  int threads = 1;
  float max_disparity() const { return static_cast<float>(ndisp - 1); }
};

// Search settings of one level: the random search's ranges, and how much of the
// spatial and random search a confident pixel skips.
struct SearchSchedule {
  float initial_range = 0;   // disparity range of the first trial
  float normal_range = 0;    // normal range of the first trial
  float min_range = 0;       // trials continue while the range is at least this
  float confident_threshold = 2;  // confidence at or above which a pixel is confident
  float confident_max_range = 0;  // confident pixels skip trials with a larger range
  // confident pixels try only this many spatial candidates (pms_spatial_candidate_tried)
  int confident_spatial_candidates = PMS_SPATIAL_CANDIDATES;
  // Confident pixels sit the stage out and keep their planes; only the unsure ones
  // search (the finest level's refill iteration, StereoParams::refill_unsure_only).
  bool unsure_only = false;
};

// Random planes for every pixel of `view`, then their costs.
void init_random_planes(const LevelInputs& in, int view, std::uint32_t iteration,
                        PlaneField& field);

// Costs of the planes already in `field` (after carrying them from a coarser level, or
// after the filling changed some). Pixels where `unchanged` (may be null) is nonzero keep
// their cost: their plane is the one it was computed for, and a stored cost is always
// its plane's full cost (a winning candidate never reaches its bound).
void evaluate_costs(const LevelInputs& in, int view, PlaneField& field,
                    const std::vector<std::uint8_t>* unchanged = nullptr);

// Pixels of `parity` ((x + y) % 2) try the planes of their PMS_SPATIAL_CANDIDATES
// neighbours of the other parity, confident ones only the schedule's nearest.
// `confidence` (may be null: no pixel is confident) is per pixel of this level.
void propagate_spatial(const LevelInputs& in, int view, int parity,
                       const SearchSchedule& schedule, const std::vector<float>* confidence,
                       PlaneField& field);

// Pixels of `parity` try the plane of the pixel they match in the other view.
// `confidence` (may be null) matters only with schedule.unsure_only.
void propagate_view(const LevelInputs& in, int view, int parity, const SearchSchedule& schedule,
                    const std::vector<float>* confidence, const PlaneField& other,
                    PlaneField& field);

// Pixels of `parity` try random perturbations of their plane with halving ranges.
// `confidence` (may be null) is per pixel of this level.
void refine_random(const LevelInputs& in, int view, int parity, std::uint32_t iteration,
                   const SearchSchedule& schedule, const std::vector<float>* confidence,
                   PlaneField& field);

// Planes of the next finer level: pixel (x, y) takes coarse pixel (x / 2, y / 2).
// `fine` must already have its size; costs are left for evaluate_costs.
void carry_planes_to_finer(const PlaneField& coarse, PlaneField& fine);

// d = a x + b y + c at every pixel.
std::vector<float> plane_disparities(const PlaneField& field, int threads);

// C(p) = 1 / (1 + |d(p) - d_other(p')|) for every pixel of `view`.
std::vector<float> lr_confidence(const std::vector<float>& disparity,
                                 const std::vector<float>& other_disparity, int width,
                                 int height, int view, int threads);

// Confidence of the next finer level: pixel (x, y) takes coarse pixel (x / 2, y / 2).
std::vector<float> upsample_nearest(const std::vector<float>& coarse, int coarse_width,
                                    int coarse_height, int fine_width, int fine_height);

}  // namespace flexsight

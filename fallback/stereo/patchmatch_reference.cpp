#include "fallback/stereo/patchmatch_reference.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "kernels/stereo/postprocess_math.h"

namespace flexsight {
namespace {

constexpr float kNoBound = std::numeric_limits<float>::max();

float view_direction(int view) { return view == PMS_VIEW_LEFT ? -1.0f : 1.0f; }

// Cost of plane `abc` at (x, y) of `view`, abandoned once it reaches `bound`.
float plane_cost(const LevelInputs& in, int view, int x, int y, const float* abc, float bound) {
  const ViewImage& ref = *in.views[view];
  const ViewImage& other = *in.views[1 - view];
  return pms_plane_cost(ref.color.data(), ref.gradient.data(), other.color.data(),
                        other.gradient.data(), in.weights, ref.width, ref.height, in.cost, x, y,
                        abc[0], abc[1], abc[2], view_direction(view), bound);
}

// Runs `update(x, y)` on every pixel of `parity` (or every pixel for parity < 0), rows
// spread over threads. Determinism comes from the stages, not from this loop.
template <typename Update>
void for_each_pixel(int width, int height, int parity, int threads, const Update& update) {
#pragma omp parallel for schedule(dynamic, 2) num_threads(threads)
  for (int y = 0; y < height; ++y) {
    int x_begin = parity < 0 ? 0 : (y + parity) % 2;
    int x_step = parity < 0 ? 1 : 2;
    for (int x = x_begin; x < width; x += x_step) update(x, y);
  }
}

// Whether the pixel at `index` is confident under `schedule` (never without a confidence).
bool is_confident(const SearchSchedule& schedule, const std::vector<float>* confidence,
                  int index) {
  return confidence && pms_is_confident((*confidence)[index], schedule.confident_threshold);
}

// The best plane found so far for one pixel while a stage tries candidates.
struct BestPlane {
  float abc[3];
  float cost;
  bool changed = false;

  BestPlane(const PlaneField& field, int index) : cost(field.cost[index]) {
    std::memcpy(abc, &field.planes[4 * static_cast<size_t>(index)], sizeof abc);
  }
  bool same_as(const float* candidate) const {
    return std::memcmp(abc, candidate, sizeof abc) == 0;
  }
  void offer(const float* candidate, float candidate_cost) {
    if (candidate_cost < cost) {
      std::memcpy(abc, candidate, sizeof abc);
      cost = candidate_cost;
      changed = true;
    }
  }
  void store(PlaneField& field, int index) const {
    if (!changed) return;
    std::memcpy(&field.planes[4 * static_cast<size_t>(index)], abc, sizeof abc);
    field.cost[index] = cost;
  }
};

}  // namespace

void PlaneField::resize(int w, int h) {
  width = w;
  height = h;
  planes.assign(4 * static_cast<size_t>(w) * h, 0.0f);
  cost.assign(static_cast<size_t>(w) * h, 0.0f);
}

void init_random_planes(const LevelInputs& in, int view, std::uint32_t iteration,
                        PlaneField& field) {
  const ViewImage& image = *in.views[view];
  field.resize(image.width, image.height);
  for_each_pixel(field.width, field.height, -1, in.threads, [&](int x, int y) {
    int index = y * field.width + x;
    float* abc = &field.planes[4 * static_cast<size_t>(index)];
    pms_random_plane(in.seed, view, index, iteration, x, y, in.max_disparity(), abc);
    field.cost[index] = plane_cost(in, view, x, y, abc, kNoBound);
  });
}

void evaluate_costs(const LevelInputs& in, int view, PlaneField& field,
                    const std::vector<std::uint8_t>* unchanged) {
  for_each_pixel(field.width, field.height, -1, in.threads, [&](int x, int y) {
    int index = y * field.width + x;
    if (unchanged && (*unchanged)[index]) return;
    field.cost[index] = plane_cost(in, view, x, y, &field.planes[4 * static_cast<size_t>(index)],
                                   kNoBound);
  });
}

void propagate_spatial(const LevelInputs& in, int view, int parity,
                       const SearchSchedule& schedule, const std::vector<float>* confidence,
                       PlaneField& field) {
  for_each_pixel(field.width, field.height, parity, in.threads, [&](int x, int y) {
    int index = y * field.width + x;
    bool confident = is_confident(schedule, confidence, index);
    if (confident && schedule.unsure_only) return;
    BestPlane best(field, index);
    for (int candidate = 0; candidate < PMS_SPATIAL_CANDIDATES; ++candidate) {
      if (!pms_spatial_candidate_tried(candidate, confident,
                                       schedule.confident_spatial_candidates)) {
        continue;
      }
      int dx = 0;
      int dy = 0;
      pms_spatial_offset(candidate, &dx, &dy);
      int nx = x + dx;
      int ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= field.width || ny >= field.height) continue;
      const float* neighbour = &field.planes[4 * (static_cast<size_t>(ny) * field.width + nx)];
      if (best.same_as(neighbour)) continue;  // its cost here is the one we hold
      best.offer(neighbour, plane_cost(in, view, x, y, neighbour, best.cost));
    }
    best.store(field, index);
  });
}

void propagate_view(const LevelInputs& in, int view, int parity, const SearchSchedule& schedule,
                    const std::vector<float>* confidence, const PlaneField& other,
                    PlaneField& field) {
  const float direction = view_direction(view);
  for_each_pixel(field.width, field.height, parity, in.threads, [&](int x, int y) {
    int index = y * field.width + x;
    if (schedule.unsure_only && is_confident(schedule, confidence, index)) return;
    BestPlane best(field, index);
    float d = pms_plane_disparity(best.abc[0], best.abc[1], best.abc[2], static_cast<float>(x),
                                  static_cast<float>(y));
    float match_x = pms_floor_round(static_cast<float>(x) + direction * d);
    if (match_x < 0.0f || match_x > static_cast<float>(field.width - 1)) return;
    const float* source =
        &other.planes[4 * (static_cast<size_t>(y) * field.width + static_cast<int>(match_x))];
    float candidate[3];
    if (!pms_transfer_plane(source, 1 - view, candidate)) return;
    if (best.same_as(candidate)) return;
    best.offer(candidate, plane_cost(in, view, x, y, candidate, best.cost));
    best.store(field, index);
  });
}

void refine_random(const LevelInputs& in, int view, int parity, std::uint32_t iteration,
                   const SearchSchedule& schedule, const std::vector<float>* confidence,
                   PlaneField& field) {
  const int trials = pms_search_trial_count(schedule.initial_range, schedule.min_range);
  // The trials a confident pixel skips: the first ones, whose range exceeds
  // confident_max_range (the OpenCL path launches them for the unsure pixels only).
  const int wide =
      pms_search_wide_trial_count(schedule.initial_range, trials, schedule.confident_max_range);
  for_each_pixel(field.width, field.height, parity, in.threads, [&](int x, int y) {
    int index = y * field.width + x;
    bool confident = is_confident(schedule, confidence, index);
    if (confident && schedule.unsure_only) return;
    BestPlane best(field, index);
    float range = schedule.initial_range;
    float normal_range = schedule.normal_range;
    for (int trial = 0; trial < trials; ++trial, range *= 0.5f, normal_range *= 0.5f) {
      if (confident && trial < wide) continue;
      float u[4];
      for (int c = 0; c < 4; ++c) {
        u[c] = pms_random_unit(in.seed, view, index, iteration, pms_search_trial_key(trial, c));
      }
      float candidate[3];
      if (!pms_perturb_plane(best.abc, x, y, in.max_disparity(), range, normal_range, u[0], u[1],
                             u[2], u[3], candidate)) {
        continue;
      }
      best.offer(candidate, plane_cost(in, view, x, y, candidate, best.cost));
    }
    best.store(field, index);
  });
}

void carry_planes_to_finer(const PlaneField& coarse, PlaneField& fine) {
  for (int y = 0; y < fine.height; ++y) {
    for (int x = 0; x < fine.width; ++x) {
      const size_t source = pms_coarse_pixel(x, y, coarse.width, coarse.height);
      pms_carry_plane_to_finer(&coarse.planes[4 * source],
                               &fine.planes[4 * (static_cast<size_t>(y) * fine.width + x)]);
    }
  }
}

std::vector<float> plane_disparities(const PlaneField& field, int threads) {
  std::vector<float> disparity(field.pixels());
  for_each_pixel(field.width, field.height, -1, threads, [&](int x, int y) {
    int index = y * field.width + x;
    const float* abc = &field.planes[4 * static_cast<size_t>(index)];
    disparity[index] = pms_plane_disparity(abc[0], abc[1], abc[2], static_cast<float>(x),
                                           static_cast<float>(y));
  });
  return disparity;
}

std::vector<float> lr_confidence(const std::vector<float>& disparity,
                                 const std::vector<float>& other_disparity, int width,
                                 int height, int view, int threads) {
  std::vector<float> confidence(disparity.size());
  for_each_pixel(width, height, -1, threads, [&](int x, int y) {
    confidence[y * width + x] = pms_confidence(disparity.data(), other_disparity.data(), width,
                                               x, y, view_direction(view));
  });
  return confidence;
}

std::vector<float> upsample_nearest(const std::vector<float>& coarse, int coarse_width,
                                    int coarse_height, int fine_width, int fine_height) {
  std::vector<float> fine(static_cast<size_t>(fine_width) * fine_height);
  for (int y = 0; y < fine_height; ++y) {
    for (int x = 0; x < fine_width; ++x) {
      fine[y * fine_width + x] = coarse[pms_coarse_pixel(x, y, coarse_width, coarse_height)];
    }
  }
  return fine;
}

}  // namespace flexsight

#pragma once
// Every parameter of the PatchMatch Stereo matcher, with its default and why.
// The CLI exposes each field as --kebab-case-name; check() rejects impossible values.
#include <cmath>
#include <cstdint>
#include <string>

namespace flexsight {

enum class StereoMethod { PPMS, PMS };

struct StereoParams {
  // Pyramidal PatchMatch (default) or flat PatchMatch on the full resolution only.
  StereoMethod method = StereoMethod::PPMS;
  // Disparity search range: disparities lie in [0, ndisp - 1] at the finest level.
  int ndisp = 64;
  // Side of the square support window in pixels (odd).
  int window = 35;
  // Only every step-th row and column of the window is summed; 2 keeps accuracy and
  // divides the cost of a matching evaluation by four.
  int window_step = 2;
  // PPMS: the window step on every level below the coarsest, whose planes come carried
  // from the level above and only need refining; the coarsest level (which starts from
  // random planes) and flat PMS use window_step. Those levels take about 90 % of the
  // time; a step of 4 samples 81 window pixels (step 3: 121, step 2: 289). 15 MiddEval3
  // Q scenes, OpenCL, bad-2 all, with the 16 spatial candidates of pms_spatial_offset:
  // step 4 11.58 / 11.58 / 11.62 % with seeds 1 / 2 / 3 in 0.7x the time of step 3,
  // which gives 11.40 % (seed 1). The wider spatial candidates buy back more than the
  // coarser window costs: with the old 8 candidates step 4 gave 12.23 % against 11.93
  // for step 3.
  int window_step_fine = 4;
  // PPMS: the finest level's window step and iterations, where they differ from the
  // levels above (0 = window_step_fine, iterations_fine). The finest level takes about
  // three quarters of the time, so these are the knobs for speed. 15 MiddEval3 Q
  // scenes, OpenCL, bad-2 all, seed 1, mean time per scene on a slow hour (defaults
  // 10.92 % in 16.3 s): step 5 11.14 % in 11.4 s (0.70x), 1 iteration 11.16 % in 12.8 s
  // (0.78x), both 11.20 % in 8.85 s (0.54x); for comparison --iterations-fine 1
  // --refill-iterations 0 12.24 % in 7.1 s.
  int window_step_finest = 0;
  int iterations_finest = 0;
  // Weight of the gradient term against the colour term in the matching cost.
  float alpha = 0.9f;
  // Truncation of the colour (L1 over RGB) and gradient dissimilarities.
  float tau_color = 10.0f;
  float tau_gradient = 2.0f;
  // Weight of a 5x5 census Hamming distance (0..24 bits) added to each window pixel's
  // dissimilarity (kernels/stereo/pms_math.h). The census only sees which neighbours are darker,
  // so it survives the exposure and lighting changes between the two cameras (MiddEval3's
  // PianoL, MotorcycleE) and the faint texture of walls that colour differences truncated
  // at tau_color drown in. An addition to Bleyer et al.'s cost; 0 gives theirs exactly.
  float census_weight = 4.0f;
  // The census distance counts at most this many of its 24 bits, so that a window pixel
  // that has no true match under the plane (occluded in the other view, or on another
  // surface) costs a bounded amount, as the colour and gradient terms are truncated at
  // tau_color and tau_gradient. 15 MiddEval3 Q scenes, OpenCL, bad-2 all, seeds 1-5:
  // 24 (no cap) 10.95 / 11.10 / 11.21 / 11.13 / 11.07 % (mean 11.09), 10 bits 10.93 /
  // 10.83 / 10.92 / 10.96 / 10.91 (mean 10.91; nonocc 7.25 -> 7.10, Motorcycle 6.52 ->
  // 6.40 on average); with seeds 1 / 2 only, 8 bits 10.87 / 11.10, 16 bits 11.18 /
  // 11.12 (on Motorcycle alone 4-20 bits gave 6.32-6.73 %).
  float census_cap = 10.0f;
  // Adaptive support weight exp(-|I_p - I_q|_1 / gamma) exp(-|q - p| / gamma_distance)
  // (Yoon and Kweon 2006; Bleyer et al. keep the colour factor only: gamma_distance
  // inf). Window pixels far from the centre more often lie on another surface of a
  // similar colour, so they count less. 15 MiddEval3 Q scenes, OpenCL, bad-2 all, seeds
  // 1 / 2 / 3 / 4: inf 12.09 / 12.18 / 11.96 / 12.12 %, 30 px 12.01 / 11.98 / 11.94 /
  // 12.09, 20 px 11.93 / 11.95 / 12.14 / 11.93 (seed 1: 50 px 12.15, 17.5 px 12.01).
  float gamma = 10.0f;
  float gamma_distance = 20.0f;
  // PatchMatch iterations (each: both views, both checkerboard parities) of flat PMS, on
  // its only level (Bleyer et al. use 3).
  int iterations = 3;
  // PPMS: iterations on the coarsest level (at most coarsest_width pixels wide, so they
  // cost little). 15 MiddEval3 Q scenes, bad-2 all, seeds 1 / 2: 3 iterations 12.28 /
  // 12.19 %, 5 iterations 12.17 / 12.21 %: within the seed-to-seed spread, so 3 stays.
  int iterations_coarsest = 3;
  // PPMS: iterations on the levels below the coarsest, which start from a good guess.
  // More is not better: 1, 2 and 3 gave 13.34, 12.28 and 12.52 % (a third iteration
  // lets textureless areas drift away from the coarse answer). With the 16 spatial
  // candidates (15 MiddEval3 Q scenes, OpenCL, bad-2 all, seed 1): 1, 2 and 3 give
  // 11.77, 11.58 and 12.00 % in 0.52x, 1x and 1.3x the time; 1 with window_step_fine 3
  // 11.59 / 11.77 / 11.70 % (seeds 1 / 2 / 3, against 11.58 / 11.58 / 11.62) in 0.72x.
  int iterations_fine = 2;
  // Random search: trial k perturbs the disparity by up to (ndisp_level / 2) / 2^k;
  // trials continue while that range is at least min_search_range pixels.
  float min_search_range = 0.25f;
  // PPMS: on the levels below the coarsest the random search starts at this range
  // (pixels of that level) instead of half the disparity range: the carried planes are
  // already close. 15 MiddEval3 Q scenes, bad-2 all: 4 px 12.62 %, 8 px 12.35, 16 px
  // 12.28, 32 px 12.36: too narrow cannot undo the coarse level's mistakes, too wide lets
  // textureless areas drift.
  float fine_search_range = 16.0f;
  // PPMS: where the coarser level's confidence C = 1/(1+|dL-dR|) reaches
  // confident_threshold, trials with a range above confident_max_range are skipped,
  // since the carried plane is already within a pixel or two of the answer. 15 MiddEval3
  // Q scenes, OpenCL, bad-2 all, seeds 1 / 2 (confident_spatial_candidates 8, no
  // refresh): 2 px 11.60 / 11.70 %, 1 px 11.53 / 11.65 %; with refresh_confidence, see
  // there.
  float confident_threshold = 0.5f;
  float confident_max_range = 1.0f;
  // PPMS: confident pixels try only this many of the spatial candidates, nearest first
  // (pms_spatial_offset: 4 per ring at 1, 5, 15 and 45 px; 16 = all). The far rings
  // exist to carry planes into areas whose planes are wrong, and a confident pixel's is
  // not. 15 MiddEval3 Q scenes, OpenCL, bad-2 all (seed 1; time of the whole eval):
  // 16 11.58 % (seeds 2 / 3: 11.58 / 11.62) in 113 s, 12 11.60 in 111 s, 8 11.60
  // (seeds 2 / 3: 11.70 / 11.59) in 94 s, 4 11.78 in 85 s, 0 13.85 in 84 s.
  int confident_spatial_candidates = 8;
  // PPMS: below the coarsest level, after every iteration but the last, the confidence
  // is recomputed from the level's own planes (the same left/right rule), so that the
  // next iteration spends its far candidates and wide trials on the pixels that are still
  // inconsistent, not on those the carried confidence doubted. 15 MiddEval3 Q
  // scenes, OpenCL, bad-2 all, seed 1: off 11.60 % (confident_max_range 2) / 11.53 (1 px),
  // on 11.53 / 11.44; with 1 px, seeds 2 / 3: off 11.65 / -, on 11.56 / 11.58. Motorcycle
  // on PoCL: 6.7 s either way (refine_random 1.81 -> 1.65 s, the spatial propagation
  // unchanged: about as many pixels are confident after an iteration as before it).
  bool refresh_confidence = true;
  // On the finest level, after its iterations: the pixels of both views that fail the
  // left/right check take the background plane (as with fill_coarse), and this many more
  // iterations run, steered by that check (the confidence rules above). The filled
  // planes offer the background to their neighbours, and visible pixels among the filled
  // ones can win their own surface back; the post-processing then checks again. A third
  // plain iteration does not do this: textureless areas drift. 15 MiddEval3 Q scenes,
  // OpenCL, bad-2 all, seed 1: 0 11.14 %, 1 10.96 % (Motorcycle 6.67 -> 6.49); one
  // iteration of the unsure pixels only 11.03, one with all 16 candidates for every
  // pixel 10.96 (6.45); the check-and-fill between the two iterations instead of after
  // them 6.65 on Motorcycle; the extra iteration without the fill 6.69; 2 iterations
  // 11.23 % (6.65).
  int refill_iterations = 1;
  // Only the pixels that fail that check (confidence below confident_threshold) search in
  // those iterations; the others keep their planes (false: every pixel, steered by the
  // check). The failed pixels are what the iteration is for; the consistent ones,
  // about 83 % of Motorcycle's, were mostly polishing their planes there, a sub-pixel
  // gain bad-2 does not see. 15 MiddEval3 Q scenes, OpenCL, bad-2 all / nonocc, seconds
  // per scene (PoCL, 2 cores): seed 1 every pixel 10.92 / 7.11 %, unsure only 10.95 /
  // 7.12 %; seed 2 11.05 / 7.28 % in 8.56 s, unsure only 11.10 / 7.26 % in 7.36 s
  // (0.86x); Motorcycle 6.52 -> 6.48 % (seed 2: 6.61 -> 6.54).
  bool refill_unsure_only = true;
  // Largest normal perturbation per component at the first trial (then halved).
  float max_normal_delta = 1.0f;
  // PPMS: the coarsest level is the first whose width is at most this.
  int coarsest_width = 128;
  // PPMS: each coarser level's planes go through the left/right check and the background
  // filling before they are carried, so that the finer level starts its occluded pixels
  // from the background plane instead of whatever PatchMatch left there.
  bool fill_coarse = true;
  // Left/right check tolerance in pixels.
  float lr_tolerance = 1.0f;
  // A pixel that fails the check takes its background neighbour's plane, but its
  // disparity stays within this many pixels of the neighbour's own (pms_fill_disparity):
  // a slope fitted to one window, carried across a wide hole, drifts off the background.
  // 15 MiddEval3 Q scenes, bad-2 all, seeds 1 / 2: no limit (Bleyer et al.) 12.28 /
  // 12.19 %, 2 px 12.12 / 11.98 %, 4 px 12.12 / 11.96 %; 1 px 12.28 (seed 1): 2 to 4 px
  // is a plateau. With 2 px, 12 of 15 scenes gain with both seeds (ArtL -1.1, PianoL
  // -0.1 / -1.2, Playroom -1.0 / -0.8); Piano (+0.6) and Vintage (+0.2) lose.
  // 2026-12-02, with the census cap (OpenCL, seeds 1 / 2 / 3): 2 px 10.93 / 10.83 /
  // 10.92 %, 3 px 10.75 / 10.78 / 10.84, 4 px 10.79 / 10.68 / 10.75 (mean 10.74 against
  // 10.89, better with every seed), 6 px 10.91 (seed 1); 4 px gains most on the hard
  // scenes (seed 1: PianoL -1.0, Piano -0.8, Jadeplant -0.4, Shelves -0.4) and loses on
  // Pipes (+0.5); Motorcycle 6.26 -> 6.34 / 6.47 / 6.39 % (3 px: 6.23 / 6.43 / 6.36).
  float fill_max_extrapolation = 4.0f;
  // Weighted median filter window (odd) and colour bandwidth for filled pixels.
  int median_window = 35;
  float median_gamma = 10.0f;
  // In that median only disparities at most this many pixels above the pixel's filled
  // (background) disparity vote: a hole left by the check is mostly occlusion, which
  // belongs to the background, and the foreground beside it must not bleed in. On the 15
  // MiddEval3 Q scenes, bad-2 all: no limit 12.90 %, 0.5 px 12.46, 1 px 12.39, 2 px
  // 12.35, 4 px 12.42.
  float median_background_margin = 2.0f;
  // Then a weighted median over every pixel (window odd, 1 = off): it removes the
  // isolated wrong planes PatchMatch leaves. A wide colour bandwidth, because at this
  // size the window rarely straddles an edge that colour alone would reveal.
  int final_median_window = 7;
  float final_median_gamma = 40.0f;
  // Last, segments of fewer than speckle_size pixels (4-neighbours joined when their
  // disparities differ by at most speckle_range; OpenCV's filterSpeckles has the same
  // two) are refilled as if they had failed the left/right check: background filling
  // from the pixels outside them, then the hole median (0 = off). PatchMatch leaves such
  // islands where one wrong plane spread over a few dozen pixels, too many for the 7x7
  // median. 15 MiddEval3 Q scenes, OpenCL, bad-2 all, seed 1 (off: 11.44 %): 50 / 100 /
  // 200 px 11.32 / 11.32 / 11.35 % (prototyped: 400 / 1000 px 11.55 / 12.18, where real
  // thin structures go); with 100 px, a range of 0.5 / 2 px 11.39 / 11.38 %.
  int speckle_size = 100;
  float speckle_range = 1.0f;
  // Before the filling, segments of the finest level's raw left disparities smaller
  // than raw_speckle_size pixels (the same joining rule, speckle_range) count as failing
  // the left/right check (0 = off): a plane that won at one pixel and a few around it
  // against every neighbour is more often wrong than right, and the right view can be
  // wrong the same way. 15 MiddEval3 Q scenes, OpenCL, bad-2 all, seed 1 (off: 11.32 %):
  // 4 / 8 / 15 / 20 / 30 / 50 / 100 px 11.26 / 11.17 / 11.11 / 11.14 / 11.17 / 11.20 /
  // 11.46 %: 20, inside the plateau.
  int raw_speckle_size = 20;
  // Random generator key: same seed, same bytes.
  std::uint32_t seed = 1;
  // Worker threads for the reference path (0 = all cores). Never changes the result.
  int threads = 0;

  // Throws InputError (subject "parameter <name>") for an impossible value.
  void check() const;
};

const char* method_name(StereoMethod method);

// Named settings of the knobs that trade accuracy for speed (the window steps and the
// iterations below the coarsest level); every other field keeps its value. "accurate"
// is the defaults above. "fast" samples the windows more sparsely and runs one iteration
// per finer level, about 3x faster for 0.6-0.7 points of bad-2 (15 MiddEval3 Q scenes,
// 11.57 % on average over seeds 1-3 against 10.89; figures at fast_preset() in
// stereo_params.cpp). Returns false for an unknown name.
bool apply_stereo_preset(const std::string& name, StereoParams& params);

// "accurate, fast": for messages and --help.
const char* stereo_preset_names();

}  // namespace flexsight

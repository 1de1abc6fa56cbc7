#pragma once
// Every parameter of the PatchMatch Stereo matcher, with its default and why.
// The CLI exposes each field as --kebab-case-name; check() rejects impossible values.
// Figures are bad-2 over all pixels on the 15 MiddEval3 training scenes at quarter
// resolution (either path: both give the same bytes); the sweeps behind each default
// are in docs/tuning-log.md.
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
  // Rows of the support window (odd; 0 = window, square): a window wider than tall
  // sums more of a surface that slopes along the rows. Figures: docs/stereo.md, item 3.
  int window_rows = 0;
  // Only every step-th row and column of the window is summed; 2 keeps accuracy and
  // divides the cost of a matching evaluation by four.
  int window_step = 2;
  // PPMS: the window step on every level below the coarsest, whose planes come carried
  // from the level above and only need refining; the coarsest level (which starts from
  // random planes) and flat PMS use window_step. Those levels take about 90 % of the
  // time, and a step of 4 samples 81 window pixels (step 3: 121, step 2: 289): with the
  // far spatial candidates of pms_spatial_offset, which make up for the sparser window,
  // step 4 costs about 0.2 points against step 3 in 0.7x the time.
  int window_step_fine = 4;
  // PPMS: the finest level's window step and iterations, where they differ from the
  // levels above (0 = window_step_fine, iterations_fine). The finest level takes about
  // three quarters of the time, so these are the knobs for speed (the fast preset sets
  // them). By default the finest level runs as the levels above, the accurate end: one
  // iteration there instead of two costs about 0.2 points for 0.8x the time.
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
  // tau_color and tau_gradient. 10 bits: 10.91 % against 11.09 % with no cap (mean of
  // seeds 1-5); 8 and 16 bits did no better.
  float census_cap = 10.0f;
  // The census's neighbourhood (pms_census_pixel): census_rows x census_cols (odd), its
  // centre row census_row_length long (odd, >= census_cols), at most 24 bits in all.
  // 5x5 by default. A surface that slopes along the rows (a bin's top and bottom walls,
  // 2-3 px of disparity a row) shears the rows above and below the centre between the
  // views; the centre row alone (1x25) does not. Figures: docs/stereo.md, item 3.
  int census_rows = 5;
  int census_cols = 5;
  int census_row_length = 5;
  // Adaptive support weight exp(-|I_p - I_q|_1 / gamma) exp(-|q - p| / gamma_distance)
  // (Yoon and Kweon 2006; Bleyer et al. keep the colour factor only: gamma_distance
  // inf). Window pixels far from the centre more often lie on another surface of a
  // similar colour, so they count less: 20 px gains about 0.1 point over colour-only
  // weights (mean of seeds 1-4); 30 and 50 px gain less. gamma is Bleyer et al.'s.
  float gamma = 10.0f;
  float gamma_distance = 20.0f;
  // PatchMatch iterations (each: both views, both checkerboard parities) of flat PMS, on
  // its only level (Bleyer et al. use 3).
  int iterations = 3;
  // PPMS: iterations on the coarsest level (at most coarsest_width pixels wide, so they
  // cost little). Bleyer et al.'s 3: 5 iterations gain nothing beyond the seed-to-seed
  // spread.
  int iterations_coarsest = 3;
  // PPMS: iterations on the levels below the coarsest, which start from a good guess.
  // More is not better: 2 is the best of 1, 2 and 3, and a third iteration costs about
  // 0.4 points, because it lets textureless areas drift away from the coarse answer.
  int iterations_fine = 2;
  // Random search: trial k perturbs the disparity by up to (ndisp_level / 2) / 2^k;
  // trials continue while that range is at least min_search_range pixels.
  float min_search_range = 0.25f;
  // PPMS: on the levels below the coarsest the random search starts at this range
  // (pixels of that level) instead of half the disparity range: the carried planes are
  // already close. Too narrow a range cannot undo the coarse level's mistakes and too
  // wide a one lets textureless areas drift; 16 px was the best of 4, 8, 16 and 32 px.
  float fine_search_range = 16.0f;
  // PPMS: where the coarser level's confidence C = 1/(1+|dL-dR|) reaches
  // confident_threshold, trials with a range above confident_max_range are skipped,
  // since the carried plane is already within a pixel or two of the answer. The
  // threshold 0.5 is C at a disagreement of 1 px, the left/right check's tolerance; a
  // 1-px range does slightly better than 2 px (about 0.06 points over two seeds).
  float confident_threshold = 0.5f;
  float confident_max_range = 1.0f;
  // PPMS: confident pixels try only this many of the spatial candidates, nearest first
  // (pms_spatial_offset: 4 per ring at 1, 5, 15 and 45 px; 16 = all). The far rings
  // exist to carry planes into areas whose planes are wrong, and a confident pixel's is
  // not: the two near rings cost about 0.04 points against all 16 (mean of three seeds)
  // in 0.83x the time.
  int confident_spatial_candidates = 8;
  // PPMS: below the coarsest level, after every iteration but the last, the confidence
  // is recomputed from the level's own planes (the same left/right rule), so that the
  // next iteration spends its far candidates and wide trials on the pixels that are still
  // inconsistent, not on those the carried confidence doubted. It gains about
  // 0.1 point at no cost in time: about as many pixels are confident after an iteration
  // as before it.
  bool refresh_confidence = true;
  // On the finest level, after its iterations: the pixels of both views that fail the
  // left/right check take the background plane (as with fill_coarse), and this many more
  // iterations run, steered by that check (the confidence rules above). The filled
  // planes offer the background to their neighbours, and visible pixels among the filled
  // ones can win their own surface back; the post-processing then checks again. A third
  // plain iteration does not do this: textureless areas drift. One iteration takes about
  // 0.2 points off; a second costs more than the first gains.
  int refill_iterations = 1;
  // Only the pixels that fail that check (confidence below confident_threshold) search in
  // those iterations; the others keep their planes (false: every pixel, steered by
  // the check). The failed pixels are what the iteration is for; the consistent ones,
  // about 83 % of Motorcycle's, would mostly polish their planes there, a sub-pixel
  // gain bad-2 does not see: 0.86x the time for at most 0.05 points.
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
  // a slope fitted to one window, carried across a wide hole, drifts off the background
  // (infinity gives Bleyer et al.'s unlimited extrapolation, which did worse than 2 or
  // 4 px). 4 px: 10.74 % against 10.89 % with 2 px (mean of seeds 1-3).
  float fill_max_extrapolation = 4.0f;
  // Weighted median filter window (odd) and colour bandwidth for filled pixels.
  int median_window = 35;
  float median_gamma = 10.0f;
  // In that median only disparities at most this many pixels above the pixel's filled
  // (background) disparity vote: a hole left by the check is mostly occlusion, which
  // belongs to the background, and the foreground beside it must not bleed in. 2 px was
  // the best of 0.5 to 4 px and takes about 0.55 points off against no limit.
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
  // median. 100 px takes about 0.1 point off; from a few hundred pixels up, real thin
  // structures are refilled too.
  int speckle_size = 100;
  float speckle_range = 1.0f;
  // Both segment steps also join two neighbours whose disparity step continues the step
  // beside them to within speckle_range (pms_segment_pair_joined): on a steep surface
  // (a bin wall at a grazing angle, 2 px a row) the plain rule cuts every row into its
  // own small segment, and the refill pulls the wall down to the floor. Off by default
  // (on MiddEval3 it costs a little; docs/tuning-log.md), on in the active preset
  // (ActiveCost says why).
  bool speckle_slopes = false;
  // Before the filling, segments of the finest level's raw left disparities smaller
  // than raw_speckle_size pixels (the same joining rule, speckle_range) count as failing
  // the left/right check (0 = off): a plane that won at one pixel and a few around it
  // against every neighbour is more often wrong than right, and the right view can be
  // wrong the same way. 20 px, inside a plateau from 8 to 50 px, takes about 0.2 points
  // off.
  int raw_speckle_size = 20;
  // Before the filling, pixels whose support window (window x window) has a grey-level
  // standard deviation below this many levels count as failing the left/right check
  // (0 = off; host/stereo/texture_mask.h): where nothing is textured, a match is noise
  // that both views can agree on, and the fill carries the textured neighbours' plane
  // in instead. The active preset sets it: the table outside a projector's field.
  float textureless_spread = 0.0f;
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
// per finer level, about 3x faster for about 0.65 points of bad-2 (fast_preset() in
// stereo_params.cpp says why). "active" is for projector-lit scenes (active stereo):
// the accurate knobs, plus a 25-px window, higher truncations of the colour and gradient
// terms, a wider left/right tolerance, every consistent pixel voting in a 5x5 hole median,
// the texture gate, the flat fill and speckles that follow slopes (the only preset that
// touches those fields;
// ActiveCost in stereo_params.cpp says why). Returns false for an unknown name.
bool apply_stereo_preset(const std::string& name, StereoParams& params);

// "accurate, fast, active": for messages and --help.
const char* stereo_preset_names();

}  // namespace flexsight

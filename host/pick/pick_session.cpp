#include "host/pick/pick_session.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/geometry/depth_from_disparity.h"
#include "host/pick/ordered_posing.h"
#include "host/geometry/stereo_rig.h"
#include "host/io/input_error.h"
#include "host/pick/pick_stereo.h"
#include "host/stereo/stereo_backend.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Boxes overlapping more than this are one part (proposed as several classes).
constexpr double kDuplicateIou = 0.5;


// The boxes and classes to pose: the namer's (pick_naming.h) when there is one, else the
// detector's (pose_proposals).
std::vector<NamedProposal> proposals_to_pose(const PickResult& result, const cv::Mat& bgr, PartNamer* namer,
                                             const PickSettings& settings) {
  if (namer != nullptr) {
    return named_proposals(result.detections, *namer, bgr, settings.classes_per_box, kDuplicateIou, settings.naming_mix);
  }
  std::vector<NamedProposal> proposals;
  for (int i : pose_proposals(result.detections, settings.classes_per_box, kDuplicateIou)) {
    proposals.push_back({result.detections[i], -1.0});
  }
  return proposals;
}

PosingOptions posing_options(const PickSettings& settings, Clock::time_point pick_start) {
  PosingOptions options;
  options.mode = settings.mode;
  options.budget_seconds = settings.budget_ms / 1000.0;
  options.threads = settings.threads > 0 ? settings.threads : omp_get_max_threads();
  options.pose = settings.pose;
  options.model_option = settings.model;
  options.acceptance = settings.acceptance;
  options.depth_for_candidate = settings.depth_for_candidate;
  options.start = pick_start;
  return options;
}

// The posed parts ranked by pick_score (rank_picks) and one kept per part
// (remove_duplicate_picks); in first-pick mode the accepted part leads. The first pick:
// the accepted part, else the best-ranked.
void rank_posed(PickResult& result) {
  PosingOutcome& posing = result.posing;
  result.picks = std::move(posing.posed);
  posing.posed.clear();
  rank_picks(result.picks);
  result.proposals = result.picks;
  const int accepted = posing.first_pick >= 0 ? posing.candidates[posing.first_pick].best : -1;
  if (accepted >= 0 && result.mode == PickMode::FirstPick) {
    std::stable_partition(result.picks.begin(), result.picks.end(),
                          [&](const PickCandidate& c) { return c.proposal_index == accepted; });
  }
  remove_duplicate_picks(result.picks, kDuplicateIou);
  const auto first = std::find_if(result.proposals.begin(), result.proposals.end(),
                                  [&](const PickCandidate& c) { return c.proposal_index == accepted; });
  result.first_pick_accepted = first != result.proposals.end();
  result.has_first_pick = result.first_pick_accepted || !result.picks.empty();
  if (result.first_pick_accepted) {
    result.first_pick = *first;
  } else if (result.has_first_pick) {
    result.first_pick = result.picks.front();
  }
  result.seconds_to_first_pick = posing.seconds_to_first_pick;
}

// Known-part mode: every known part needs its templates (and so its CAD model; the
// detector class is checked by the detector). Only these are posed, so the templates
// file may hold the cell's parts alone.
void check_known_parts(const KnownParts& parts, const PoseModels& models, const PickSettings& settings) {
  for (int id : parts.obj_ids) {
    if (models.has(id)) continue;
    // Which of the two is missing, read again on this error path only.
    const bool has_cad = PartLibrary::load_folder(settings.cad).index_of(id) >= 0;
    throw InputError("option --parts", "object " + std::to_string(id) + " has no " +
                                           (has_cad ? "templates in " + settings.templates
                                                    : "CAD model in " + settings.cad));
  }
}

}  // namespace

struct PickSession::Impl {
  PickSettings settings;
  ComputeBackend compute;
  StereoBackend stereo;
  SsdDetector detector;
  std::unique_ptr<PartNamer> namer;  // before the templates: the cheaper files are checked first
  PoseModels models;
  std::vector<ProposalClass> proposal_classes;  // the detector's classes with their parts' sizes

  explicit Impl(const PickSettings& s)
      : settings(s),
        compute(s.backend),
        stereo(compute),
        detector(s.model, compute, s.detector),
        namer(s.namer.empty() ? nullptr : std::make_unique<PartNamer>(s.namer)),
        models(s.templates, s.cad) {
    if (namer) namer->require_same_parts(detector.labels(), s.model);
    const bool known_parts = !s.detector.parts.every_part();
    if (known_parts) {
      check_known_parts(s.detector.parts, models, s);
    } else {
      for (const DetectorLabel& label : detector.labels()) {
        if (!models.has(label.category_id)) {
          throw InputError(s.model, "detects object " + std::to_string(label.category_id) + " (" + label.name +
                                        "), which " + s.templates + " and " + s.cad +
                                        " do not hold: a detector for other parts than the CAD folder's");
        }
      }
    }
    // The classes a depth region may be proposed as: the known parts alone in known-part mode.
    const std::vector<DetectorLabel>& labels = detector.labels();
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (!s.detector.parts.contains(labels[i].category_id)) continue;
      proposal_classes.push_back({labels[i].category_id, static_cast<int>(i), models.mesh(labels[i].category_id).diameter});
    }
  }
};

PickSession::PickSession(const PickSettings& settings) : impl_(std::make_unique<Impl>(settings)) {}

void PickSession::set_ndisp(int ndisp) { impl_->settings.stereo.ndisp = ndisp; }

void PickSession::set_pair_settings(const PickSettings& settings) {
  check_pair_settings(settings);
  impl_->settings = settings;
}

void PickSession::check_pair_settings(const PickSettings& settings) const {
  const PickSettings& loaded = impl_->settings;
  const SsdDetectorOptions &d = settings.detector, &l = loaded.detector;
  const BackendOptions &b = settings.backend, &lb = loaded.backend;
  const std::pair<bool, const char*> fixed[] = {
      {settings.model != loaded.model, "--model"},
      {settings.templates != loaded.templates, "--templates"},
      {settings.cad != loaded.cad, "--cad"},
      {settings.namer != loaded.namer, "--namer"},
      {d.score_threshold != l.score_threshold, "--score"},
      {d.parts.obj_ids != l.parts.obj_ids, "--parts"},
      {d.iou_threshold != l.iou_threshold || d.top_k_per_class != l.top_k_per_class ||
           d.max_detections != l.max_detections || d.dnn_target != l.dnn_target,
       "--model"},
      {b.kind != lb.kind, "--device"},
      {b.cl_platform != lb.cl_platform, "--cl-platform"},
      {b.cl_device != lb.cl_device, "--cl-device"},
      {b.cl_max_memory != lb.cl_max_memory, "--cl-max-memory"},
      {b.cl_build_options != lb.cl_build_options, "--cl-build-options"},
  };
  for (const auto& [differs, option] : fixed) {
    if (differs) throw InputError(std::string("option ") + option, "is loaded once for the session and cannot change per pair");
  }
}

void PickSession::set_pick_mode(PickMode mode, int budget_ms) {
  impl_->settings.mode = mode;
  impl_->settings.budget_ms = budget_ms;
}

cv::Mat PickSession::disparity(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8) {
  return disparity_at_scale(impl_->stereo, left_rgb8, right_rgb8, impl_->settings.stereo,
                            impl_->settings.stereo_downscale, ProgressCallback(), nullptr);
}

TilingPlan PickSession::detection_tiling(cv::Size image, const PinholeCamera& camera, const cv::Mat& depth_mm) const {
  const PickSettings& settings = impl_->settings;
  if (settings.detection_tile == 0) return {};
  if (settings.detection_tile > 0) return fixed_tiling(settings.detection_tile);
  // A part's size in pixels: f x diameter / depth, at the median measured depth (the
  // bin's floor and the parts on it).
  std::vector<float> depths;
  depths.reserve(depth_mm.total());
  for (auto it = depth_mm.begin<float>(); it != depth_mm.end<float>(); ++it) {
    if (*it > 0.0f) depths.push_back(*it);
  }
  if (depths.empty()) return {};
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const double depth = depths[depths.size() / 2];
  std::vector<double> diameters;
  for (const DetectorLabel& label : impl_->detector.labels()) {
    if (settings.detector.parts.contains(label.category_id)) {
      diameters.push_back(impl_->models.mesh(label.category_id).diameter);
    }
  }
  std::sort(diameters.begin(), diameters.end());
  const double focal = camera.fx;
  return tiling_for_part_sizes(image, focal * diameters[diameters.size() / 2] / depth,
                               focal * diameters.back() / depth);
}
PickSession::~PickSession() = default;
const PoseModels& PickSession::models() const { return impl_->models; }
const SsdDetector& PickSession::detector() const { return impl_->detector; }

PickResult PickSession::pick(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8, const StereoCamera& rig,
                              const cv::Mat& texture_left_rgb8) {
  const PickSettings& settings = impl_->settings;
  PickResult result;
  result.camera = stereo_rig_from(rig, left_rgb8.cols, left_rgb8.rows).left;

  const Clock::time_point pick_start = Clock::now();
  auto start = pick_start;
  ProgressCallback progress;
  if (!settings.quiet) progress = [](const std::string& stage) { std::cerr << "  stereo: " << stage << "\n"; };
  PickDisparity matched = pick_disparity(impl_->stereo, left_rgb8, right_rgb8, rig, settings.stereo,
                                         settings.stereo_plan, settings.stereo_downscale, progress, &result.stereo_path);
  result.disparity = std::move(matched.disparity);
  result.bin_region = matched.region;
  result.stereo_plan = settings.stereo_plan;
  result.stereo_downscale = settings.stereo_downscale;
  result.seconds.stereo = seconds_since(start);

  start = Clock::now();
  result.depth_mm = depth_from_disparity(result.disparity, rig, 1e-3, DepthRule::pick());
  result.floor_depth_mm = floor_depth_mm(result.depth_mm);
  result.seconds.depth = seconds_since(start);

  start = Clock::now();
  if (!texture_left_rgb8.empty() && texture_left_rgb8.size() != left_rgb8.size()) {
    throw InputError("pick", "the image without the pattern is not the pair's size");
  }
  cv::Mat bgr;
  cv::cvtColor(texture_left_rgb8.empty() ? left_rgb8 : texture_left_rgb8, bgr, cv::COLOR_RGB2BGR);
  result.detection_tiling = detection_tiling(bgr.size(), result.camera, result.depth_mm);
  // Parts lie in the bin: outside it tiles would only find the table and the walls' tops.
  if (settings.detect_in_bin && result.bin_region.found) result.detection_tiling.region = result.bin_region.rect;
  result.detections = detect_in_tiles([&](const cv::Mat& tile) { return impl_->detector.detect(tile); }, bgr,
                                      result.detection_tiling, settings.detector.iou_threshold);
  result.detector_path = impl_->detector.planned();
  result.seconds.detection = seconds_since(start);

  start = Clock::now();
  std::vector<NamedProposal> proposals = proposals_to_pose(result, bgr, impl_->namer.get(), settings);
  if (impl_->namer) result.namer_path = impl_->namer->model_path();
  result.seconds.naming = seconds_since(start);

  // The parts the depth shows that no network box matches, proposed too.
  if (settings.depth_proposals) {
    start = Clock::now();
    result.depth = propose_from_depth(result.depth_mm, result.camera, result.detections, impl_->proposal_classes,
                                      settings.classes_per_box);
    result.depth_proposals_run = true;
    for (const ObjectDetection& box : result.depth.boxes) proposals.push_back({box, -1.0, true});
    result.seconds.segmentation = seconds_since(start);
  }

  // The candidates posed in cheap order, several proposals at once (one estimator per
  // thread), as far as the mode says.
  start = Clock::now();
  result.mode = settings.mode;
  result.budget_ms = settings.budget_ms;
  result.acceptance = settings.acceptance;
  PosingOptions posing = posing_options(settings, pick_start);
  std::mutex stereo_mutex;  // one matcher (one OpenCL queue) for every posing thread
  std::vector<cv::Rect> refined;  // the boxes matched again
  if (settings.refine_boxes && settings.stereo_downscale > 1 && !posing.depth_for_candidate) {
    const StereoCamera full_rig = rig.resized_to(left_rgb8.cols, left_rgb8.rows);
    posing.depth_for_candidate = [&](const cv::Rect& box, const cv::Mat& scene_depth_mm) {
      const std::lock_guard<std::mutex> lock(stereo_mutex);
      cv::Mat disparity = result.disparity.clone(), depth_mm = scene_depth_mm.clone();
      const RegionCrop crop = refine_pick_box(impl_->stereo, left_rgb8, right_rgb8, full_rig, settings.stereo, box,
                                              0.0, disparity, depth_mm);
      if (!crop.left.empty()) refined.push_back(box);
      return depth_mm;
    };
  }
  result.posing = pose_in_cheap_order({bgr, result.depth_mm, result.camera, result.floor_depth_mm}, proposals,
                                      impl_->models, posing);
  // Counted over the candidates in the result only: a later one may have been begun while
  // the first pick was decided (which depends on the threads' timing).
  for (const CandidateOutcome& c : result.posing.candidates) {
    if (c.posed && std::find(refined.begin(), refined.end(), c.candidate.box) != refined.end()) ++result.refined_boxes;
  }
  result.seconds.pose = seconds_since(start);

  start = Clock::now();
  rank_posed(result);
  result.seconds.ranking = seconds_since(start);
  return result;
}

}  // namespace flexsight

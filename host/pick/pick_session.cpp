#include "host/pick/pick_session.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/geometry/depth_from_disparity.h"
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

// Pixels of a part nearer than this to a nearer measured surface still count as seen:
// stereo depth is a few millimetres off at a metre.
constexpr double kVisibilityToleranceMm = 5.0;

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

// Each proposal posed in its box, several at once (one estimator per thread); the parts a
// template fits, in proposal order.
std::vector<PickCandidate> pose_detections(const PickResult& result, const cv::Mat& bgr, const PoseModels& models,
                                           const PickSettings& settings, const std::vector<NamedProposal>& proposals) {
  const cv::Rect image_rect(cv::Point(), bgr.size());
  std::vector<PickCandidate> candidates(proposals.size());
  std::vector<bool> posed(proposals.size(), false);
  std::exception_ptr failure;
  const int threads = settings.threads > 0 ? settings.threads : omp_get_max_threads();
#pragma omp parallel num_threads(threads)
  {
    PoseEstimator estimator(settings.pose);
#pragma omp for schedule(dynamic)
    for (int i = 0; i < static_cast<int>(proposals.size()); ++i) {
      try {
        const ObjectDetection& d = proposals[i].detection;
        const cv::Rect box = cv::Rect(cv::Point(static_cast<int>(std::floor(d.box[0])), static_cast<int>(std::floor(d.box[1]))),
                                      cv::Point(static_cast<int>(std::ceil(d.box[2])), static_cast<int>(std::ceil(d.box[3])))) &
                             image_rect;
        if (box.width < 4 || box.height < 4) continue;
        const PoseModel& model = models.model(d.category_id, settings.model);
        PoseEstimate estimate;
        try {
          estimate = estimator.estimate(model, bgr, result.depth_mm, result.camera, box);
        } catch (const InputError&) {
          continue;  // a box without any measured depth: nothing to pose it with
        }
        // No template of the class fits the box at the measured depth: a box of another
        // class, or of several parts; nothing was posed.
        if (estimate.candidates == 0) continue;
        PickCandidate& c = candidates[i];
        c.obj_id = d.category_id;
        c.pose = estimate.pose;
        c.box = box;
        c.detection_score = d.score;
        c.from_depth = proposals[i].from_depth;
        c.naming_score = proposals[i].naming_score;
        c.pose_score = estimate.score;
        c.times = estimate.times;
        c.visible_fraction = visible_fraction(model.mesh, estimate.pose, result.camera, result.depth_mm,
                                              kVisibilityToleranceMm);
        c.height_mm = result.floor_depth_mm > 0.0 ? result.floor_depth_mm - estimate.pose.t.z() : 0.0;
        posed[i] = true;
      } catch (...) {
#pragma omp critical
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  std::vector<PickCandidate> picks;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (posed[i]) picks.push_back(candidates[i]);
  }
  return picks;
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
    if (!s.detector.parts.every_part()) {
      check_known_parts(s.detector.parts, models, s);
      return;
    }
    for (const DetectorLabel& label : detector.labels()) {
      if (!models.has(label.category_id)) {
        throw InputError(s.model, "detects object " + std::to_string(label.category_id) + " (" + label.name +
                                      "), which " + s.templates + " and " + s.cad +
                                      " do not hold: a detector for other parts than the CAD folder's");
      }
    }
    const std::vector<DetectorLabel>& labels = detector.labels();
    for (std::size_t i = 0; i < labels.size(); ++i) {
      proposal_classes.push_back({labels[i].category_id, static_cast<int>(i), models.mesh(labels[i].category_id).diameter});
    }
  }
};

PickSession::PickSession(const PickSettings& settings) : impl_(std::make_unique<Impl>(settings)) {}

void PickSession::set_ndisp(int ndisp) { impl_->settings.stereo.ndisp = ndisp; }

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

  auto start = Clock::now();
  ProgressCallback progress;
  if (!settings.quiet) progress = [](const std::string& stage) { std::cerr << "  stereo: " << stage << "\n"; };
  result.disparity = pick_disparity(impl_->stereo, left_rgb8, right_rgb8, rig, settings.stereo, settings.stereo_plan,
                                    settings.stereo_downscale, progress, &result.stereo_path)
                         .disparity;
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

  // Each proposal posed on its own, several at once (one estimator per thread).
  start = Clock::now();
  result.picks = pose_detections(result, bgr, impl_->models, settings, proposals);
  result.seconds.pose = seconds_since(start);

  start = Clock::now();
  rank_picks(result.picks);
  result.proposals = result.picks;
  remove_duplicate_picks(result.picks, kDuplicateIou);
  result.seconds.ranking = seconds_since(start);
  return result;
}

}  // namespace flexsight

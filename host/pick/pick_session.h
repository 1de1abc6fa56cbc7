#pragma once
// The pick job on one rectified pair: stereo depth, detection, the pose in each box, and
// the ranked list for the robot. A PickSession loads its models once (detector,
// templates, CAD parts, the OpenCL context) and serves any number of pairs: `flexsight
// pick`, `flexsight eval-pick` and a service all call PickSession::pick. One
// ComputeBackend (one OpenCL context) serves the matcher and the detector's
// post-processing.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/detect/ssd_detector.h"
#include "host/detect/tiled_detection.h"
#include "host/geometry/stereo_camera.h"
#include "host/pick/depth_proposals.h"
#include "host/pick/ordered_posing.h"
#include "host/pick/pick_naming.h"
#include "host/pick/pick_ranking.h"
#include "host/pick/pick_stereo.h"
#include "host/pose/pose_models.h"
#include "host/runtime/device_options.h"
#include "host/stereo/stereo_params.h"

namespace flexsight {

inline PoseEstimatorParams bin_pose_params() {
  PoseEstimatorParams params;
  params.dcd.thresholds = DcdParams::EdgeThresholds::kContrastAndNoise;
  return params;
}

struct PickSettings {
  StereoParams stereo;
  BackendOptions backend;
  // detector.parts: known-part mode (host/detect/known_parts.h), only those detected and posed.
  SsdDetectorOptions detector;
  // A bin's parts lie on its dark, uniform floor, where edge thresholds brought to each
  // box's contrast and noise pose more parts right (docs/pose.md, "Edges under noise").
  PoseEstimatorParams pose = bin_pose_params();
  std::string model;      // the detector (resolved path)
  std::string templates;  // flexsight pose-templates' file
  std::string cad;        // the CAD folder the templates were made from
  int threads = 0;        // parts posed at once (0 = all cores)
  // Detection tiles (host/detect/tiled_detection.h): -1 sized from the parts' diameters
  // and the measured depth, 0 the whole image only, else tiles of this many pixels.
  int detection_tile = -1;
  // Classes posed per box (pose_proposals in host/pick/pick_ranking.h), the best fit kept.
  int classes_per_box = 5;
  // The namer (host/detect/part_namer.h) whose classes are posed per box instead of the
  // detector's (pick_naming.h); empty: the detector's classes alone.
  std::string namer;
  NamingMix naming_mix = NamingMix::Product;
  // The pair is matched at 1/stereo_downscale of its size and the disparity brought back
  // along the matcher's planes (host/stereo/disparity_upsampling.h: no depth is mixed
  // across a part's edge): the matcher's time falls with the square of it; detection and
  // pose keep the full image.
  int stereo_downscale = 1;
  // Which pixels are matched (host/pick/pick_stereo.h): the whole pair (full), or the bin's
  // region alone over its disparity range, found in a match at 1/8 size (roi;
  // docs/pick.md, "Stereo where it matters"). stereo_downscale applies to what is matched.
  // roi: on the development bins the same pose recall and first picks as full in 0.4x
  // the matcher's time (docs/pick.md, "At a robot's pace").
  StereoPlan stereo_plan = StereoPlan::kBinRegion;
  // With the pair matched coarser than its size (stereo_downscale > 1), each candidate's
  // box is matched again at full size before it is posed (refine_pick_box in
  // host/pick/pick_stereo.h): the coarse match finds the bin and orders the candidates,
  // the few posed get full-resolution depth.
  bool refine_boxes = true;
  // With the bin's region (StereoPlan::kBinRegion), detection tiles cover it alone: 4x
  // faster detection, but on the development bins mAP@0.5 fell from 0.50 to 0.40 (pose
  // recall 66.1 -> 67.9 %), so it is off by default (docs/pick.md, "At a robot's pace").
  bool detect_in_bin = false;
  // Parts segmented from the depth above the bin floor that no network box matches are
  // posed too (host/pick/depth_proposals.h).
  bool depth_proposals = false;
  // How much of the bin is posed (ordered_posing.h; docs/pick.md, "The first pick
  // first"): the first pick that passes `acceptance`, every proposal, or on after the
  // first pick until `budget_ms` of the pick (from its start, stereo included) have passed.
  PickMode mode = PickMode::FirstPick;
  int budget_ms = 0;
  AcceptanceRule acceptance;
  // The depth each candidate box is posed with (ordered_posing.h); empty: the scene's.
  CandidateDepth depth_for_candidate;
  bool quiet = false;
};

struct PickStageSeconds {
  double stereo = 0.0, depth = 0.0, detection = 0.0, pose = 0.0, ranking = 0.0;
  double segmentation = 0.0;  // proposals from depth (0 when off)
  double naming = 0.0;        // the namer's (pick_naming.h), 0 without one
  double total() const { return stereo + depth + detection + naming + segmentation + pose + ranking; }
};

struct PickResult {
  cv::Mat disparity;  // CV_32FC1, left view
  cv::Mat depth_mm;   // CV_32FC1, 0 where unknown
  PinholeCamera camera;
  double floor_depth_mm = 0.0;
  std::vector<ObjectDetection> detections;
  std::vector<PickCandidate> picks;  // ranked, best first
  // Every pose tried (a box with several classes, ranked; picks are what is left after
  // remove_duplicate_picks), for diagnosis.
  std::vector<PickCandidate> proposals;
  // The candidates in cheap order, which were posed and why the first pick was taken
  // (its `posed` moved into picks and proposals).
  PickMode mode = PickMode::FirstPick;
  int budget_ms = 0;          // PickMode::Budget's
  AcceptanceRule acceptance;  // the rule the first pick was checked by
  PosingOutcome posing;
  // The answer for the robot: the accepted candidate's best pose, else (none accepted)
  // the best-ranked pick; none without any pick.
  bool has_first_pick = false;
  bool first_pick_accepted = false;
  PickCandidate first_pick;
  double seconds_to_first_pick = 0.0;  // from the pick's start (ordered_posing.h)
  // The depth segmentation and its proposals (depth_proposals_run: when
  // PickSettings::depth_proposals is on).
  bool depth_proposals_run = false;
  DepthProposals depth;
  TilingPlan detection_tiling;  // the tiles detection ran on (tile 0: the whole image)
  StereoPlan stereo_plan = StereoPlan::kFull;  // what was matched, at 1/stereo_downscale
  int stereo_downscale = 1;
  BinRegion bin_region;         // StereoPlan::kBinRegion: the bin found (found false otherwise)
  int refined_boxes = 0;        // candidates' boxes matched again at full size (refine_boxes)
  PickStageSeconds seconds;
  std::string stereo_path, detector_path;  // which backend each ran on
  std::string namer_path;                  // the namer's model; empty without one
};

class PickSession {
 public:
  // Loads and checks everything before any image: the detector (its files), the
  // templates against the CAD folder, and that every class the detector knows has a
  // model and templates (else an InputError naming --model). With known parts
  // (settings.detector.parts) only those are detected and posed: each must be a class
  // of the detector and have a CAD model and templates (else an InputError naming
  // --parts and what is missing). Builds the OpenCL parts.
  explicit PickSession(const PickSettings& settings);
  ~PickSession();
  PickSession(const PickSession&) = delete;
  PickSession& operator=(const PickSession&) = delete;

  const PoseModels& models() const;
  const SsdDetector& detector() const;
  // `left`, `right`: RGB8 of one size; `rig`: their calibration at that size.
  // `texture_left_rgb8`: the left view with the projector off, when the camera takes one
  // (empty otherwise): detection and the pose's edges then use it, since the projector's
  // dots hide the parts from a detector trained without them and are edges themselves.
  PickResult pick(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8, const StereoCamera& rig,
                  const cv::Mat& texture_left_rgb8 = cv::Mat());

  // How much of the bin the next pairs are posed for (PickSettings::mode, budget_ms): a
  // service's per-request choice.
  void set_pick_mode(PickMode mode, int budget_ms = 0);

  // The matcher's disparity range for the next pairs (each bin's calib.txt may give its own).
  void set_ndisp(int ndisp);

  // The settings of the next pairs (a service whose requests carry pick's options): what
  // was loaded at construction stays (detector and its options, templates, CAD folder,
  // namer, backend); InputError naming the option when `settings` asks for another.
  void set_pair_settings(const PickSettings& settings);
  // set_pair_settings' check alone (a service refuses a request before it queues it).
  void check_pair_settings(const PickSettings& settings) const;

  // The matcher alone, with pick's settings (eval-pick's pair without the pattern).
  cv::Mat disparity(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8);

 private:
  TilingPlan detection_tiling(cv::Size image, const PinholeCamera& camera, const cv::Mat& depth_mm) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexsight

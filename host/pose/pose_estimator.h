#pragma once
// The 6D pose of one part in one box (docs/pose.md): the box's edges and their
// directional chamfer tensor, the template search at the depth the box's stereo depth
// gives, Levenberg-Marquardt on the tensor for the best candidates, point-to-plane ICP
// of the part's visible surface against the depth in the box, and a score from the edge
// fit and the depth fit together; the best-scoring candidate wins.
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "host/pose/dcd_refiner.h"
#include "host/pose/dcd_tensor.h"
#include "host/pose/edge_template.h"
#include "host/pose/point_to_plane_icp.h"
#include "host/pose/template_search.h"
#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight {

// Which refinements run after the search. The default is ICP alone from the template's
// pose: on the tuning sets (seeds 11, 12) it posed 28/30 isolated and 55/62 cluttered
// parts within ADD(-S) 0.1 d, against 27/30 and 48/62 with the edge LM first (the LM
// settles some candidates in neighbouring edge minima that ICP then cannot leave);
// docs/pose.md.
enum class PoseRefinement { kBoth, kEdgesOnly, kDepthOnly };

struct PoseEstimatorParams {
  DcdParams dcd;
  SearchParams search;
  DcdRefineParams refine;
  IcpParams icp;
  PoseRefinement refinement = PoseRefinement::kDepthOnly;
  double box_margin = 0.25;      // the tensor covers the box grown by this much per side
  int scored_candidates = 3;     // the best candidates after the edge refinement that
                                 // are fitted to the depth and scored
  double retry_below_score = 0.5;  // when the best of those scores below this, every
                                   // other candidate is fitted and scored too
  bool try_half_turns = true;    // also fit each scored candidate turned by 180 degrees
                                 // about the model's x, y and z axes
  int max_scene_points = 1500;   // depth pixels of the box used by ICP (evenly strided)
  int max_model_points = 1500;   // visible model surface points used by ICP
  double depth_tolerance = 0.02; // of the diameter (at least 2 mm): a depth that agrees
  // Depth pixels nearer than the box's surface depth minus this many diameters hide the
  // part (0 = off); an edge point there costs occluded_point_cost pixels at most.
  double occluder_margin = 0.3;
  double occluded_point_cost = 4.0;
  void check() const;
};

struct PoseStageTimes {
  double edges_ms = 0.0, search_ms = 0.0, refine_ms = 0.0, icp_ms = 0.0, score_ms = 0.0;
  double total_ms() const { return edges_ms + search_ms + refine_ms + icp_ms + score_ms; }
};

struct PoseEstimate {
  int obj_id = 0;
  Pose pose;
  double score = 0.0;      // 0..1: edge fit times depth fit
  double edge_cost = 0.0;  // mean directional chamfer distance of the edge points, pixels
  double depth_fit = 0.0;  // of the part's rendered pixels with a measured depth: the
                           // fraction that agree (occluded pixels do not count)
  int candidates = 0;      // hypotheses refined
  PoseStageTimes times;
};

// One part model: its mesh and its templates.
struct PoseModel {
  int obj_id = 0;
  std::shared_ptr<const Mesh> mesh;
  const PartTemplates* templates = nullptr;  // owned by the caller's TemplateSet
  int in_plane_steps = 40;
};

class PoseEstimator {
 public:
  explicit PoseEstimator(const PoseEstimatorParams& params);
  ~PoseEstimator();
  PoseEstimator(const PoseEstimator&) = delete;
  PoseEstimator& operator=(const PoseEstimator&) = delete;

  // `image`: 8-bit grey or BGR; `depth`: CV_32FC1 mm, 0 where unknown, the image's size;
  // `box` in image pixels. Throws InputError for an empty box, a box outside the image,
  // a depth of another size, or a box with no depth at all.
  PoseEstimate estimate(const PoseModel& model, const cv::Mat& image, const cv::Mat& depth,
                        const PinholeCamera& camera, const cv::Rect& box);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The median depth (mm) of the measured pixels in the middle half of `box` (the whole
// box when the middle has none); 0 when the box has no measured depth.
double box_surface_depth(const cv::Mat& depth, const cv::Rect& box);

}  // namespace flexsight

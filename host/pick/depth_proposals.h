#pragma once
// Proposals from depth (docs/pick.md, "Proposals from depth"): the parts the depth
// segmentation finds above the bin floor (host/segment) that no network box matches
// become boxes to pose. Their classes come from the detections inside them, best score
// first; where the detector saw nothing there, from the parts whose size is nearest the
// region's.
#include <opencv2/core.hpp>
#include <vector>

#include "host/detect/ssd_detector.h"
#include "host/geometry/pinhole_camera.h"
#include "host/segment/depth_segmentation.h"

namespace flexsight {

// A class the proposals may name: the detector's ids and the part's diameter.
struct ProposalClass {
  int category_id = 0;
  int class_id = 0;
  double diameter_mm = 0.0;
};

struct DepthProposals {
  DepthSegmentation segmentation;
  // Per kept region (segmentation.regions): whether a network box matches it.
  std::vector<bool> matched;
  // The unmatched regions' boxes, each as up to classes_per_box detections (one per
  // class, best first), in region order.
  std::vector<ObjectDetection> boxes;
};

// A region matches a network box when their IoU exceeds this: the network's box is
// posed, the region adds nothing.
constexpr double kDepthMatchIou = 0.5;
// A detection lends its class to a region when this share of the smaller box lies in
// the other.
constexpr double kClassOverlap = 0.5;

// The segmentation of `depth_mm` with part sizes from `classes`, matched against
// `detections`. `classes` must not be empty.
DepthProposals propose_from_depth(const cv::Mat& depth_mm, const PinholeCamera& camera,
                                  const std::vector<ObjectDetection>& detections,
                                  const std::vector<ProposalClass>& classes, int classes_per_box);

// The classes a region's box is proposed as: those of the detections overlapping it
// (kClassOverlap), each at its best score, best first; else the `classes` whose diameter
// is nearest the region's extent (score 0). At most classes_per_box.
std::vector<ObjectDetection> region_proposals(const DepthRegion& region, const std::vector<ObjectDetection>& detections,
                                              const std::vector<ProposalClass>& classes, int classes_per_box);

// The regions over a grey copy of `left_rgb8` (BGR): every region above the floor tinted,
// the kept ones boxed (orange: proposed, blue: a network box matches it).
cv::Mat depth_regions_picture(const cv::Mat& left_rgb8, const DepthProposals& proposals);

}  // namespace flexsight

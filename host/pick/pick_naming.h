#pragma once
// Which classes pick poses at a box when a namer (host/detect/part_namer.h) is loaded:
// the detector finds the parts far more often than it names them, so each group of
// overlapping boxes is named once from a crop of its best box, and the group's
// `classes_per_box` best classes by the namer's probability (alone, or times the
// detector's score for that class in the group) are posed.
#include <string>
#include <vector>

#include "host/detect/part_namer.h"
#include "host/detect/ssd_detector.h"

namespace flexsight {

enum class NamingMix {
  Namer,    // the namer's probability alone
  Product,  // the namer's probability x (the detector's best score of the class in the group + 0.05)
};
// "namer" or "product"; InputError naming `option` otherwise.
NamingMix parse_naming_mix(const std::string& text, const std::string& option);

struct NamedProposal {
  ObjectDetection detection;  // the group's best box, its category the named class
  double naming_score = 0.0;  // the namer's probability of that class at the box
  bool from_depth = false;    // a region of the depth no detector box matched (host/segment)
};

// Detections grouped as pose_proposals groups them (best first; IoU above `iou` with a
// group's best box), then per group its `classes_per_box` best classes by the mix, best
// first. `bgr`: the image the detections are in.
std::vector<NamedProposal> named_proposals(const std::vector<ObjectDetection>& detections, PartNamer& namer,
                                           const cv::Mat& bgr, int classes_per_box, double iou, NamingMix mix);

}  // namespace flexsight

#pragma once
// Known-part mode: the parts a cell handles (`--parts 5,12`), as bin-picking cells are
// taught the CAD models of their parts. Detection then reports only those classes and the
// pick poses only them.
//
// How the detector's scores change: with a softmax model (the shipped one) the class
// scores of an anchor share one unit of probability with the background, so a part the
// network half-confuses with an absent look-alike scores low for its own class. Knowing
// the look-alike cannot be there is a prior of zero for it, and Bayes' rule then gives
// the softmax over the background and the known classes only: the logits of the other
// classes are left out before the scores, not the scores filtered after. With a sigmoid
// model each class's score is independent of the others, so leaving the other classes'
// logits out is exactly filtering their boxes. Either way the boxes of absent classes
// never enter NMS, so they cannot suppress a known part's box either.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/detect/detector_model.h"

namespace flexsight {

struct KnownParts {
  // Object ids (category ids of the detector's labels), ascending; empty: every part.
  std::vector<int> obj_ids;

  bool every_part() const { return obj_ids.empty(); }
  // Whether obj_id is one of them (any id when every_part()).
  bool contains(int obj_id) const;
};

// "5,12" into the known parts: parse_object_ids's rules, InputError naming `option`.
KnownParts parse_known_parts(const std::string& text, const std::string& option = "--parts");

// The detector classes (0-based class_id, ascending) of the known parts; empty for
// every_part(). InputError naming `option` for an id that is not a class of `labels`
// (read from `model`).
std::vector<int> known_part_classes(const KnownParts& parts, const std::vector<DetectorLabel>& labels,
                                    const std::string& model, const std::string& option = "--parts");

// The class logits (N x (C + 1), CV_32F, column 0 the background) cut to the background
// and the columns of `classes` (class_id + 1 each): N x (classes.size() + 1).
cv::Mat known_part_logits(const cv::Mat& class_logits, const std::vector<int>& classes);

}  // namespace flexsight

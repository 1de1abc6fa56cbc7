#include "host/pick/pick_acceptance.h"

#include <cstdio>

namespace flexsight {
namespace {

std::string below(const char* figure, double value, double bound) {
  char text[96];
  std::snprintf(text, sizeof text, "%s %.4f < %.4f", figure, value, bound);
  return text;
}

}  // namespace

std::string acceptance_failure(const PickCandidate& candidate, const AcceptanceRule& rule) {
  // NaN figures fail: the comparisons are written so that they pass only on a number.
  if (!(candidate.pose_score >= rule.min_pose_score)) return below("pose_score", candidate.pose_score, rule.min_pose_score);
  if (!(candidate.depth_fit >= rule.min_depth_fit)) return below("depth_fit", candidate.depth_fit, rule.min_depth_fit);
  if (!(candidate.visible_fraction >= rule.min_visible_fraction)) {
    return below("visible_fraction", candidate.visible_fraction, rule.min_visible_fraction);
  }
  return "";
}

}  // namespace flexsight

#include "host/pick/pick_outputs.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <utility>
#include <opencv2/imgproc.hpp>

#include "host/pose/pose_drawing.h"

namespace flexsight {
namespace {

// Picks ranked below this pick_score are left out of the picture (still in the JSON).
constexpr double kPictureMinPickScore = 0.5;

using Json = nlohmann::ordered_json;

// R row-major and t (mm) as JSON arrays.
std::pair<Json, Json> pose_json(const Pose& pose) {
  Json R = Json::array(), t = Json::array();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R.push_back(pose.R(i, j));
    t.push_back(pose.t(i));
  }
  return {R, t};
}

// The depth segmentation's floor, regions and proposals (when pick ran it).
Json depth_proposals_json(const DepthProposals& depth, double seconds) {
  Json regions = Json::array();
  for (std::size_t i = 0; i < depth.segmentation.regions.size(); ++i) {
    const DepthRegion& r = depth.segmentation.regions[i];
    regions.push_back({{"box", {r.box.x, r.box.y, r.box.width, r.box.height}},
                       {"score", r.score},
                       {"extent_mm", r.extent_mm},
                       {"area_mm2", r.area_mm2},
                       {"depth_mm", r.depth_mm},
                       {"matched", static_cast<bool>(depth.matched[i])}});
  }
  const FloorPlane& floor = depth.segmentation.floor;
  return {{"floor", {{"found", floor.found},
                     {"normal", {floor.normal.x(), floor.normal.y(), floor.normal.z()}},
                     {"offset_mm", floor.offset},
                     {"inlier_share", floor.inlier_share}}},
          {"regions_above_floor", depth.segmentation.region_count},
          {"regions", regions},
          {"proposals", depth.boxes.size()},
          {"seconds", seconds}};
}

// How far pick posed the bin: each candidate in cheap order with its cues, whether it was
// posed and how its best pose fared against the acceptance rule.
Json candidates_json(const PosingOutcome& posing, const std::vector<PickCandidate>& posed) {
  Json candidates = Json::array();
  int order = 1;
  for (const CandidateOutcome& c : posing.candidates) {
    const CandidateCues& q = c.candidate.cues;
    Json cues = {{"height_mm", q.height_mm}, {"free_space", q.free_space}, {"visible_estimate", q.visible_estimate},
                 {"detection_score", q.detection_score}};
    if (q.naming_score >= 0.0) cues["naming_score"] = q.naming_score;
    const cv::Rect& b = c.candidate.box;
    Json entry = {{"order", order++},
                  {"box", {b.x, b.y, b.width, b.height}},
                  {"proposals", c.candidate.proposals.size()},
                  {"cheap_score", c.candidate.cheap_score},
                  {"cues", cues},
                  {"posed", c.posed}};
    if (c.posed) {
      const auto best = std::find_if(posed.begin(), posed.end(),
                                     [&](const PickCandidate& p) { return p.proposal_index == c.best; });
      entry["best"] = nullptr;
      if (best != posed.end()) {
        const auto [R, t] = pose_json(best->pose);
        entry["best"] = {{"obj_id", best->obj_id},         {"pose_score", best->pose_score},
                         {"depth_fit", best->depth_fit},   {"visible_fraction", best->visible_fraction},
                         {"pick_score", best->pick_score}, {"R", R},
                         {"t_mm", t}};
      }
      entry["accepted"] = c.rejection.empty();
      if (!c.rejection.empty()) entry["rejected"] = c.rejection;
    }
    candidates.push_back(entry);
  }
  return candidates;
}

// The answer for the robot and why it was taken.
Json first_pick_json(const PickResult& result, const AcceptanceRule& rule) {
  if (!result.has_first_pick) return nullptr;
  const PickCandidate& c = result.first_pick;
  const auto [R, t] = pose_json(c.pose);
  char why[200];
  if (result.first_pick_accepted) {
    std::snprintf(why, sizeof why, "accepted: pose_score %.3f >= %.3f, depth_fit %.3f >= %.3f, visible_fraction %.3f >= %.3f",
                  c.pose_score, rule.min_pose_score, c.depth_fit, rule.min_depth_fit, c.visible_fraction,
                  rule.min_visible_fraction);
  } else {
    std::snprintf(why, sizeof why, "no candidate passed the acceptance rule: every proposal posed, the best-ranked taken");
  }
  return {{"accepted", result.first_pick_accepted},
          {"why", why},
          {"candidate", result.posing.first_pick >= 0 ? Json(result.posing.first_pick + 1) : Json(nullptr)},
          {"rule", {{"min_pose_score", rule.min_pose_score}, {"min_depth_fit", rule.min_depth_fit},
                    {"min_visible_fraction", rule.min_visible_fraction}}},
          {"obj_id", c.obj_id},
          {"pick_score", c.pick_score},
          {"pose_score", c.pose_score},
          {"depth_fit", c.depth_fit},
          {"visible_fraction", c.visible_fraction},
          {"height_mm", c.height_mm},
          {"box", {c.box.x, c.box.y, c.box.width, c.box.height}},
          {"R", R},
          {"t_mm", t}};
}

// What was matched at which size, the bin found and the boxes matched again.
Json stereo_plan_json(const PickResult& result) {
  Json plan = {{"plan", stereo_plan_name(result.stereo_plan)},
               {"downscale", result.stereo_downscale},
               {"refined_boxes", result.refined_boxes}};
  if (result.stereo_plan == StereoPlan::kBinRegion) {
    const BinRegion& bin = result.bin_region;
    plan["bin_region"] = {{"found", bin.found},
                          {"rect", {bin.rect.x, bin.rect.y, bin.rect.width, bin.rect.height}},
                          {"disparity_range", {bin.range.min, bin.range.max}}};
  }
  return plan;
}

Json detection_tiles_json(const TilingPlan& tiling) {
  Json tiles = {{"tile", tiling.tile}, {"stride", tiling.stride}};
  if (!tiling.region.empty()) {
    tiles["region"] = {tiling.region.x, tiling.region.y, tiling.region.width, tiling.region.height};
  }
  return tiles;
}

}  // namespace

std::string pick_json(const PickResult& result, const PickInputsDescription& inputs) {
  Json picks = Json::array();
  int rank = 1;
  for (const PickCandidate& c : result.picks) {
    const auto [R, t] = pose_json(c.pose);
    picks.push_back({{"rank", rank++},
                     {"obj_id", c.obj_id},
                     {"pick_score", c.pick_score},
                     {"pose_score", c.pose_score},
                     {"detection_score", c.detection_score},
                     {"visible_fraction", c.visible_fraction},
                     {"height_mm", c.height_mm},
                     {"box", {c.box.x, c.box.y, c.box.width, c.box.height}},
                     {"R", R},
                     {"t_mm", t},
                     {"pose_ms", {{"edges", c.times.edges_ms}, {"search", c.times.search_ms},
                                  {"refine", c.times.refine_ms}, {"icp", c.times.icp_ms},
                                  {"score", c.times.score_ms}}}});
    if (result.depth_proposals_run) picks.back()["source"] = c.from_depth ? "depth" : "network";
    if (c.naming_score >= 0.0) picks.back()["naming_score"] = c.naming_score;
  }
  Json proposals = Json::array();
  for (const PickCandidate& c : result.proposals) {
    const auto [R, t] = pose_json(c.pose);
    proposals.push_back({{"obj_id", c.obj_id},
                         {"pose_score", c.pose_score},
                         {"detection_score", c.detection_score},
                         {"visible_fraction", c.visible_fraction},
                         {"box", {c.box.x, c.box.y, c.box.width, c.box.height}},
                         {"R", R},
                         {"t_mm", t}});
    if (result.depth_proposals_run) proposals.back()["source"] = c.from_depth ? "depth" : "network";
    if (c.naming_score >= 0.0) proposals.back()["naming_score"] = c.naming_score;
  }
  const PickStageSeconds& s = result.seconds;
  Json document = {
      {"inputs", {{"left", inputs.left}, {"right", inputs.right}, {"calib", inputs.calib}, {"model", inputs.model},
                  {"templates", inputs.templates}, {"cad", inputs.cad},
                  {"passive_left", inputs.passive_left.empty() ? Json(nullptr) : Json(inputs.passive_left)},
                  {"parts", inputs.parts.empty() ? Json(nullptr) : Json(inputs.parts)}}},
      {"image_size", {result.disparity.cols, result.disparity.rows}},
      {"camera", {{"fx", result.camera.fx}, {"fy", result.camera.fy}, {"cx", result.camera.cx}, {"cy", result.camera.cy}}},
      {"frame", "left camera: x right, y down, z forward, mm; R row-major maps model to camera"},
      {"stereo", result.stereo_path},
      {"detector", result.detector_path},
      {"floor_depth_mm", result.floor_depth_mm},
      {"detections", result.detections.size()},
      {"stereo_plan", stereo_plan_json(result)},
      {"detection_tiles", detection_tiles_json(result.detection_tiling)},
      {"seconds", {{"stereo", s.stereo}, {"depth", s.depth}, {"detection", s.detection}, {"pose", s.pose},
                   {"ranking", s.ranking}, {"total", s.total()}}},
      {"seconds_to_first_pick", result.seconds_to_first_pick},
      {"mode", pick_mode_name(result.mode)},
      {"first_pick", first_pick_json(result, result.acceptance)},
      {"picks", picks},
      {"proposals", proposals},
      {"candidates", candidates_json(result.posing, result.proposals)}};
  if (result.mode == PickMode::Budget) document["budget_ms"] = result.budget_ms;
  if (result.depth_proposals_run) document["depth_proposals"] = depth_proposals_json(result.depth, s.segmentation);
  // Only with a namer, so that pick without one writes what it wrote before.
  if (!result.namer_path.empty()) {
    document["namer"] = result.namer_path;
    document["seconds"]["naming"] = s.naming;
  }
  return document.dump(1) + "\n";
}

cv::Mat pick_picture(const cv::Mat& left_rgb8, const PickResult& result, const PoseModels& models) {
  cv::Mat bgr;
  cv::cvtColor(left_rgb8, bgr, cv::COLOR_RGB2BGR);
  // The picks a robot would consider: the first always, the rest while they fit well.
  // Drawing the detector's hundreds of low-score proposals as well would hide the parts.
  std::vector<PosedPart> parts;
  int rank = 1;
  for (const PickCandidate& c : result.picks) {
    if (rank > 1 && c.pick_score < kPictureMinPickScore) break;
    // The first pick green, the others orange.
    const cv::Scalar colour = rank == 1 ? cv::Scalar(80, 220, 80) : cv::Scalar(0, 140, 255);
    cv::rectangle(bgr, c.box, cv::Scalar(200, 200, 0), 1);
    parts.push_back({models.model(c.obj_id, "").mesh, c.pose, colour,
                     "#" + std::to_string(rank) + " obj " + std::to_string(c.obj_id)});
    ++rank;
  }
  draw_posed_parts(bgr, parts, result.camera);
  return bgr;
}

}  // namespace flexsight

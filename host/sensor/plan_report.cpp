#include "host/sensor/plan_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace flexsight {
namespace {

using Json = nlohmann::ordered_json;

struct Row {
  std::string name, value;
};
struct Section {
  std::string title;
  std::vector<Row> rows;
};

std::string fmt(const char* format, double a) {
  char text[128];
  std::snprintf(text, sizeof text, format, a);
  return text;
}
std::string fmt(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}
std::string fmt(const char* format, double a, double b, double c) {
  char text[200];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

// No "-0.0" for a value that is zero up to rounding (the centred near-plane disparity).
double clean(double value) { return std::abs(value) < 1e-6 ? 0.0 : value; }

std::string devices_text(unsigned seen) {
  std::string text;
  if (seen & kSeenByLeft) text += "C1 ";
  if (seen & kSeenByRight) text += "C2 ";
  if (seen & kSeenByProjector) text += "P ";
  if (text.empty()) return "none";
  text.pop_back();
  return text;
}

std::string region_text(const RegionCoverage& r) {
  return fmt("%.1f %% (C1 %.1f, C2 %.1f, ", r.all, r.left, r.right) +
         fmt("P %.1f, both cameras %.1f)", r.projector, r.cameras);
}

// One line on whether the volume fits: the samples inside, then the box's surface (its
// faces and corners can leave a frustum while every cell centre is still inside).
std::string verdict(const VolumeCoverage& c) {
  if (c.any_unseen) {
    return fmt("the volume does NOT fit: %.1f %% of it is not seen by all three", 100.0 - c.volume.all);
  }
  bool surface_seen = true;
  for (const RegionCoverage& f : c.faces) surface_seen = surface_seen && f.all >= 100.0;
  for (const CornerCoverage& k : c.corners) surface_seen = surface_seen && k.seen == kSeenByAll;
  return surface_seen ? std::string("the whole volume is seen by all three")
                      : std::string("the inside is seen by all three, parts of the box's surface are not "
                                    "(faces, corners)");
}

// The figures once, in the order both text forms print them.
std::vector<Section> sections(const SensorPlan& p) {
  const SensorPlanInputs& in = p.inputs;
  const WorkingVolume& v = in.volume;
  const double um = in.pixel_um;
  std::vector<Section> out;

  out.push_back({"Rig", {
      {"baseline", fmt("%.1f mm", in.baseline_mm)},
      {"cameras", fmt("%.0f x %.0f px (%.1f MP)", in.width, in.height, in.width * in.height / 1e6) +
                      fmt(", pixel %.2f um (sensor %.2f x %.2f mm)", um, px_to_mm(in.width, um),
                          px_to_mm(in.height, um))},
      {"focal length", fmt("%.1f px = %.2f mm", p.rig.focal(), p.focal_mm) +
                           (p.focal_fitted ? (p.doffs_centred ? " (the largest at which the volume fits both images)"
                                                : " (the largest at which the volume fits both images with the "
                                                  "centring doffs, not necessarily with this one)")
                            : "")},
      {"field of view", fmt("%.2f x %.2f deg", p.hfov_deg, p.vfov_deg)},
      {"volume fits both images up to", fmt("f = %.1f px = %.2f mm", p.fitting_focal_px,
                                               px_to_mm(p.fitting_focal_px, um))},
      {"doffs (cx right - cx left)", fmt("%.1f px", p.rig.doffs) +
                                         (p.doffs_centred ? " (centres the volume in both images)" : "")},
      {"projector", fmt("%.1f x %.1f deg at x = %.1f mm", in.projector_hfov_deg, in.projector_vfov_deg,
                        in.projector_offset_mm)},
      {"working volume", fmt("%.0f x %.0f x %.0f mm", v.width, v.height, v.depth) +
                             fmt(", centroid at %.0f mm (z %.0f..%.0f)", v.distance, v.near_z(), v.far_z())},
  }});

  const VolumeCoverage& c = p.coverage;
  Section coverage{"Coverage (seen by C1, C2 and P)", {
      {"verdict", verdict(c)},
      {"volume", region_text(c.volume)},
      {"grid", fmt("%.1f mm step: %.0f samples", c.step_mm, static_cast<double>(c.volume.samples)) +
                   " (" + std::to_string(c.nx) + " x " + std::to_string(c.ny) + " x " +
                   std::to_string(c.nz) + ")"},
  }};
  for (const RegionCoverage& f : c.faces) coverage.rows.push_back({"face " + f.name, region_text(f)});
  for (const RegionCoverage& s : c.slabs) coverage.rows.push_back({s.name, fmt("%.1f %%", s.all)});
  for (const CornerCoverage& k : c.corners) {
    coverage.rows.push_back({"corner " + k.name, devices_text(k.seen)});
  }
  coverage.rows.push_back(
      {"unseen region", c.any_unseen ? fmt("x %.0f..%.0f, ", c.unseen_min.x(), c.unseen_max.x()) +
                                           fmt("y %.0f..%.0f, ", c.unseen_min.y(), c.unseen_max.y()) +
                                           fmt("z %.0f..%.0f mm (bounding box of unseen samples)",
                                               c.unseen_min.z(), c.unseen_max.z())
                                     : std::string("none")});
  out.push_back(coverage);

  out.push_back({fmt("Depth resolution (dZ = Z^2 x %.4g px / (f B))", in.subpixel_px), {
      {"near plane", fmt("Z %.0f mm: dZ %.4f mm, pixel %.4f mm", v.near_z(), p.dz_near_mm, p.pixel_near_mm)},
      {"far plane", fmt("Z %.0f mm: dZ %.4f mm, pixel %.4f mm", v.far_z(), p.dz_far_mm, p.pixel_far_mm)},
  }});

  out.push_back({"Disparity range", {
      {"f B / Z", fmt("%.1f (near) .. %.1f (far) px", p.raw_disparity_near, p.raw_disparity_far)},
      {"with doffs (f B / Z - doffs)", fmt("%.1f (near) .. %.1f (far) px", clean(p.disparity_near), clean(p.disparity_far))},
      {"matcher (searches 0..ndisp-1)",
       fmt("ndisp %.0f once the pair is shifted by %.0f px to doffs ", p.ndisp, p.matcher_shift_px) +
           fmt("%.1f px (far plane at disparity >= 0)", p.rig.doffs + p.matcher_shift_px)},
  }});

  out.push_back({fmt("The paper's %.2g mm at the far plane", in.target_dz_mm), {
      {"at this focal length", fmt("needs a disparity step of %.3f px (1/%.1f)", p.subpixel_for_target,
                                   1.0 / p.subpixel_for_target)},
      {"at this disparity step", fmt("needs f = %.0f px = %.2f mm", p.focal_for_target_px,
                                     px_to_mm(p.focal_for_target_px, um)) +
                                     fmt(" (%.1f deg wide)", hfov_from_focal(p.focal_for_target_px, in.width))},
      {"at whole-pixel disparities", fmt("needs f = %.0f px = %.2f mm", p.focal_for_target_1px,
                                         px_to_mm(p.focal_for_target_1px, um)) +
                                         fmt(" (%.1f deg wide)", hfov_from_focal(p.focal_for_target_1px, in.width))},
      {"as a pixel footprint (Z / f)", fmt("f = %.0f px = %.2f mm", p.focal_for_lateral_target,
                                           px_to_mm(p.focal_for_lateral_target, um)) +
                                           fmt(" (%.1f deg wide), where dZ = %.2g mm needs a step of ",
                                               hfov_from_focal(p.focal_for_lateral_target, in.width),
                                               in.target_dz_mm) +
                                           fmt("%.3f px", p.subpixel_for_target_at_lateral)},
  }});
  return out;
}

}  // namespace

std::string plan_table(const SensorPlan& plan) {
  std::ostringstream out;
  for (const Section& s : sections(plan)) {
    size_t width = 0;
    for (const Row& r : s.rows) width = std::max(width, r.name.size());
    out << s.title << "\n";
    for (const Row& r : s.rows) {
      out << "  " << r.name << std::string(width - r.name.size() + 2, ' ') << r.value << "\n";
    }
  }
  return out.str();
}

std::string plan_markdown(const SensorPlan& plan) {
  std::ostringstream out;
  out << "# Sensor plan\n\n";
  for (const Section& s : sections(plan)) {
    out << "## " << s.title << "\n\n| | |\n|---|---|\n";
    for (const Row& r : s.rows) out << "| " << r.name << " | " << r.value << " |\n";
    out << "\n";
  }
  out << "Pictures: [top.png](top.png), [side.png](side.png).\n";
  return out.str();
}

std::string plan_json(const SensorPlan& p) {
  const SensorPlanInputs& in = p.inputs;
  const WorkingVolume& v = in.volume;
  auto point = [](const Eigen::Vector3d& q) { return Json::array({q.x(), q.y(), q.z()}); };
  auto region = [](const RegionCoverage& r) {
    return Json{{"name", r.name},   {"samples", r.samples},     {"all_percent", r.all},
                {"left_percent", r.left}, {"right_percent", r.right}, {"projector_percent", r.projector},
                {"cameras_percent", r.cameras}};
  };
  Json j;
  j["inputs"] = {{"baseline_mm", in.baseline_mm},
                 {"image_size", Json::array({in.width, in.height})},
                 {"pixel_um", in.pixel_um},
                 {"focal_px", p.rig.focal()},
                 {"focal_fitted", p.focal_fitted},
                 {"doffs_px", p.rig.doffs},
                 {"doffs_centred", p.doffs_centred},
                 {"projector_fov_deg", Json::array({in.projector_hfov_deg, in.projector_vfov_deg})},
                 {"projector_offset_mm", in.projector_offset_mm},
                 {"volume_mm", Json::array({v.width, v.height, v.depth})},
                 {"distance_mm", v.distance},
                 {"subpixel_px", in.subpixel_px},
                 {"target_dz_mm", in.target_dz_mm},
                 {"grid_mm", in.grid_mm}};
  const PinholeCamera& left = p.rig.left;
  const PinholeCamera& right = p.rig.right;
  j["camera"] = {{"focal_px", p.rig.focal()},   {"focal_mm", p.focal_mm},
                 {"hfov_deg", p.hfov_deg},       {"vfov_deg", p.vfov_deg},
                 {"fitting_focal_px", p.fitting_focal_px},
                 {"cx_left", left.cx},           {"cx_right", right.cx},
                 {"cy", left.cy}};
  const VolumeCoverage& c = p.coverage;
  Json coverage = region(c.volume);
  coverage["grid"] = Json::array({c.nx, c.ny, c.nz});
  coverage["faces"] = Json::array();
  for (const RegionCoverage& f : c.faces) coverage["faces"].push_back(region(f));
  coverage["slabs"] = Json::array();
  for (const RegionCoverage& s : c.slabs) coverage["slabs"].push_back(region(s));
  coverage["corners"] = Json::array();
  for (const CornerCoverage& k : c.corners) {
    coverage["corners"].push_back({{"name", k.name},
                                   {"point_mm", point(k.point)},
                                   {"left", (k.seen & kSeenByLeft) != 0},
                                   {"right", (k.seen & kSeenByRight) != 0},
                                   {"projector", (k.seen & kSeenByProjector) != 0}});
  }
  coverage["unseen_box_mm"] =
      c.any_unseen ? Json{{"min", point(c.unseen_min)}, {"max", point(c.unseen_max)}} : Json(nullptr);
  j["coverage"] = coverage;
  j["depth_resolution"] = {{"subpixel_px", in.subpixel_px},     {"near_z_mm", v.near_z()},
                           {"far_z_mm", v.far_z()},             {"dz_near_mm", p.dz_near_mm},
                           {"dz_far_mm", p.dz_far_mm},          {"pixel_near_mm", p.pixel_near_mm},
                           {"pixel_far_mm", p.pixel_far_mm}};
  j["disparity"] = {{"raw_near_px", p.raw_disparity_near}, {"raw_far_px", p.raw_disparity_far},
                    {"doffs_px", p.rig.doffs},          {"near_px", p.disparity_near},
                    {"far_px", p.disparity_far},           {"min_px", p.disparity_far},
                    {"max_px", p.disparity_near},          {"ndisp", p.ndisp},
                    {"matcher_shift_px", p.matcher_shift_px},
                    {"matcher_doffs_px", p.rig.doffs + p.matcher_shift_px}};
  j["target_dz"] = {{"target_dz_mm", in.target_dz_mm},
                    {"far_z_mm", v.far_z()},
                    {"subpixel_px_at_focal", p.subpixel_for_target},
                    {"focal_px_at_subpixel", p.focal_for_target_px},
                    {"focal_mm_at_subpixel", px_to_mm(p.focal_for_target_px, in.pixel_um)},
                    {"focal_px_at_1px", p.focal_for_target_1px},
                    {"focal_mm_at_1px", px_to_mm(p.focal_for_target_1px, in.pixel_um)},
                    {"footprint_focal_px", p.focal_for_lateral_target},
                    {"footprint_focal_mm", px_to_mm(p.focal_for_lateral_target, in.pixel_um)},
                    {"footprint_subpixel_px", p.subpixel_for_target_at_lateral}};
  return j.dump(2) + "\n";
}

}  // namespace flexsight

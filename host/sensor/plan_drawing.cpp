#include "host/sensor/plan_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace flexsight {
namespace {

constexpr double kPi = 3.14159265358979323846;
const cv::Scalar kWhite(255, 255, 255), kBlack(0, 0, 0), kGrey(190, 190, 190), kDarkGrey(90, 90, 90);
const cv::Scalar kGreen(0, 160, 0), kOrange(0, 140, 255), kRed(0, 0, 220);

// A frustum in the picture's plane: apex at (across, 0), edges z * slope_lo, z * slope_hi.
struct Frustum {
  double apex = 0.0, slope_lo = 0.0, slope_hi = 0.0;
  cv::Scalar colour;
};

struct Device {
  double across = 0.0;
  cv::Scalar colour;
  std::string label;
};

// Everything one view shows, in mm: `across` is x (top view) or y (side view).
struct View {
  std::string title, across_name;
  std::vector<Device> devices;
  std::vector<Frustum> frustums;
  double box_lo = 0.0, box_hi = 0.0, near_z = 0.0, far_z = 0.0;
  cv::Mat1f unseen;  // rows z (near first), columns across
};

// The working volume in `view`: lo..hi across, its depth range, and where no camera sees it.
void show_volume(View& view, double lo, double hi, const WorkingVolume& volume, const cv::Mat1f& unseen) {
  view.box_lo = lo;
  view.box_hi = hi;
  view.near_z = volume.near_z();
  view.far_z = volume.far_z();
  view.unseen = unseen;
}

cv::Mat draw(const View& view) {
  // The frustums are drawn a little past the far plane, so that their spread there shows.
  const double z_end = view.far_z * 1.12;
  double half = std::max(std::abs(view.box_lo), std::abs(view.box_hi));
  for (const Frustum& f : view.frustums) {
    half = std::max({half, std::abs(f.apex + z_end * f.slope_lo), std::abs(f.apex + z_end * f.slope_hi)});
  }
  for (const Device& d : view.devices) half = std::max(half, std::abs(d.across));
  half *= 1.05;
  const int width = 1000, margin = 50, legend = 70;
  const double scale = (width - 2.0 * margin) / (2.0 * half);  // px per mm
  const int height = static_cast<int>(std::ceil(z_end * scale)) + 2 * margin + legend;
  cv::Mat image(height, width, CV_8UC3, kWhite);
  auto at = [&](double across, double z) {
    return cv::Point(static_cast<int>(std::lround(width / 2.0 + across * scale)),
                     static_cast<int>(std::lround(margin + z * scale)));
  };

  // The volume, then its unseen share per column on top.
  cv::rectangle(image, at(view.box_lo, view.near_z), at(view.box_hi, view.far_z), kGrey, cv::FILLED);
  const int rows = view.unseen.rows, cols = view.unseen.cols;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float share = view.unseen(r, c);
      if (share <= 0.0f) continue;
      const double a0 = view.box_lo + (view.box_hi - view.box_lo) * c / cols;
      const double a1 = view.box_lo + (view.box_hi - view.box_lo) * (c + 1) / cols;
      const double z0 = view.near_z + (view.far_z - view.near_z) * r / rows;
      const double z1 = view.near_z + (view.far_z - view.near_z) * (r + 1) / rows;
      const double keep = 1.0 - 0.8 * std::min(1.0f, share) - 0.2;  // any unseen share shows
      const cv::Scalar colour = kRed * (1.0 - keep) + kGrey * keep;
      cv::rectangle(image, at(a0, z0), at(a1, z1), colour, cv::FILLED);
    }
  }
  cv::rectangle(image, at(view.box_lo, view.near_z), at(view.box_hi, view.far_z), kDarkGrey, 2);

  for (const Frustum& f : view.frustums) {
    cv::line(image, at(f.apex, 0.0), at(f.apex + z_end * f.slope_lo, z_end), f.colour, 2, cv::LINE_AA);
    cv::line(image, at(f.apex, 0.0), at(f.apex + z_end * f.slope_hi, z_end), f.colour, 2, cv::LINE_AA);
  }
  for (const Device& d : view.devices) {
    const cv::Point centre = at(d.across, 0.0);
    cv::rectangle(image, centre - cv::Point(14, 10), centre + cv::Point(14, 0), d.colour, cv::FILLED);
    cv::putText(image, d.label, centre + cv::Point(-14, -16), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1,
                cv::LINE_AA);
  }

  char text[160];
  std::snprintf(text, sizeof text, "near %.0f mm", view.near_z);
  cv::putText(image, text, at(view.box_hi, view.near_z) + cv::Point(8, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              kBlack, 1, cv::LINE_AA);
  std::snprintf(text, sizeof text, "far %.0f mm", view.far_z);
  cv::putText(image, text, at(view.box_hi, view.far_z) + cv::Point(8, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              kBlack, 1, cv::LINE_AA);

  // Title, legend and a 100 mm scale bar along the bottom.
  const int base = height - legend + 20;
  cv::putText(image, view.title, cv::Point(margin, base), cv::FONT_HERSHEY_SIMPLEX, 0.55, kBlack, 1,
              cv::LINE_AA);
  cv::putText(image, "green: camera frustums   orange: projector   grey: volume   red: not seen by all three",
              cv::Point(margin, base + 24), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1, cv::LINE_AA);
  const cv::Point bar(width - margin - static_cast<int>(std::lround(100.0 * scale)), base);
  cv::line(image, bar, cv::Point(width - margin, base), kBlack, 2);
  cv::putText(image, "100 mm", bar + cv::Point(0, -6), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1, cv::LINE_AA);
  return image;
}

double tan_half(double fov_deg) { return std::tan(fov_deg * kPi / 360.0); }

}  // namespace

cv::Mat draw_top_view(const StereoRig& rig, const WorkingVolume& volume, const VolumeCoverage& coverage) {
  View view;
  view.title = "top view (x across, z down)";
  view.across_name = "x";
  const double centres[2] = {rig.left_centre_x(), rig.right_centre_x()};
  const PinholeCamera* cameras[2] = {&rig.left, &rig.right};
  for (int i = 0; i < 2; ++i) {
    const PinholeCamera& cam = *cameras[i];
    view.frustums.push_back({centres[i], -cam.cx / cam.fx, (cam.width - cam.cx) / cam.fx, kGreen});
  }
  const double tp = tan_half(rig.projector.hfov_deg);
  view.frustums.push_back({rig.projector.centre_x, -tp, tp, kOrange});
  view.devices = {{-rig.baseline_mm / 2.0, kRed, "C1"},
                  {rig.baseline_mm / 2.0, kRed, "C2"},
                  {rig.projector.centre_x, kDarkGrey, "P"}};
  show_volume(view, volume.min_x(), volume.max_x(), volume, coverage.top_unseen);
  return draw(view);
}

cv::Mat draw_side_view(const StereoRig& rig, const WorkingVolume& volume, const VolumeCoverage& coverage) {
  View view;
  view.title = "side view (y across, z down; the cameras and the projector line up)";
  view.across_name = "y";
  const PinholeCamera& cam = rig.left;  // both cameras share their vertical frustum
  view.frustums.push_back({0.0, -cam.cy / cam.fx, (cam.height - cam.cy) / cam.fx, kGreen});
  const double tp = tan_half(rig.projector.vfov_deg);
  view.frustums.push_back({0.0, -tp, tp, kOrange});
  view.devices = {{0.0, kRed, "C1 C2 P"}};
  show_volume(view, volume.min_y(), volume.max_y(), volume, coverage.side_unseen);
  return draw(view);
}

}  // namespace flexsight

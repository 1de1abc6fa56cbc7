#include "host/sensor/volume_coverage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace flexsight {
namespace {

// Counts of a region's samples per device, turned into percentages at the end.
struct Tally {
  long long samples = 0, left = 0, right = 0, projector = 0, cameras = 0, all = 0;
  void add(unsigned seen) {
    ++samples;
    left += (seen & kSeenByLeft) != 0;
    right += (seen & kSeenByRight) != 0;
    projector += (seen & kSeenByProjector) != 0;
    cameras += (seen & (kSeenByLeft | kSeenByRight)) == (kSeenByLeft | kSeenByRight);
    all += seen == kSeenByAll;
  }
  RegionCoverage percent(const std::string& name) const {
    auto pct = [&](long long n) { return samples ? 100.0 * static_cast<double>(n) / samples : 0.0; };
    return {name, samples, pct(left), pct(right), pct(projector), pct(cameras), pct(all)};
  }
};

double cell_centre(double lo, double size, int cells, int i) { return lo + (i + 0.5) * size / cells; }

// One face of the box sampled on the grid of its two in-plane axes.
RegionCoverage face_coverage(const StereoRig& rig, const std::string& name, int na, int nb,
                             const std::function<Eigen::Vector3d(int, int)>& point) {
  Tally tally;
  for (int a = 0; a < na; ++a) {
    for (int b = 0; b < nb; ++b) tally.add(seen_by(rig, point(a, b)));
  }
  return tally.percent(name);
}

}  // namespace

unsigned seen_by(const StereoRig& rig, const Eigen::Vector3d& p) {
  return (camera_sees(rig.left, rig.left_centre_x(), p) ? kSeenByLeft : 0u) |
         (camera_sees(rig.right, rig.right_centre_x(), p) ? kSeenByRight : 0u) |
         (rig.projector.sees(p) ? kSeenByProjector : 0u);
}

long long cells_along(double size_mm, double step_mm) {
  return std::max(1LL, static_cast<long long>(std::ceil(size_mm / step_mm - 1e-9)));
}

VolumeCoverage measure_coverage(const StereoRig& rig, const WorkingVolume& volume, double step_mm,
                                int slab_count) {
  VolumeCoverage out;
  out.step_mm = step_mm;
  out.nx = static_cast<int>(cells_along(volume.width, step_mm));
  out.ny = static_cast<int>(cells_along(volume.height, step_mm));
  out.nz = static_cast<int>(cells_along(volume.depth, step_mm));
  const int nx = out.nx, ny = out.ny, nz = out.nz;
  auto x_at = [&](int i) { return cell_centre(volume.min_x(), volume.width, nx, i); };
  auto y_at = [&](int i) { return cell_centre(volume.min_y(), volume.height, ny, i); };
  auto z_at = [&](int i) { return cell_centre(volume.near_z(), volume.depth, nz, i); };

  Tally whole;
  std::vector<Tally> slabs(slab_count);
  out.top_unseen = cv::Mat1f(nz, nx, 0.0f);
  out.side_unseen = cv::Mat1f(nz, ny, 0.0f);
  out.unseen_min = {1e300, 1e300, 1e300};
  out.unseen_max = {-1e300, -1e300, -1e300};
  for (int k = 0; k < nz; ++k) {
    Tally& slab = slabs[std::min(slab_count - 1, k * slab_count / nz)];
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const Eigen::Vector3d p(x_at(i), y_at(j), z_at(k));
        const unsigned seen = seen_by(rig, p);
        whole.add(seen);
        slab.add(seen);
        if (seen == kSeenByAll) continue;
        out.top_unseen(k, i) += 1.0f / ny;
        out.side_unseen(k, j) += 1.0f / nx;
        out.any_unseen = true;
        out.unseen_min = {std::min(out.unseen_min.x(), p.x()), std::min(out.unseen_min.y(), p.y()),
                          std::min(out.unseen_min.z(), p.z())};
        out.unseen_max = {std::max(out.unseen_max.x(), p.x()), std::max(out.unseen_max.y(), p.y()),
                          std::max(out.unseen_max.z(), p.z())};
      }
    }
  }
  out.volume = whole.percent("volume");
  for (int s = 0; s < slab_count; ++s) {
    const double z0 = volume.near_z() + volume.depth * s / slab_count;
    const double z1 = volume.near_z() + volume.depth * (s + 1) / slab_count;
    char name[64];
    std::snprintf(name, sizeof name, "z %.0f..%.0f", z0, z1);
    out.slabs.push_back(slabs[s].percent(name));
  }

  // The faces lie on the box's planes themselves, where coverage is lost first.
  out.faces.push_back(face_coverage(rig, "near", nx, ny, [&](int a, int b) {
    return Eigen::Vector3d{x_at(a), y_at(b), volume.near_z()};
  }));
  out.faces.push_back(face_coverage(rig, "far", nx, ny, [&](int a, int b) {
    return Eigen::Vector3d{x_at(a), y_at(b), volume.far_z()};
  }));
  out.faces.push_back(face_coverage(rig, "left", ny, nz, [&](int a, int b) {
    return Eigen::Vector3d{volume.min_x(), y_at(a), z_at(b)};
  }));
  out.faces.push_back(face_coverage(rig, "right", ny, nz, [&](int a, int b) {
    return Eigen::Vector3d{volume.max_x(), y_at(a), z_at(b)};
  }));
  out.faces.push_back(face_coverage(rig, "top", nx, nz, [&](int a, int b) {
    return Eigen::Vector3d{x_at(a), volume.min_y(), z_at(b)};
  }));
  out.faces.push_back(face_coverage(rig, "bottom", nx, nz, [&](int a, int b) {
    return Eigen::Vector3d{x_at(a), volume.max_y(), z_at(b)};
  }));

  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p = volume.corner(c);
    const std::string name = std::string((c & 4) ? "far" : "near") + ((c & 2) ? " bottom" : " top") +
                             ((c & 1) ? " right" : " left");
    out.corners[c] = {name, p, seen_by(rig, p)};
  }
  return out;
}

}  // namespace flexsight

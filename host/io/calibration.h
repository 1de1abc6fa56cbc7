#pragma once
// Calibration files of the stereo benchmarks.
#include <array>
#include <optional>
#include <string>

namespace flexsight {

// A pattern projector as a third (inverse) camera, in optional calib.txt lines of the
// same key=value form (docs/projector.md):
//   proj=[fp 0 cx; 0 fp cy; 0 0 1]   pinhole intrinsics of the pattern image (px)
//   projwidth=W  projheight=H        the pattern image's size
//   projR=[3x3]  projt=[tx ty tz]    x_proj = R x_cam0 + t (mm; projR optional, identity)
//   projpattern=FILE                 the pattern image, relative to the calib file
struct ProjectorCalib {
  std::array<double, 9> K{};
  int width = 0, height = 0;
  std::array<double, 9> R{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 3> t{};
  std::string pattern;       // as written in the file
  std::string pattern_path;  // resolved against the calib file's folder (reading only)
};

// The projector's lines as read_middlebury_calib reads them back (\n-terminated).
std::string projector_calib_text(const ProjectorCalib& projector);

// A calib.txt's text without its projector lines (proj*), e.g. to give it another projector.
std::string calib_text_without_projector(const std::string& path);

// Middlebury 2014 calib.txt: cam0=[f 0 cx; 0 f cy; 0 0 1], cam1=..., doffs, baseline
// (mm), width, height, ndisp, and optionally isint, vmin, vmax, dyavg, dymax.
struct MiddleburyCalib {
  std::array<double, 9> cam0{};
  std::array<double, 9> cam1{};
  double doffs = 0;
  double baseline_mm = 0;
  int width = 0;
  int height = 0;
  int ndisp = 0;
  int vmin = -1;  // -1 when absent
  int vmax = -1;
  std::optional<ProjectorCalib> projector;  // when the file has the proj* lines
};

// Throws InputError naming the file and the key for a missing file, a missing
// required key (cam0, cam1, doffs, baseline, width, height, ndisp), a malformed
// matrix or number, or impossible values (ndisp <= 0, width/height <= 0, f <= 0);
// and, once any proj* key is there, for a missing one, a principal point outside the
// pattern, a projR that is not a rotation, a missing or unreadable pattern file or one
// whose size is not projwidth x projheight.
MiddleburyCalib read_middlebury_calib(const std::string& path);

// KITTI 2012 (P0..P3) / 2015 (P_rect_02 ...) calibration: 3x4 projection matrices.
struct KittiCalib {
  std::array<double, 12> P0{};  // left gray camera, rectified
  std::array<double, 12> P1{};  // right gray camera, rectified
  double focal_px() const { return P0[0]; }
  // Baseline in metres from P1 = [f 0 cx -f*B; ...].
  double baseline_m() const { return -P1[3] / P1[0]; }
};

// Reads "P0: 12 numbers" and "P1: ..." lines (also accepts P_rect_00/01 names).
// Throws InputError for a missing file, missing P0/P1 or a line without 12 numbers.
KittiCalib read_kitti_calib(const std::string& path);

}  // namespace flexsight

// Pick's stereo plans on one bin (docs/pick.md, "Stereo where it matters"), timed and
// written for scripts/pick/stereo_plan_report.py to score against the ground truth:
//   flexsight_bench_stereo_plan BIN_DIR OUT_DIR [--boxes BOXES.txt] [--plans a,b,...]
// BIN_DIR holds im0.png, im1.png and calib.txt (MiddEval3 layout); the active preset is
// used, as pick does. Each plan writes OUT_DIR/<plan>.pfm and one line of OUT_DIR/times.tsv
// (plan, wall seconds of the plan alone and with the boxes, CPU seconds,
// the bin's rectangle and range). Plans: full1, full2, full4 (the whole pair at 1/N), roi1, roi2, roi4
// (the bin's region at 1/N), and with --boxes (one "x y w h diameter" a line, full-size pixels and mm)
// refine4: roi4, then every box matched again at full size (refine_pick_box; a fifth
// column: the part's diameter, mm),
// each box's time in OUT_DIR/boxes.tsv; --refine-preset P (default active) and
// --refine-coarsest W (BoxRefinement::coarsest_width) set the refinement's matcher,
// --region-coarsest W (BinRegionPlan::coarsest_width) the roi plans'.
#include <sys/resource.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "host/geometry/stereo_camera.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/pfm.h"
#include "host/pick/pick_stereo.h"
#include "host/pick/stereo_region.h"

using namespace flexsight;

namespace {

double seconds_of(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The process's CPU seconds (every thread): on a shared machine the wall time follows the
// other jobs' load, the CPU time much less.
double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

struct Box {
  cv::Rect rect;
  double diameter_mm = 0.0;
};

std::vector<Box> read_boxes(const std::string& path) {
  std::vector<Box> boxes;
  std::ifstream in(path);
  int x, y, w, h;
  double diameter;
  while (in >> x >> y >> w >> h >> diameter) boxes.push_back({cv::Rect(x, y, w, h), diameter});
  return boxes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: flexsight_bench_stereo_plan BIN_DIR OUT_DIR [--boxes BOXES.txt] [--plans a,b]\n";
    return 1;
  }
  const std::string bin = argv[1], out = argv[2];
  BoxRefinement refinement;
  BinRegionPlan bin_plan;
  std::string refine_preset = "active";
  std::string boxes_path, plans = "full1,full2,full4,roi1,roi2,roi4";
  for (int i = 3; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--boxes") boxes_path = argv[i + 1];
    if (std::string(argv[i]) == "--plans") plans = argv[i + 1];
    if (std::string(argv[i]) == "--refine-preset") refine_preset = argv[i + 1];
    if (std::string(argv[i]) == "--refine-coarsest") refinement.coarsest_width = std::stoi(argv[i + 1]);
    if (std::string(argv[i]) == "--region-coarsest") bin_plan.coarsest_width = std::stoi(argv[i + 1]);
  }
  const cv::Mat left = load_rgb8(bin + "/im0.png"), right = load_rgb8(bin + "/im1.png");
  const StereoCamera rig = read_stereo_camera(bin + "/calib.txt");
  StereoParams params;
  apply_stereo_preset("active", params);
  params.ndisp = read_middlebury_calib(bin + "/calib.txt").ndisp;
  StereoBackend stereo{BackendOptions()};
  stereo.run(left(cv::Rect(0, 0, 256, 192)), right(cv::Rect(0, 0, 256, 192)), params);  // kernels built

  std::ofstream times(out + "/times.tsv");
  std::stringstream list(plans);
  for (std::string plan; std::getline(list, plan, ',');) {
    const int scale = std::stoi(plan.substr(plan.find_first_of("0123456789")));
    const bool roi = plan.rfind("roi", 0) == 0 || plan.rfind("refine", 0) == 0;
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = cpu_seconds();
    PickDisparity result = pick_disparity(stereo, left, right, rig, params,
                                          roi ? StereoPlan::kBinRegion : StereoPlan::kFull, scale, {},
                                          nullptr, bin_plan);
    const double coarse = seconds_of(start);
    if (plan.rfind("refine", 0) == 0) {
      StereoParams refine_params = params;
      apply_stereo_preset(refine_preset, refine_params);
      std::ofstream box_times(out + "/boxes.tsv");
      for (const Box& part : read_boxes(boxes_path)) {
        const cv::Rect& box = part.rect;
        const auto box_start = std::chrono::steady_clock::now();
        const double box_cpu = cpu_seconds();
        cv::Mat depth_mm(result.disparity.size(), CV_32FC1, cv::Scalar(0));
        const RegionCrop crop = refine_pick_box(stereo, left, right, rig.resized_to(left.cols, left.rows), refine_params,
                                                box, part.diameter_mm, result.disparity, depth_mm, refinement);
        box_times << box.x << "\t" << box.y << "\t" << box.width << "\t" << box.height << "\t"
                  << crop.left.width << "x" << crop.left.height << "\t" << crop.ndisp << "\t" << seconds_of(box_start)
                  << "\t" << cpu_seconds() - box_cpu << "\n";
      }
    }
    times << plan << "\t" << coarse << "\t" << seconds_of(start) << "\t" << cpu_seconds() - cpu_start << "\t" << result.region.rect.x << ","
          << result.region.rect.y << "," << result.region.rect.width << "," << result.region.rect.height << "\t"
          << result.region.range.min << "," << result.region.range.max << "\n";
    times.flush();
    write_pfm(out + "/" + plan + ".pfm", result.disparity);
    std::cerr << plan << " " << seconds_of(start) << " s\n";
  }
  return 0;
}

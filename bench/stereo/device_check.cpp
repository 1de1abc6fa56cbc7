// flexsight_device_check: the matcher on an OpenCL device (a GPU when one is lent),
// timed end to end and compared byte for byte with the reference path on the same
// machine. Made for a machine that has no OpenCV codecs and no apt: it links only
// OpenCV's core, reads binary PPM (P6) pairs and writes PFM, so that
// scripts/stereo/device_bundle.sh can carry it with the few libraries it needs.
//
// usage: flexsight_device_check MANIFEST OUT_DIR [--repeat N] [--reference 0|1]
//                               [--cl-platform SEL] [--cl-device SEL] [--profile]
//                               [--preset accurate|fast|active] [--cl-build-options "OPTS"]
// MANIFEST: one scene a line, "NAME LEFT.ppm RIGHT.ppm NDISP" (paths relative to the
// manifest's folder). Writes OUT_DIR/NAME.pfm (OpenCL result) and a Markdown table on
// stdout: per scene the median and fastest end-to-end time of `repeat` runs (upload,
// every level, post-processing, download) after one untimed warm-up run, the
// reference path's time and whether both gave the same bytes. Exit code 1 when any
// scene's bytes differ or an input is bad.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/runtime/cl_program.h"
#include "host/stereo/opencl_matcher.h"
#include "host/stereo/stereo_pipeline.h"

namespace {

using flexsight::InputError;

// Binary PPM with maxval 255, as scripts/stereo/device_bundle.sh writes it; RGB order.
cv::Mat read_ppm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open");
  std::string magic;
  int width = 0, height = 0, maxval = 0;
  in >> magic >> width >> height >> maxval;
  if (magic != "P6" || width <= 0 || height <= 0 || maxval != 255) {
    throw InputError(path, "not an 8-bit binary PPM (P6, maxval 255)");
  }
  in.get();  // the single whitespace after maxval
  cv::Mat rgb(height, width, CV_8UC3);
  in.read(reinterpret_cast<char*>(rgb.data), static_cast<std::streamsize>(rgb.total() * 3));
  if (in.gcount() != static_cast<std::streamsize>(rgb.total() * 3)) {
    throw InputError(path, "truncated pixel data");
  }
  return rgb;
}

struct Scene {
  std::string name, left, right;
  int ndisp = 0;
};

std::vector<Scene> read_manifest(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open");
  const std::string folder = path.find('/') == std::string::npos
                                 ? std::string(".")
                                 : path.substr(0, path.find_last_of('/'));
  std::vector<Scene> scenes;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Scene s;
    if (!(fields >> s.name >> s.left >> s.right >> s.ndisp) || s.ndisp <= 0) {
      throw InputError(path, "bad line '" + line + "' (want NAME LEFT RIGHT NDISP)");
    }
    s.left = folder + "/" + s.left;
    s.right = folder + "/" + s.right;
    scenes.push_back(s);
  }
  if (scenes.empty()) throw InputError(path, "no scenes");
  return scenes;
}

bool same_bytes(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

int run(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: flexsight_device_check MANIFEST OUT_DIR [--repeat N] "
                 "[--reference 0|1] [--cl-platform SEL] [--cl-device SEL] [--profile] "
                 "[--preset accurate|fast|active] [--cl-build-options \"OPTS\"]\n";
    return 1;
  }
  const std::string manifest = argv[1];
  const std::string out_dir = argv[2];
  int repeat = 5;
  bool reference = true;
  flexsight::opencl::OpenClOptions options;
  flexsight::StereoParams params;  // the defaults, as `flexsight stereo` uses them
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--repeat" && has_value) {
      const std::string value = argv[++i];
      const bool digits = value.find_first_not_of("0123456789") == std::string::npos;
      if (value.empty() || value.size() > 6 || !digits) {
        throw InputError("--repeat", "expected a whole number, got '" + value + "'");
      }
      repeat = std::stoi(value);
    } else if (arg == "--reference" && has_value) {
      reference = std::string(argv[++i]) != "0";
    } else if (arg == "--cl-platform" && has_value) {
      options.cl_platform = argv[++i];
    } else if (arg == "--cl-device" && has_value) {
      options.cl_device = argv[++i];
    } else if (arg == "--profile") {
      options.profile = true;
    } else if (arg == "--cl-build-options" && has_value) {
      // e.g. -cl-nv-maxrregcount=64 on NVIDIA; options that change the bytes are refused
      options.cl_build_options = argv[++i];
      const std::string inexact = flexsight::opencl::inexact_build_option(options.cl_build_options);
      if (!inexact.empty()) throw InputError("--cl-build-options", inexact);
    } else if (arg == "--preset" && has_value) {
      const std::string name = argv[++i];
      if (!flexsight::apply_stereo_preset(name, params)) {
        throw InputError("--preset", std::string("expected one of ") +
                                         flexsight::stereo_preset_names() + ", got '" + name + "'");
      }
    } else {
      throw InputError(arg, "unknown option or missing value");
    }
  }
  if (repeat < 1) throw InputError("--repeat", "must be at least 1");
  const std::vector<Scene> scenes = read_manifest(manifest);

  const auto build_start = std::chrono::steady_clock::now();
  flexsight::opencl::OpenClMatcher matcher(options);
  const double build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
  std::cout << "device: " << matcher.device_description() << "\n"
            << "kernel build: " << build_s << " s\n\n"
            << "| scene | size | ndisp | OpenCL median (ms) | OpenCL fastest (ms) | runs | "
               "reference (s) | same bytes |\n|---|---|---:|---:|---:|---:|---:|---|\n";
  bool all_same = true;
  std::vector<double> medians;
  for (const Scene& s : scenes) {
    const cv::Mat left = read_ppm(s.left);
    const cv::Mat right = read_ppm(s.right);
    if (left.size() != right.size()) throw InputError(s.right, "size differs from the left");
    params.ndisp = s.ndisp;
    std::vector<double> ms;
    // One untimed run first: it builds the kernels specialised for this scene's sizes
    // (the median's window) and warms the device's clocks and caches.
    flexsight::StereoResult result = matcher.run(left, right, params);
    for (int r = 0; r < repeat; ++r) {
      const auto start = std::chrono::steady_clock::now();
      result = matcher.run(left, right, params);
      ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count());
    }
    flexsight::write_pfm(out_dir + "/" + s.name + ".pfm", result.disparity);
    std::string reference_s = "-", same = "not checked";
    if (reference) {
      const auto start = std::chrono::steady_clock::now();
      const flexsight::StereoResult expected = flexsight::run_stereo(left, right, params);
      reference_s = std::to_string(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      const bool ok = same_bytes(result.disparity, expected.disparity) &&
                      same_bytes(result.raw_left, expected.raw_left) &&
                      same_bytes(result.raw_right, expected.raw_right);
      all_same = all_same && ok;
      same = ok ? "yes" : "NO";
    }
    medians.push_back(median(ms));
    std::cout << "| " << s.name << " | " << left.cols << "x" << left.rows << " | " << s.ndisp
              << " | " << median(ms) << " | " << *std::min_element(ms.begin(), ms.end())
              << " | " << repeat << " | " << reference_s << " | " << same << " |\n"
              << std::flush;
    if (options.profile) {
      for (const auto& k : matcher.kernel_timings()) {
        std::cout << "|   " << k.kernel << " | | | " << 1e3 * k.seconds << " (device) | | "
                  << k.launches << " | | |\n";
      }
    }
  }
  double sum = 0;
  for (double m : medians) sum += m;
  std::cout << "| **mean of medians** | | | " << sum / medians.size() << " | | | | "
            << (!reference ? "not checked" : all_same ? "all yes" : "SOME DIFFER") << " |\n";
  return all_same ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "flexsight_device_check: " << e.what() << "\n";
    return 1;
  }
}

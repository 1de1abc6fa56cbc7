// flexsight pose IMAGE ...: the parts in one image, each in its box (a detections
// file), with the image's depth (a depth PFM in mm, or a disparity PFM and the stereo
// calibration). Everything is read and checked before the first pose.
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "host/cli/arguments.h"
#include "host/cli/pose_image_form.h"
#include "host/dataset/bop_pose_results.h"
#include "host/dataset/dataset_files.h"
#include "host/geometry/depth_from_disparity.h"
#include "host/geometry/stereo_camera.h"
#include "host/io/atomic_file.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/pfm.h"
#include "host/pose/pose_drawing.h"
#include "host/geometry/stereo_rig.h"
#include "host/pose/pose_models.h"

namespace flexsight {
namespace {

using dataset_files::Json;
using dataset_files::read_json;

struct BoxInput {
  int obj_id = 0;
  double score = 0.0;
  cv::Rect box;
};

// COCO detection results (flexsight detect's output): category_id is the object id.
std::vector<BoxInput> read_boxes(const std::string& path, double min_score, const cv::Size& image,
                                 const PoseModels& models) {
  const Json json = read_json(path);
  if (!json.is_array()) throw InputError(path, "expected a JSON list of detections {category_id, bbox, score}");
  std::vector<BoxInput> boxes;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const Json& d = json[i];
    const std::string where = path + ": detection " + std::to_string(i);
    if (!d.is_object() || !d.contains("category_id") || !d.contains("bbox") || !d["bbox"].is_array() ||
        d["bbox"].size() != 4 || !d["category_id"].is_number_integer()) {
      throw InputError(where, "needs an integer category_id and a bbox [x, y, width, height]");
    }
    BoxInput b;
    b.obj_id = d["category_id"].get<int>();
    b.score = d.contains("score") && d["score"].is_number() ? d["score"].get<double>() : 1.0;
    if (b.score < min_score) continue;
    double v[4];
    for (int k = 0; k < 4; ++k) {
      if (!d["bbox"][k].is_number() || !std::isfinite(d["bbox"][k].get<double>())) throw InputError(where, "bbox holds a value that is not a number");
      v[k] = d["bbox"][k].get<double>();
    }
    b.box = cv::Rect(static_cast<int>(std::floor(v[0])), static_cast<int>(std::floor(v[1])),
                     static_cast<int>(std::ceil(v[0] + v[2]) - std::floor(v[0])),
                     static_cast<int>(std::ceil(v[1] + v[3]) - std::floor(v[1])));
    if (!(v[2] > 0.0 && v[3] > 0.0)) throw InputError(where, "the box is empty");
    if ((b.box & cv::Rect(cv::Point(), image)) != b.box) {
      throw InputError(where, "the box is not inside the " + std::to_string(image.width) + " x " +
                                  std::to_string(image.height) + " image");
    }
    models.model(b.obj_id, where);
    boxes.push_back(b);
  }
  return boxes;
}

struct PoseImageOptions {
  std::string depth_path, disparity_path, calib_path, boxes_path, templates, output, csv, png;
  double min_score = 0.3;
};

PoseImageOptions parse_pose_image_options(std::vector<std::string>& args) {
  PoseImageOptions o;
  take_options(args, {{"--depth", &o.depth_path},
                      {"--disparity", &o.disparity_path},
                      {"--calib", &o.calib_path},
                      {"--boxes", &o.boxes_path},
                      {"--templates", &o.templates},
                      {"-o", &o.output},
                      {"--csv", &o.csv},
                      {"--png", &o.png}});
  o.min_score = take_number_option(args, "--score", 0.3);
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("pose", "unexpected argument '" + args[0] + "'");
  if (o.templates.empty()) throw InputError("option --templates", "missing (make them with flexsight pose-templates CAD_DIR -o FILE)");
  if (o.calib_path.empty()) throw InputError("option --calib", "missing: the camera (Middlebury, KITTI or OpenCV stereo calibration)");
  if (o.boxes_path.empty()) throw InputError("option --boxes", "missing: the detections (flexsight detect -o DETS.json)");
  if (o.depth_path.empty() == o.disparity_path.empty()) throw InputError("option --depth / --disparity", "give exactly one");
  if (o.output.empty()) throw InputError("option -o", "missing: the poses JSON to write");
  if (!(o.min_score >= 0.0 && o.min_score <= 1.0)) throw InputError("option --score", "must be in [0, 1]");
  for (const std::string& path : {o.output, o.csv, o.png}) check_output_file(path);
  return o;
}

struct PosedBoxes {
  std::vector<PoseEstimateRecord> records;
  std::vector<PosedPart> drawn;
  dataset_files::Json poses = dataset_files::Json::array();  // the poses JSON
};

// Each box posed in turn, a line per part on stdout.
PosedBoxes pose_boxes(const std::vector<BoxInput>& boxes, const PoseModels& models, const std::string& boxes_path,
                      const cv::Mat& bgr, const cv::Mat& depth, const PinholeCamera& camera,
                      const PoseEstimatorParams& params) {
  PosedBoxes posed;
  std::vector<PoseEstimateRecord>& records = posed.records;
  std::vector<PosedPart>& drawn = posed.drawn;
  dataset_files::Json& poses = posed.poses;
  PoseEstimator estimator(params);
  for (const BoxInput& b : boxes) {
    const PoseModel& model = models.model(b.obj_id, boxes_path);
    const PoseEstimate e = estimator.estimate(model, bgr, depth, camera, b.box);
    PoseEstimateRecord r = pose_estimate_record(0, 0, b.obj_id, e.score, e.pose.R, e.pose.t);
    r.time_s = e.times.total_ms() / 1000.0;
    records.push_back(r);
    dataset_files::Json R = dataset_files::Json::array(), t = dataset_files::Json::array();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) R.push_back(e.pose.R(i, j));
      t.push_back(e.pose.t(i));
    }
    poses.push_back({{"obj_id", b.obj_id},
                     {"score", e.score},
                     {"detection_score", b.score},
                     {"box", {b.box.x, b.box.y, b.box.width, b.box.height}},
                     {"R", R},
                     {"t_mm", t},
                     {"edge_cost_px", e.edge_cost},
                     {"depth_fit", e.depth_fit},
                     {"ms", {{"edges", e.times.edges_ms}, {"search", e.times.search_ms}, {"refine", e.times.refine_ms},
                             {"icp", e.times.icp_ms}, {"score", e.times.score_ms}}}});
    std::ostringstream label;
    label << "obj " << b.obj_id << " " << std::fixed << std::setprecision(2) << e.score;
    drawn.push_back({model.mesh, e.pose, cv::Scalar(0, 140, 255), label.str()});
    std::cout << "obj " << b.obj_id << ": score " << std::fixed << std::setprecision(3) << e.score << ", t = ("
              << std::setprecision(1) << e.pose.t.x() << ", " << e.pose.t.y() << ", " << e.pose.t.z() << ") mm, "
              << e.times.total_ms() << " ms\n";
  }
  return posed;
}

}  // namespace

int run_pose_image_form(const std::string& image_path, std::vector<std::string>& args,
                        const std::string& cad_dir, const PoseEstimatorParams& params) {
  const PoseImageOptions options = parse_pose_image_options(args);
  const std::string& depth_path = options.depth_path;
  const std::string& disparity_path = options.disparity_path;
  const std::string& calib_path = options.calib_path;
  const std::string& boxes_path = options.boxes_path;
  const std::string& output = options.output;
  const std::string& templates = options.templates;
  const std::string& csv = options.csv;
  const std::string& png = options.png;
  const double min_score = options.min_score;
  const cv::Mat rgb = load_rgb8(image_path);
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  const StereoCamera rig = read_stereo_camera(calib_path);
  if (rig.width > 0 && (rig.width != bgr.cols || rig.height != bgr.rows)) {
    throw InputError(calib_path, "is for " + std::to_string(rig.width) + " x " + std::to_string(rig.height) +
                                     " images, " + image_path + " is " + std::to_string(bgr.cols) + " x " +
                                     std::to_string(bgr.rows));
  }
  const PinholeCamera camera = stereo_rig_from(rig, bgr.cols, bgr.rows).left;
  const std::string depth_source = depth_path.empty() ? disparity_path : depth_path;
  const cv::Mat input = read_pfm(depth_source);
  if (input.size() != bgr.size()) {
    throw InputError(depth_source, "is " + std::to_string(input.cols) + " x " + std::to_string(input.rows) +
                                       ", the image " + std::to_string(bgr.cols) + " x " + std::to_string(bgr.rows));
  }
  cv::Mat depth(bgr.size(), CV_32FC1, cv::Scalar(0));
  if (depth_path.empty()) {
    depth = depth_from_disparity(input, rig, 1e-3, DepthRule::pose_input());
  } else {
    for (int y = 0; y < depth.rows; ++y) {
      for (int x = 0; x < depth.cols; ++x) {
        const float v = input.at<float>(y, x);
        if (std::isfinite(v) && v > 0.0f) depth.at<float>(y, x) = v;
      }
    }
  }
  const PoseModels models(templates, cad_dir);
  const std::vector<BoxInput> boxes = read_boxes(boxes_path, min_score, bgr.size(), models);

  const PosedBoxes posed = pose_boxes(boxes, models, boxes_path, bgr, depth, camera, params);
  const std::vector<PoseEstimateRecord>& records = posed.records;
  const dataset_files::Json& poses = posed.poses;
  write_atomically(output, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << poses.dump(1) << "\n";
    if (!out) throw InputError(output, "cannot be written (" + std::string(std::strerror(errno)) + ")");
  });
  if (!csv.empty()) write_bop_pose_results(csv, records);
  if (!png.empty()) {
    draw_posed_parts(bgr, posed.drawn, camera);
    write_atomically(png, [&](const std::string& tmp) {
      if (!cv::imwrite(tmp + ".png", bgr)) throw InputError(png, "cannot be written: OpenCV could not encode or save it");
      std::filesystem::rename(tmp + ".png", tmp);
    });
  }
  std::cout << "pose: " << records.size() << " parts -> " << output << "\n";
  return 0;
}

}  // namespace flexsight

#include "host/cli/pose_outputs.h"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <opencv2/imgproc.hpp>

#include "host/dataset/dataset_files.h"
#include "host/pose/pose_drawing.h"

namespace flexsight {
namespace {

constexpr int kPictureImages = 12;

// The first images with the ground truth's outlines (green) and the estimates' (orange),
// tiled 4 wide at a third of their size... or full size when there are few.
void write_picture(const std::string& path, const BopReader& reader, std::size_t image_count,
                   const std::vector<PoseEstimateRecord>& records, const PoseModels& models, double min_visib) {
  std::vector<cv::Mat> tiles;
  for (std::size_t i = 0; i < std::min<std::size_t>(image_count, kPictureImages); ++i) {
    const AnnotatedImage image = reader.load(i);
    cv::Mat bgr;
    cv::cvtColor(image.rgb, bgr, cv::COLOR_RGB2BGR);
    const PinholeCamera camera = camera_of(image);
    std::vector<PosedPart> parts;
    for (const PartAnnotation& part : image.parts) {
      if (part.visib_fract < min_visib || !models.has(part.obj_id)) continue;
      Pose pose;
      pose.R = part.cam_R_m2c;
      pose.t = part.cam_t_m2c;
      parts.push_back({models.model(part.obj_id, "").mesh, pose, cv::Scalar(80, 220, 80), ""});
    }
    for (const PoseEstimateRecord& record : records) {
      if (record.scene_id != image.scene_id || record.im_id != image.im_id) continue;
      Pose pose;
      pose.R = record.R;
      pose.t = record.t;
      std::ostringstream label;
      label << "obj " << record.obj_id << " " << std::fixed << std::setprecision(2) << record.score;
      parts.push_back({models.model(record.obj_id, "").mesh, pose, cv::Scalar(0, 140, 255), label.str()});
    }
    draw_posed_parts(bgr, parts, camera);
    tiles.push_back(bgr);
  }
  if (tiles.empty()) return;
  const int columns = std::min<int>(4, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  const cv::Size tile(tiles[0].cols / 2, tiles[0].rows / 2);
  cv::Mat sheet(rows * tile.height, columns * tile.width, CV_8UC3, cv::Scalar(32, 32, 32));
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    cv::Mat small;
    cv::resize(tiles[k], small, tile, 0, 0, cv::INTER_AREA);
    small.copyTo(sheet(cv::Rect(static_cast<int>(k % columns) * tile.width,
                                static_cast<int>(k / columns) * tile.height, tile.width, tile.height)));
  }
  cv::imwrite(path, sheet, {cv::IMWRITE_JPEG_QUALITY, 90});
}

}  // namespace

void write_pose_dataset_outputs(const std::string& folder, const BopReader& reader, std::size_t image_count,
                                const std::vector<PoseEstimateRecord>& records, const PoseRunTiming& timing,
                                const PoseReport& report, const PoseModels& models) {
  write_bop_pose_results(folder + "/poses.csv", records);
  write_picture(folder + "/poses.jpg", reader, image_count, records, models, report.settings.min_visib_fract);
  const auto stages = median_stage_times(timing.stages);
  const double wall_ms_per_part = records.empty() ? 0.0 : 1000.0 * timing.wall_s / records.size();

  nlohmann::ordered_json json = nlohmann::ordered_json::parse(to_json(report));
  nlohmann::ordered_json times = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : stages) times[stage] = ms;
  json["median_ms_per_part"] = times;
  json["parts_posed"] = records.size();
  json["threads"] = timing.threads;
  json["wall_ms_per_part"] = wall_ms_per_part;
  dataset_files::write_text(folder + "/report.json", json.dump(2) + "\n");

  std::ostringstream md;
  md << "# Poses of the ground-truth boxes of " << report.dataset << "\n\n"
     << records.size() << " parts in " << image_count << " images, " << timing.threads
     << " at once: " << std::fixed << std::setprecision(1) << wall_ms_per_part
     << " ms per part (wall time / parts).\n\n"
     << "| stage | median ms per part (one thread each) |\n|---|---|\n";
  for (const auto& [stage, ms] : stages) md << "| " << stage << " | " << ms << " |\n";
  md << "\n" << to_markdown(report);
  dataset_files::write_text(folder + "/report.md", md.str());
  std::cout << "median ms per part:";
  for (const auto& [stage, ms] : stages) std::cout << " " << stage << " " << std::fixed << std::setprecision(1) << ms;
  std::cout << "; " << wall_ms_per_part << " ms per part with " << timing.threads << " threads\n";
}

}  // namespace flexsight

#include "host/pick/depth_proposals.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

namespace flexsight {
namespace {

cv::Rect2d box_of(const ObjectDetection& d) { return {d.box[0], d.box[1], d.box[2] - d.box[0], d.box[3] - d.box[1]}; }

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter <= 0.0 ? 0.0 : inter / (a.area() + b.area() - inter);
}

}  // namespace

std::vector<ObjectDetection> region_proposals(const DepthRegion& region, const std::vector<ObjectDetection>& detections,
                                              const std::vector<ProposalClass>& classes, int classes_per_box) {
  const cv::Rect2d box(region.box);
  // Each class's best detection overlapping the region.
  std::map<int, ObjectDetection> best;
  for (const ObjectDetection& d : detections) {
    const cv::Rect2d b = box_of(d);
    const double inter = (b & box).area();
    if (inter < kClassOverlap * std::min(b.area(), box.area())) continue;
    auto it = best.find(d.category_id);
    if (it == best.end() || d.score > it->second.score) best[d.category_id] = d;
  }
  std::vector<ObjectDetection> named;
  for (const auto& [category, d] : best) named.push_back(d);
  std::stable_sort(named.begin(), named.end(),
                   [](const ObjectDetection& a, const ObjectDetection& b) { return a.score > b.score; });
  if (named.empty()) {
    // Nothing detected there: the parts of the region's size.
    std::vector<ProposalClass> by_size = classes;
    std::stable_sort(by_size.begin(), by_size.end(), [&](const ProposalClass& a, const ProposalClass& b) {
      return std::abs(a.diameter_mm - region.extent_mm) < std::abs(b.diameter_mm - region.extent_mm);
    });
    for (const ProposalClass& c : by_size) {
      ObjectDetection d;
      d.category_id = c.category_id;
      d.class_id = c.class_id;
      d.score = 0.0f;
      named.push_back(d);
    }
  }
  if (static_cast<int>(named.size()) > classes_per_box) named.resize(classes_per_box);
  for (ObjectDetection& d : named) {
    d.box[0] = static_cast<float>(region.box.x);
    d.box[1] = static_cast<float>(region.box.y);
    d.box[2] = static_cast<float>(region.box.br().x);
    d.box[3] = static_cast<float>(region.box.br().y);
  }
  return named;
}

DepthProposals propose_from_depth(const cv::Mat& depth_mm, const PinholeCamera& camera,
                                  const std::vector<ObjectDetection>& detections,
                                  const std::vector<ProposalClass>& classes, int classes_per_box) {
  CV_Assert(!classes.empty());
  DepthSegmentationOptions options;
  options.smallest_part_mm = options.largest_part_mm = classes.front().diameter_mm;
  for (const ProposalClass& c : classes) {
    options.smallest_part_mm = std::min(options.smallest_part_mm, c.diameter_mm);
    options.largest_part_mm = std::max(options.largest_part_mm, c.diameter_mm);
  }
  DepthProposals proposals;
  proposals.segmentation = segment_depth(depth_mm, camera, options);
  for (const DepthRegion& region : proposals.segmentation.regions) {
    const cv::Rect2d box(region.box);
    const bool matched = std::any_of(detections.begin(), detections.end(),
                                     [&](const ObjectDetection& d) { return iou(box_of(d), box) > kDepthMatchIou; });
    proposals.matched.push_back(matched);
    if (matched) continue;
    const std::vector<ObjectDetection> named = region_proposals(region, detections, classes, classes_per_box);
    proposals.boxes.insert(proposals.boxes.end(), named.begin(), named.end());
  }
  return proposals;
}

cv::Mat depth_regions_picture(const cv::Mat& left_rgb8, const DepthProposals& proposals) {
  cv::Mat grey, bgr;
  cv::cvtColor(left_rgb8, grey, cv::COLOR_RGB2GRAY);
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  const cv::Mat& labels = proposals.segmentation.labels;
  // A colour per label from a golden-angle hue walk: neighbours differ.
  cv::Mat hsv(1, proposals.segmentation.region_count + 1, CV_8UC3), palette;
  for (int label = 0; label < hsv.cols; ++label) {
    hsv.at<cv::Vec3b>(0, label) = cv::Vec3b(static_cast<unsigned char>(std::fmod(label * 137.508, 360.0) / 2.0), 200, 255);
  }
  cv::cvtColor(hsv, palette, cv::COLOR_HSV2BGR);
  for (int v = 0; v < bgr.rows; ++v) {
    for (int u = 0; u < bgr.cols; ++u) {
      const int label = labels.at<int>(v, u);
      if (label == 0) continue;
      cv::Vec3b& pixel = bgr.at<cv::Vec3b>(v, u);
      const cv::Vec3b tint = palette.at<cv::Vec3b>(0, label);
      for (int c = 0; c < 3; ++c) pixel[c] = static_cast<unsigned char>((pixel[c] + tint[c]) / 2);
    }
  }
  const int thickness = std::max(1, bgr.cols / 640);
  for (std::size_t i = 0; i < proposals.segmentation.regions.size(); ++i) {
    const cv::Scalar colour = proposals.matched[i] ? cv::Scalar(255, 120, 0) : cv::Scalar(0, 140, 255);
    cv::rectangle(bgr, proposals.segmentation.regions[i].box, colour, thickness);
  }
  return bgr;
}

}  // namespace flexsight

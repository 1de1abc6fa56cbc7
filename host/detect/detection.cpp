#include "host/detect/detection.h"

namespace flexsight {

Detection detection_from_record(const SsdDetectionRecord& record) {
  Detection detection;
  detection.class_id = record.class_id;
  detection.score = record.score;
  for (int k = 0; k < 4; ++k) detection.box[k] = record.box[k];
  detection.anchor = record.anchor;
  return detection;
}

std::vector<Detection> detections_from_records(const std::vector<SsdDetectionRecord>& records) {
  std::vector<Detection> detections;
  detections.reserve(records.size());
  for (const SsdDetectionRecord& record : records) {
    detections.push_back(detection_from_record(record));
  }
  return detections;
}

Detection detection_in_pixels(const Detection& detection, int width, int height) {
  Detection pixels = detection;
  pixels.box[0] = detection.box[0] * static_cast<float>(width);
  pixels.box[1] = detection.box[1] * static_cast<float>(height);
  pixels.box[2] = detection.box[2] * static_cast<float>(width);
  pixels.box[3] = detection.box[3] * static_cast<float>(height);
  return pixels;
}

}  // namespace flexsight

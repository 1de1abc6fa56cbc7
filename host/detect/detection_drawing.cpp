#include "host/detect/detection_drawing.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>

#include "host/io/id_colour.h"
#include "host/io/tile_sheet.h"

namespace flexsight {
namespace {

// `text` on a filled box of `colour` with its lower-left corner at `corner`, kept inside
// the image.
void draw_label(cv::Mat& image, const std::string& text, cv::Point corner,
                const cv::Scalar& colour) {
  constexpr double kFontScale = 0.4;
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, kFontScale, 1, &baseline);
  corner.x = std::clamp(corner.x, 0, std::max(0, image.cols - size.width - 2));
  corner.y = std::clamp(corner.y, size.height + 2, std::max(size.height + 2, image.rows - 1));
  cv::rectangle(image, corner + cv::Point(0, -size.height - 2),
                corner + cv::Point(size.width + 2, 1), colour, cv::FILLED);
  cv::putText(image, text, corner + cv::Point(1, -1), cv::FONT_HERSHEY_SIMPLEX, kFontScale,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

}  // namespace

cv::Mat draw_detections(const cv::Mat& rgb, const std::vector<ObjectDetection>& found,
                        double scale) {
  cv::Mat picture;
  if (scale == 1.0) {
    picture = rgb.clone();
  } else {
    cv::resize(rgb, picture, cv::Size(), scale, scale,
               scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  }
  for (auto it = found.rbegin(); it != found.rend(); ++it) {
    const cv::Point top_left(cvRound(it->box[0] * scale), cvRound(it->box[1] * scale));
    const cv::Point bottom_right(cvRound(it->box[2] * scale), cvRound(it->box[3] * scale));
    const cv::Scalar colour = id_colour(it->category_id);
    cv::rectangle(picture, top_left, bottom_right, colour, 1, cv::LINE_AA);
    char label[48];
    std::snprintf(label, sizeof label, "%d %.2f", it->category_id, it->score);
    draw_label(picture, label, top_left, colour);
  }
  return picture;
}

cv::Mat detection_contact_sheet(const std::vector<cv::Mat>& images,
                                const std::vector<std::vector<ObjectDetection>>& found,
                                const DetectionSheetOptions& options) {
  if (images.empty()) return cv::Mat();
  std::vector<cv::Mat> tiles;
  for (size_t i = 0; i < images.size(); ++i) {
    const double scale = static_cast<double>(options.tile_width) / images[i].cols;
    tiles.push_back(draw_detections(images[i], found.at(i), scale));
    // The tile's number, black on white, at the lower left where boxes rarely start.
    draw_label(tiles.back(), "#" + std::to_string(i + 1), cv::Point(0, tiles.back().rows - 1),
               cv::Scalar(255, 255, 255));
  }
  return tile_sheet(tiles, options.tile_width, options.columns, WideTiles::kTrim);
}

}  // namespace flexsight

#include "host/synth/contact_sheet.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>

#include "host/io/id_colour.h"

namespace flexsight {
namespace {

cv::Mat draw_tile(const AnnotatedImage& image, int tile_width) {
  const double scale = static_cast<double>(tile_width) / image.rgb.cols;
  cv::Mat tile;
  cv::resize(image.rgb, tile, cv::Size(), scale, scale, cv::INTER_AREA);
  for (const PartAnnotation& part : image.parts) {
    if (part.bbox_visib.empty()) continue;
    const cv::Rect box(cvRound(part.bbox_visib.x * scale), cvRound(part.bbox_visib.y * scale),
                       std::max(1, cvRound(part.bbox_visib.width * scale)),
                       std::max(1, cvRound(part.bbox_visib.height * scale)));
    const cv::Scalar colour = id_colour(part.obj_id);
    cv::rectangle(tile, box, colour, 1, cv::LINE_AA);
    const std::string label = std::to_string(part.obj_id);
    int baseline = 0;
    const cv::Size text = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.35, 1, &baseline);
    const cv::Point corner(box.x, std::max(text.height + 2, box.y));
    cv::rectangle(tile, corner + cv::Point(0, -text.height - 2),
                  corner + cv::Point(text.width + 2, 1), colour, cv::FILLED);
    cv::putText(tile, label, corner + cv::Point(1, -1), cv::FONT_HERSHEY_SIMPLEX, 0.35,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return tile;
}

}  // namespace

cv::Mat make_contact_sheet(const std::vector<AnnotatedImage>& images,
                           const ContactSheetOptions& options) {
  if (images.empty()) return cv::Mat();
  std::vector<cv::Mat> tiles;
  int tile_height = 0;
  for (const AnnotatedImage& image : images) {
    tiles.push_back(draw_tile(image, options.tile_width));
    tile_height = std::max(tile_height, tiles.back().rows);
  }
  constexpr int kGap = 4;
  const int columns = std::min<int>(options.columns, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  cv::Mat sheet(rows * (tile_height + kGap) + kGap, columns * (options.tile_width + kGap) + kGap,
                CV_8UC3, cv::Scalar(255, 255, 255));
  for (size_t i = 0; i < tiles.size(); ++i) {
    const int column = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
    tiles[i].copyTo(sheet(cv::Rect(kGap + column * (options.tile_width + kGap),
                                   kGap + row * (tile_height + kGap), tiles[i].cols,
                                   tiles[i].rows)));
  }
  return sheet;
}

}  // namespace flexsight

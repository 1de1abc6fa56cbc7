#include "host/synth/contact_sheet.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>

#include "host/io/id_colour.h"
#include "host/io/tile_sheet.h"

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
  for (const AnnotatedImage& image : images) tiles.push_back(draw_tile(image, options.tile_width));
  return tile_sheet(tiles, options.tile_width, options.columns, WideTiles::kKeep);
}

}  // namespace flexsight

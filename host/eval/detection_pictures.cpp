#include "host/eval/detection_pictures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace flexsight {
namespace {

const cv::Scalar kWhite(255, 255, 255), kBlack(0, 0, 0), kGrid(225, 225, 225),
    kAxisText(60, 60, 60);
const cv::Scalar kTruthColour(0, 220, 0), kDetectionColour(255, 0, 255);  // RGB
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// Distinct colours (RGB) for the classes' curves, dark enough on white; T-LESS's 30
// parts still share some, and the legend's order tells them apart.
cv::Scalar class_colour(std::size_t index) {
  static const cv::Scalar kPalette[] = {
      {230, 25, 75},  {60, 160, 60},  {0, 130, 200},  {245, 130, 48}, {145, 30, 180},
      {0, 160, 160},  {220, 40, 200}, {128, 128, 0},  {170, 110, 40}, {128, 0, 0},
      {0, 0, 128},    {100, 100, 100}, {110, 170, 0}, {255, 105, 180}, {150, 120, 230},
      {200, 160, 0},  {0, 100, 0},    {70, 130, 180}, {205, 92, 92},  {75, 0, 130}};
  return kPalette[index % (sizeof kPalette / sizeof kPalette[0])];
}

std::string decimals(double value, int count) {
  if (!std::isfinite(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", count, value);
  return text;
}

void put_text(cv::Mat& image, const std::string& text, cv::Point origin, double scale,
              const cv::Scalar& colour, int thickness = 1) {
  cv::putText(image, text, origin, kFont, scale, colour, thickness, cv::LINE_AA);
}

// Text centred on `centre` horizontally, its baseline at centre.y.
void put_centred(cv::Mat& image, const std::string& text, cv::Point centre, double scale,
                 const cv::Scalar& colour, int thickness = 1) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, thickness, &baseline);
  put_text(image, text, {centre.x - size.width / 2, centre.y}, scale, colour, thickness);
}

// cv::putText draws horizontally only: the y axis's label is drawn on its own strip and
// turned a quarter counter-clockwise.
void put_vertical(cv::Mat& image, const std::string& text, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &baseline);
  cv::Mat strip(size.height + baseline + 4, size.width + 4, CV_8UC3, kWhite);
  put_text(strip, text, {2, size.height + 2}, scale, kAxisText);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect where(centre.x - turned.cols / 2, centre.y - turned.rows / 2, turned.cols,
                       turned.rows);
  turned.copyTo(image(where & cv::Rect(0, 0, image.cols, image.rows)));
}

// The envelope as a step function of recall: precision p_k over (r_{k-1}, r_k], at the
// points where recall grows (after the last of them the envelope is 0, not drawn; the
// false positives between them only lower what the envelope already hides).
std::vector<cv::Point> envelope_points(const PrCurve& curve, const cv::Rect& plot) {
  const auto to_pixel = [&](double recall, double precision) {
    return cv::Point(plot.x + cvRound(recall * plot.width),
                     plot.y + plot.height - cvRound(precision * plot.height));
  };
  std::vector<cv::Point> points;
  double previous_recall = 0;
  for (std::size_t k = 0; k < curve.recall.size(); ++k) {
    if (curve.recall[k] <= previous_recall) continue;
    points.push_back(to_pixel(previous_recall, curve.precision[k]));
    points.push_back(to_pixel(curve.recall[k], curve.precision[k]));
    previous_recall = curve.recall[k];
  }
  return points;
}

}  // namespace

cv::Mat draw_pr_curves(const DetectionScores& scores) {
  const cv::Size canvas(1000, 680);
  const cv::Rect plot(90, 60, 560, 540);
  cv::Mat image(canvas, CV_8UC3, kWhite);
  char title[96];
  std::snprintf(title, sizeof title, "Precision-recall at IoU %g (VOC matching)", scores.iou_threshold);
  put_text(image, title, {plot.x, 35}, 0.7, kBlack, 2);

  // Grid, ticks every 0.1 and the axes' names.
  for (int k = 0; k <= 10; ++k) {
    const int x = plot.x + cvRound(k * plot.width / 10.0);
    const int y = plot.y + plot.height - cvRound(k * plot.height / 10.0);
    cv::line(image, {x, plot.y}, {x, plot.y + plot.height}, kGrid, 1);
    cv::line(image, {plot.x, y}, {plot.x + plot.width, y}, kGrid, 1);
    const std::string label = decimals(k / 10.0, 1);
    put_centred(image, label, {x, plot.y + plot.height + 22}, 0.5, kAxisText);
    put_text(image, label, {plot.x - 40, y + 5}, 0.5, kAxisText);
  }
  cv::rectangle(image, plot, kBlack, 1);
  put_centred(image, "recall", {plot.x + plot.width / 2, plot.y + plot.height + 52}, 0.65,
              kAxisText);
  put_vertical(image, "precision", {plot.x - 65, plot.y + plot.height / 2}, 0.65);

  // The classes thin, each in its colour, then the mean on top.
  std::vector<const ClassDetectionScores*> shown;
  for (const ClassDetectionScores& c : scores.classes) {
    if (c.ground_truth > 0) shown.push_back(&c);
  }
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const std::vector<cv::Point> points = envelope_points(shown[i]->curve, plot);
    if (points.size() >= 2) cv::polylines(image, points, false, class_colour(i), 2, cv::LINE_AA);
  }
  std::vector<cv::Point> mean;
  const std::size_t count = scores.mean_precision_101.size();
  for (std::size_t r = 0; r < count; ++r) {
    const double recall = count > 1 ? static_cast<double>(r) / (count - 1) : 0.0;
    mean.emplace_back(plot.x + cvRound(recall * plot.width),
                      plot.y + plot.height - cvRound(scores.mean_precision_101[r] * plot.height));
  }
  if (mean.size() >= 2) cv::polylines(image, mean, false, kBlack, 4, cv::LINE_AA);

  // Legend: the mean, then as many classes as fit, best described by their AP.
  const int legend_x = plot.x + plot.width + 30, row = 22;
  int y = plot.y + 10;
  cv::line(image, {legend_x, y - 5}, {legend_x + 30, y - 5}, kBlack, 4, cv::LINE_AA);
  put_text(image, "mean, mAP " + decimals(scores.map, 3), {legend_x + 40, y}, 0.5, kBlack);
  const int rows_left = (canvas.height - 20 - y) / row - 1;
  for (std::size_t i = 0; i < shown.size(); ++i) {
    y += row;
    if (static_cast<int>(i) == rows_left - 1 && shown.size() > i + 1) {
      put_text(image, "... and " + std::to_string(shown.size() - i) + " more classes",
               {legend_x, y}, 0.5, kAxisText);
      break;
    }
    cv::line(image, {legend_x, y - 5}, {legend_x + 30, y - 5}, class_colour(i), 2, cv::LINE_AA);
    put_text(image,
             std::to_string(shown[i]->category_id) + " " + shown[i]->name + ", AP " +
                 decimals(shown[i]->voc_ap, 3),
             {legend_x + 40, y}, 0.5, kBlack);
  }
  return image;
}

namespace {

void draw_label(cv::Mat& tile, const std::string& text, cv::Point corner, const cv::Scalar& colour) {
  int baseline = 0;
  const double scale = 0.42;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &baseline);
  // Above the box when there is room, inside it otherwise; within the tile.
  const int top = corner.y - size.height - 4 >= 0 ? corner.y - size.height - 4 : std::max(0, corner.y);
  const int left = std::clamp(corner.x, 0, std::max(0, tile.cols - size.width - 4));
  const cv::Rect back(left, top, size.width + 4, size.height + 4);
  cv::rectangle(tile, back, colour, cv::FILLED);
  put_text(tile, text, {back.x + 2, back.y + size.height + 1}, scale, kWhite);
}

cv::Rect scaled(const BoxXywh& box, double scale) {
  return cv::Rect(cvRound(box[0] * scale), cvRound(box[1] * scale),
                  std::max(1, cvRound(box[2] * scale)), std::max(1, cvRound(box[3] * scale)));
}

cv::Mat draw_tile(const MontageImage& image, const MontageOptions& options) {
  const double scale = static_cast<double>(options.tile_width) / image.rgb.cols;
  cv::Mat tile;
  cv::resize(image.rgb, tile, cv::Size(), scale, scale,
             scale < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
  for (const TruthBox& box : image.truth) {
    cv::rectangle(tile, scaled(box.bbox, scale), kTruthColour, 2, cv::LINE_AA);
  }
  // Lowest score first, so the best boxes and labels are drawn on top.
  std::vector<const DetectedBox*> shown;
  for (const DetectedBox& box : image.detections) {
    if (box.score >= options.min_score) shown.push_back(&box);
  }
  std::stable_sort(shown.begin(), shown.end(),
                   [](const DetectedBox* a, const DetectedBox* b) { return a->score < b->score; });
  for (const DetectedBox* box : shown) {
    const cv::Rect rect = scaled(box->bbox, scale);
    cv::rectangle(tile, rect, kDetectionColour, 2, cv::LINE_AA);
    draw_label(tile, std::to_string(box->category_id) + " " + decimals(box->score, 2), rect.tl(),
               kDetectionColour);
  }
  return tile;
}

}  // namespace

cv::Mat draw_detection_montage(const std::vector<MontageImage>& images, const MontageOptions& options) {
  if (images.empty()) return cv::Mat();
  std::vector<cv::Mat> tiles;
  int tile_height = 0;
  for (const MontageImage& image : images) {
    tiles.push_back(draw_tile(image, options));
    tile_height = std::max(tile_height, tiles.back().rows);
  }
  constexpr int kGap = 6, kCaption = 20, kLegend = 34;
  const int columns = std::min<int>(options.columns, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  const int cell_height = tile_height + kCaption + kGap;
  const int width = std::max(columns * (options.tile_width + kGap) + kGap, 560);
  cv::Mat sheet(kLegend + rows * cell_height + kGap, width, CV_8UC3, kWhite);

  cv::rectangle(sheet, cv::Rect(kGap, 10, 24, 14), kTruthColour, 2);
  put_text(sheet, "ground truth", {kGap + 32, 23}, 0.5, kBlack);
  cv::rectangle(sheet, cv::Rect(kGap + 160, 10, 24, 14), kDetectionColour, 2);
  put_text(sheet, "detections, score >= " + decimals(options.min_score, 2) + " (class score)",
           {kGap + 192, 23}, 0.5, kBlack);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const int column = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
    const cv::Point corner(kGap + column * (options.tile_width + kGap), kLegend + row * cell_height);
    tiles[i].copyTo(sheet(cv::Rect(corner.x, corner.y, tiles[i].cols, tiles[i].rows)));
    put_text(sheet, images[i].caption, {corner.x, corner.y + tiles[i].rows + 15}, 0.45, kAxisText);
  }
  return sheet;
}

}  // namespace flexsight

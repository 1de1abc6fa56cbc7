#pragma once
// The Directional Chamfer Distance tensor of D2CO (Imperoli & Pretto, "D2CO: Fast and
// Robust Registration of 3D Textureless Objects Using the Directional Chamfer
// Distance", ICVS 2015): for every pixel of an image region and every edge orientation
// bin, the cost of the cheapest edge pixel, distance in pixels plus a penalty for the
// difference in orientation. A template edge point at (x, y) with direction theta then
// costs one look-up, and the cost is smooth enough in (x, y) for Levenberg-Marquardt.
#include <opencv2/core.hpp>
#include <vector>

namespace flexsight {

struct DcdParams {
  // Number of bins over [0, pi): edge directions without sign, as D2CO (the sign of an
  // edge flips with the background behind a part, its direction does not).
  int orientation_bins = 60;
  // lambda: pixels of cost per radian of orientation difference.
  float orientation_weight = 10.0f;
  // Cells saturate here (pixels): clutter far away costs the same as no edge at all.
  float max_distance = 30.0f;
  // Hysteresis thresholds of the Canny detector on the 8-bit grey image (L2 gradient
  // magnitude of the 3x3 Sobel derivatives).
  double canny_low = 40.0, canny_high = 100.0;
  // Sigma in pixels of the Gaussian blur before Canny (0 = none).
  double blur_sigma = 1.0;
  // How the Canny thresholds meet the image (edge_thresholds.h; docs/pose.md has the
  // measurements: pick uses kContrastAndNoise, for a bin's dark uniform floor, and the
  // default stays kFixed, better on parts over photographs): kFixed applies
  // canny_low/high to the grey levels as they are; kContrast first stretches the region's
  // grey levels (2nd to 98th percentile onto 0..255), so that exposure and gain do not
  // move the edges; kNoise raises the thresholds above the region's measured gradient
  // noise; kContrastAndNoise does both.
  enum class EdgeThresholds { kFixed, kContrast, kNoise, kContrastAndNoise };
  EdgeThresholds thresholds = EdgeThresholds::kFixed;
  // Throws InputError naming the field for a value out of range or not finite.
  void check() const;
};

// Edge pixels of an image region and their direction (the edge's tangent, i.e. the
// gradient direction + pi/2, folded into [0, pi)).
struct EdgeMap {
  cv::Mat mask;         // CV_8UC1, 255 on an edge pixel
  cv::Mat orientation;  // CV_32FC1 radians in [0, pi) where mask is set, 0 elsewhere
};

// Edges of image(roi) (8-bit grey or BGR; roi clipped to the image; an empty roi after
// clipping -> InputError), in roi coordinates (pixel (0,0) = roi.tl()). The blur and
// the derivatives see a few pixels of image around the roi, so that the edges along
// its border are those of the whole image.
EdgeMap detect_edges(const cv::Mat& image, const cv::Rect& roi, const DcdParams& params);

class DcdTensor {
 public:
  // Throws std::invalid_argument when `edges` is empty or its two images do not match
  // (types or sizes), InputError from params.check().
  DcdTensor(const EdgeMap& edges, const DcdParams& params);

  int width() const;
  int height() const;
  int bins() const;
  // The bin of a direction: any finite angle, folded modulo pi (std::invalid_argument
  // for one that is not finite). Bin b covers [b pi / bins, (b + 1) pi / bins).
  int bin_of(double orientation_radians) const;
  // The cell (x, y, bin); std::invalid_argument outside the tensor.
  float at(int x, int y, int bin) const;
  // Bilinear in (x, y) inside layer `bin`; dx, dy (may be null) its derivatives. Outside
  // the tensor (beyond the outermost cell centres): max_distance, derivatives 0.
  double sample(double x, double y, int bin, double* dx = nullptr, double* dy = nullptr) const;
  // CV_32FC1 height x width; std::invalid_argument for a bin out of range.
  const cv::Mat& layer(int bin) const;
  // Where something in front of the part hides it, a template point has no edge to
  // meet: it should cost a middling fit, not the saturated distance (else the true pose
  // of a partly hidden part loses to any pose that avoids the hidden side). Cells under
  // `mask` (CV_8UC1, its pixel (0, 0) on cell `mask_origin`; it may reach beyond the
  // tensor, whose region is the visible box grown a little, while a hidden part reaches
  // farther) cost at most `value` in every bin, and so do places outside the tensor
  // that the mask covers. std::invalid_argument for a mask that is not 8-bit.
  void cap(const cv::Mat& mask, cv::Point mask_origin, float value);
  // What a place outside the tensor costs: `value` of cap() where its mask is set,
  // max_distance elsewhere.
  float outside_cost(int x, int y) const;

 private:
  void check_bin(int bin) const;

  int bins_ = 0;
  float max_distance_ = 0.0f;
  std::vector<cv::Mat> layers_;
  cv::Mat hidden_;            // cap()'s mask
  cv::Point hidden_origin_;   // the cell of its pixel (0, 0)
  float hidden_cost_ = 0.0f;
};

}  // namespace flexsight

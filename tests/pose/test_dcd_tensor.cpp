// The directional chamfer tensor against its definition, evaluated by brute force over
// every edge pixel for every cell, on small images with seeded random edges (directions
// near 0 and pi included, where the orientation axis wraps around); the bins of
// directions; bilinear sampling and its derivatives; edges of a drawn rectangle; and
// the parameters' checks.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

#include "host/io/input_error.h"
#include "host/pose/dcd_tensor.h"

using namespace flexsight;

namespace {

struct EdgePixel {
  int x, y;
  float orientation;
};

EdgeMap edge_map(const cv::Size& size, const std::vector<EdgePixel>& pixels) {
  EdgeMap edges;
  edges.mask = cv::Mat::zeros(size, CV_8UC1);
  edges.orientation = cv::Mat::zeros(size, CV_32FC1);
  for (const EdgePixel& e : pixels) {
    edges.mask.at<std::uint8_t>(e.y, e.x) = 255;
    edges.orientation.at<float>(e.y, e.x) = e.orientation;
  }
  return edges;
}

// `count` distinct random pixels; a quarter of them with directions within 1e-3 rad of
// 0 or of pi (stored below pi), the others uniform over [0, pi).
std::vector<EdgePixel> random_edges(const cv::Size& size, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> x(0, size.width - 1), y(0, size.height - 1);
  std::uniform_real_distribution<float> direction(0.0f, float(M_PI)), tiny(0.0f, 1e-3f);
  std::vector<EdgePixel> pixels;
  cv::Mat taken = cv::Mat::zeros(size, CV_8UC1);
  while (static_cast<int>(pixels.size()) < count) {
    EdgePixel e{x(rng), y(rng), 0.0f};
    if (taken.at<std::uint8_t>(e.y, e.x)) continue;
    taken.at<std::uint8_t>(e.y, e.x) = 1;
    switch (pixels.size() % 8) {
      case 0: e.orientation = tiny(rng); break;
      case 1: e.orientation = float(M_PI) - 4e-6f - tiny(rng); break;
      default: e.orientation = direction(rng); break;
    }
    if (!(e.orientation >= 0.0f && e.orientation < float(M_PI) && double(e.orientation) < M_PI)) {
      e.orientation = 0.0f;
    }
    pixels.push_back(e);
  }
  return pixels;
}

// The bin of a direction in [0, pi), written out here rather than taken from the tensor.
int reference_bin(float orientation, int bins) {
  return std::min(static_cast<int>(double(orientation) / (M_PI / bins)), bins - 1);
}

// The cell by its definition: the cheapest edge pixel, Euclidean distance plus the
// weight times the circular distance between the two bins' centres, saturated.
double brute_force_cell(const std::vector<EdgePixel>& pixels, int x, int y, int bin,
                        const DcdParams& params) {
  const int bins = params.orientation_bins;
  const double bin_width = M_PI / bins;
  double best = params.max_distance;
  for (const EdgePixel& e : pixels) {
    const int apart = std::abs(bin - reference_bin(e.orientation, bins));
    const double angle = std::min(apart, bins - apart) * bin_width;
    best = std::min(best, std::hypot(double(x - e.x), double(y - e.y)) +
                              params.orientation_weight * angle);
  }
  return best;
}

struct BruteForceCase {
  const char* name;
  int bins;
  float weight;
  float max_distance;
  int edge_count;
  unsigned seed;
};

void PrintTo(const BruteForceCase& c, std::ostream* out) { *out << c.name; }

class DcdTensorBruteForce : public ::testing::TestWithParam<BruteForceCase> {};

TEST_P(DcdTensorBruteForce, EveryCellMatchesTheDefinition) {
  const BruteForceCase& c = GetParam();
  DcdParams params;
  params.orientation_bins = c.bins;
  params.orientation_weight = c.weight;
  params.max_distance = c.max_distance;
  const cv::Size size(40, 30);
  const std::vector<EdgePixel> pixels = random_edges(size, c.edge_count, c.seed);
  const DcdTensor tensor(edge_map(size, pixels), params);
  ASSERT_EQ(tensor.width(), size.width);
  ASSERT_EQ(tensor.height(), size.height);
  ASSERT_EQ(tensor.bins(), c.bins);
  int wrong = 0, saturated = 0;
  for (int b = 0; b < c.bins; ++b) {
    const cv::Mat& layer = tensor.layer(b);
    ASSERT_EQ(layer.type(), CV_32FC1);
    ASSERT_EQ(layer.size(), size);
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) {
        const double expected = brute_force_cell(pixels, x, y, b, params);
        const float cell = tensor.at(x, y, b);
        ASSERT_EQ(cell, layer.at<float>(y, x));
        if (std::abs(cell - expected) > 1e-3 && ++wrong <= 5) {
          ADD_FAILURE() << "cell (" << x << ", " << y << ", " << b << ") = " << cell
                        << ", definition " << expected;
        }
        saturated += expected == params.max_distance;
      }
    }
  }
  EXPECT_EQ(wrong, 0);
  // The cases are meant to exercise both the saturation and the cells below it.
  const int cells = c.bins * size.area();
  if (c.edge_count == 0) {
    EXPECT_EQ(saturated, cells);
  } else {
    EXPECT_LT(saturated, cells);
  }
}

INSTANTIATE_TEST_SUITE_P(
    DcdRandomEdges, DcdTensorBruteForce,
    ::testing::Values(
        // D2CO's defaults: one bin costs 0.52 px; the far side of the circle would cost
        // 15.7 px, the wrong way around it up to 30.9 px (saturated).
        BruteForceCase{"defaults_sparse", 60, 10.0f, 30.0f, 6, 11u},
        BruteForceCase{"defaults_dense", 60, 10.0f, 30.0f, 40, 12u},
        // Few edges, a heavy orientation weight and a short saturation: most cells
        // saturate, the wrap-around between the first and the last bin decides many.
        BruteForceCase{"heavy_weight", 60, 40.0f, 12.0f, 5, 13u},
        // An odd number of bins (the two ways around the circle never tie).
        BruteForceCase{"odd_bins", 7, 3.0f, 30.0f, 10, 14u},
        BruteForceCase{"two_bins", 2, 5.0f, 20.0f, 8, 15u},
        // One bin: the plain distance transform.
        BruteForceCase{"one_bin", 1, 10.0f, 30.0f, 8, 16u},
        BruteForceCase{"no_orientation_cost", 16, 0.0f, 30.0f, 8, 17u},
        BruteForceCase{"no_edge", 60, 10.0f, 30.0f, 0, 18u}),
    [](const ::testing::TestParamInfo<BruteForceCase>& info) { return info.param.name; });

TEST(DcdTensor, NoEdgeCostsMaxDistanceEverywhere) {
  DcdParams params;
  params.max_distance = 17.5f;
  const DcdTensor tensor(edge_map({13, 9}, {}), params);
  for (int b = 0; b < tensor.bins(); ++b) {
    double lo, hi;
    cv::minMaxLoc(tensor.layer(b), &lo, &hi);
    EXPECT_EQ(lo, 17.5);
    EXPECT_EQ(hi, 17.5);
  }
  EXPECT_EQ(tensor.sample(6.3, 4.1, 5), 17.5);
}

TEST(DcdTensor, BinOfFoldsAnyAngleModuloPi) {
  DcdParams params;
  params.orientation_bins = 60;
  const DcdTensor tensor(edge_map({4, 4}, {}), params);
  const double width = M_PI / 60;
  for (int b = 0; b < 60; ++b) {
    for (int turns = -3; turns <= 3; ++turns) {
      const double centre = (b + 0.5) * width + turns * M_PI;
      EXPECT_EQ(tensor.bin_of(centre), b) << centre;
      EXPECT_EQ(tensor.bin_of(centre - 0.49 * width), b) << centre;
      EXPECT_EQ(tensor.bin_of(centre + 0.49 * width), b) << centre;
    }
  }
  EXPECT_EQ(tensor.bin_of(0.0), 0);
  EXPECT_EQ(tensor.bin_of(M_PI), 0);
  EXPECT_EQ(tensor.bin_of(-M_PI), 0);
  EXPECT_EQ(tensor.bin_of(M_PI - 1e-9), 59);
  EXPECT_EQ(tensor.bin_of(-1e-9), 59);
  EXPECT_EQ(tensor.bin_of(-M_PI / 2), 30);
  EXPECT_EQ(tensor.bin_of(std::nextafter(M_PI, 0.0)), 59);
  EXPECT_EQ(tensor.bin_of(double(std::nextafter(float(M_PI), 0.0f))), 59);
  EXPECT_THROW(tensor.bin_of(std::nan("")), std::invalid_argument);
  EXPECT_THROW(tensor.bin_of(INFINITY), std::invalid_argument);
}

// A tensor with cells that vary in both directions, for the sampling tests.
DcdTensor sampling_tensor() {
  DcdParams params;
  params.orientation_bins = 12;
  const cv::Size size(17, 11);
  return DcdTensor(edge_map(size, random_edges(size, 5, 21u)), params);
}

TEST(DcdTensorSample, EqualsTheCellsOnTheirCentres) {
  const DcdTensor tensor = sampling_tensor();
  for (int b = 0; b < tensor.bins(); ++b) {
    for (int y = 0; y < tensor.height(); ++y) {
      for (int x = 0; x < tensor.width(); ++x) {
        EXPECT_EQ(tensor.sample(x, y, b), double(tensor.at(x, y, b)));
      }
    }
  }
}

TEST(DcdTensorSample, IsBilinearBetweenTheCentres) {
  const DcdTensor tensor = sampling_tensor();
  const int b = 4;
  for (int y = 0; y + 1 < tensor.height(); ++y) {
    for (int x = 0; x + 1 < tensor.width(); ++x) {
      for (const auto& [fx, fy] : {std::pair{0.3, 0.6}, {0.75, 0.1}, {0.5, 0.5}, {0.0, 0.8}}) {
        const double top = (1 - fx) * tensor.at(x, y, b) + fx * tensor.at(x + 1, y, b);
        const double bottom = (1 - fx) * tensor.at(x, y + 1, b) + fx * tensor.at(x + 1, y + 1, b);
        EXPECT_NEAR(tensor.sample(x + fx, y + fy, b), (1 - fy) * top + fy * bottom, 1e-9);
      }
    }
  }
}

TEST(DcdTensorSample, DerivativesMatchCentralDifferences) {
  const DcdTensor tensor = sampling_tensor();
  const double h = 1e-4;
  int nonzero = 0;
  for (int b = 0; b < tensor.bins(); b += 3) {
    for (double y = 0.37; y < tensor.height() - 1; y += 0.83) {
      for (double x = 0.21; x < tensor.width() - 1; x += 0.77) {
        // Clear of the cell borders, where the derivative jumps.
        if (std::abs(x - std::round(x)) < 2 * h || std::abs(y - std::round(y)) < 2 * h) continue;
        double dx = NAN, dy = NAN;
        const double value = tensor.sample(x, y, b, &dx, &dy);
        EXPECT_EQ(value, tensor.sample(x, y, b));
        const double fd_x = (tensor.sample(x + h, y, b) - tensor.sample(x - h, y, b)) / (2 * h);
        const double fd_y = (tensor.sample(x, y + h, b) - tensor.sample(x, y - h, b)) / (2 * h);
        EXPECT_NEAR(dx, fd_x, 1e-6) << x << ", " << y << ", " << b;
        EXPECT_NEAR(dy, fd_y, 1e-6) << x << ", " << y << ", " << b;
        nonzero += dx != 0.0 || dy != 0.0;
      }
    }
  }
  EXPECT_GT(nonzero, 100);
}

TEST(DcdTensorSample, OutsideTheCentresCostsMaxDistanceWithoutSlope) {
  const DcdTensor tensor = sampling_tensor();
  const double w = tensor.width() - 1, h = tensor.height() - 1;
  for (const auto& [x, y] : {std::pair{-0.01, 3.0}, {w + 0.01, 3.0}, {4.0, -0.5}, {4.0, h + 1e-9},
                             {-100.0, -100.0}, {double(NAN), 2.0}}) {
    double dx = 1.0, dy = 1.0;
    EXPECT_EQ(tensor.sample(x, y, 2, &dx, &dy), 30.0) << x << ", " << y;
    EXPECT_EQ(dx, 0.0);
    EXPECT_EQ(dy, 0.0);
  }
  // The outermost centres are still inside.
  EXPECT_EQ(tensor.sample(w, h, 2), double(tensor.at(int(w), int(h), 2)));
  EXPECT_EQ(tensor.sample(0.0, h, 2), double(tensor.at(0, int(h), 2)));
  EXPECT_THROW(tensor.sample(1.0, 1.0, tensor.bins()), std::invalid_argument);
  EXPECT_THROW(tensor.sample(1.0, 1.0, -1), std::invalid_argument);
  EXPECT_THROW(tensor.at(int(w) + 1, 0, 0), std::invalid_argument);
  EXPECT_THROW(tensor.layer(tensor.bins()), std::invalid_argument);
}

TEST(DcdTensorCap, HiddenCellsAndHiddenPlacesOutsideCostAtMostTheCap) {
  DcdTensor tensor = sampling_tensor();
  const int w = tensor.width(), h = tensor.height();
  const DcdTensor before = sampling_tensor();
  // A mask from 2 cells left of the tensor to its middle column, rows 1..2 set.
  cv::Mat mask(h + 4, w / 2 + 2, CV_8UC1, cv::Scalar(0));
  mask.rowRange(3, 5).setTo(255);  // mask rows 3, 4 = tensor rows 1, 2
  tensor.cap(mask, cv::Point(-2, -2), 4.0f);
  for (int b = 0; b < tensor.bins(); ++b) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const bool hidden = (y == 1 || y == 2) && x < w / 2;
        const float expected = hidden ? std::min(4.0f, before.at(x, y, b)) : before.at(x, y, b);
        ASSERT_EQ(tensor.at(x, y, b), expected) << x << ", " << y << ", bin " << b;
      }
    }
  }
  // Outside the tensor: the cap where the mask is set, max_distance elsewhere.
  EXPECT_EQ(tensor.outside_cost(-1, 1), 4.0f);
  EXPECT_EQ(tensor.sample(-1.0, 2.0, 0), 4.0);
  EXPECT_EQ(tensor.outside_cost(-1, 0), 30.0f);
  EXPECT_EQ(tensor.outside_cost(-3, 1), 30.0f);  // beyond the mask
  EXPECT_EQ(tensor.outside_cost(w + 5, 1), 30.0f);
  EXPECT_THROW(tensor.cap(cv::Mat(2, 2, CV_32FC1), cv::Point(0, 0), 4.0f), std::invalid_argument);
}

// A bright rectangle on a dark background: columns 30..89, rows 20..69.
cv::Mat rectangle_image() {
  cv::Mat image(100, 120, CV_8UC1, cv::Scalar(50));
  cv::rectangle(image, cv::Point(30, 20), cv::Point(89, 69), cv::Scalar(200), cv::FILLED);
  return image;
}

// Distance between directions modulo pi.
double direction_difference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

TEST(DcdDetectEdges, FindsTheSidesOfARectangleWithTheirDirections) {
  const cv::Mat image = rectangle_image();
  const EdgeMap edges = detect_edges(image, cv::Rect(0, 0, 120, 100), DcdParams());
  ASSERT_EQ(edges.mask.type(), CV_8UC1);
  ASSERT_EQ(edges.orientation.type(), CV_32FC1);
  ASSERT_EQ(edges.mask.size(), image.size());
  // The step lies between pixels 29 and 30 (and 89 and 90, ...): an edge pixel on
  // either side of it.
  const auto near_column = [](int x, double step) { return std::abs(x - step) <= 1.0; };
  int vertical_rows[100] = {}, horizontal_columns[120] = {};
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const float orientation = edges.orientation.at<float>(y, x);
      if (edges.mask.at<std::uint8_t>(y, x) == 0) {
        ASSERT_EQ(orientation, 0.0f);
        continue;
      }
      ASSERT_EQ(edges.mask.at<std::uint8_t>(y, x), 255);
      ASSERT_GE(orientation, 0.0f);
      ASSERT_LT(double(orientation), M_PI);
      const bool on_vertical = (near_column(x, 29.5) || near_column(x, 89.5)) && y >= 19 && y <= 70;
      const bool on_horizontal =
          (near_column(y, 19.5) || near_column(y, 69.5)) && x >= 29 && x <= 90;
      EXPECT_TRUE(on_vertical || on_horizontal) << "edge pixel away from the sides at " << x
                                                << ", " << y;
      // Away from the corners, the direction of the side.
      const bool corner = (x < 34 || x > 85) && (y < 24 || y > 65);
      if (corner) continue;
      if (on_vertical) {
        EXPECT_LT(direction_difference(orientation, M_PI / 2), 0.05) << x << ", " << y;
        ++vertical_rows[y];
      } else if (on_horizontal) {
        EXPECT_LT(direction_difference(orientation, 0.0), 0.05) << x << ", " << y;
        ++horizontal_columns[x];
      }
    }
  }
  // Every side is found along its whole length (one pixel wide on each side of the
  // step: two sides per row or column).
  for (int y = 24; y <= 65; ++y) EXPECT_EQ(vertical_rows[y], 2) << "row " << y;
  for (int x = 34; x <= 85; ++x) EXPECT_EQ(horizontal_columns[x], 2) << "column " << x;
}

TEST(DcdDetectEdges, RoiCoordinatesStartAtTheRoiCorner) {
  const cv::Mat image = rectangle_image();
  const DcdParams params;
  const EdgeMap whole = detect_edges(image, cv::Rect(0, 0, 120, 100), params);
  // Inside: the same edges as the whole image, shifted (the roi's border cuts through
  // two sides of the rectangle).
  const cv::Rect roi(21, 13, 37, 29);
  const EdgeMap part = detect_edges(image, roi, params);
  ASSERT_EQ(part.mask.size(), roi.size());
  EXPECT_EQ(cv::countNonZero(part.mask != whole.mask(roi)), 0);
  EXPECT_EQ(cv::countNonZero(part.orientation != whole.orientation(roi)), 0);
  EXPECT_GT(cv::countNonZero(part.mask), 40);
  // A roi whose first column holds the rectangle's left side: the blur and the
  // derivatives must see the image to its left (a border reflected at the roi would
  // move the edge one column in).
  const cv::Rect on_side(29, 30, 20, 20);
  const EdgeMap side = detect_edges(image, on_side, params);
  EXPECT_EQ(cv::countNonZero(side.mask.col(0)), 20);
  EXPECT_EQ(cv::countNonZero(side.mask != whole.mask(on_side)), 0);
  // Partly outside: clipped to the image.
  const EdgeMap clipped = detect_edges(image, cv::Rect(80, 60, 100, 100), params);
  ASSERT_EQ(clipped.mask.size(), cv::Size(40, 40));
  EXPECT_EQ(cv::countNonZero(clipped.mask != whole.mask(cv::Rect(80, 60, 40, 40))), 0);
  // A BGR image gives the edges of its grey version.
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  const EdgeMap from_bgr = detect_edges(bgr, roi, params);
  EXPECT_EQ(cv::countNonZero(from_bgr.mask != part.mask), 0);
}

TEST(DcdDetectEdges, RejectsAnEmptyRoiAndOtherImageTypes) {
  const cv::Mat image = rectangle_image();
  EXPECT_THROW(detect_edges(image, cv::Rect(120, 0, 10, 10), DcdParams()), InputError);
  EXPECT_THROW(detect_edges(image, cv::Rect(-20, -20, 20, 20), DcdParams()), InputError);
  EXPECT_THROW(detect_edges(image, cv::Rect(5, 5, 0, 10), DcdParams()), InputError);
  EXPECT_THROW(detect_edges(cv::Mat(), cv::Rect(0, 0, 10, 10), DcdParams()), InputError);
  cv::Mat wide;
  image.convertTo(wide, CV_16U);
  EXPECT_THROW(detect_edges(wide, cv::Rect(0, 0, 10, 10), DcdParams()), InputError);
}

// A bad value throws InputError whose message names the field.
template <class Change>
void expect_rejected(const char* field, Change change) {
  DcdParams params;
  change(params);
  try {
    params.check();
    ADD_FAILURE() << field << ": accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)DcdTensor(edge_map({4, 4}, {}), params), InputError) << field;
  EXPECT_THROW(detect_edges(rectangle_image(), cv::Rect(0, 0, 10, 10), params), InputError)
      << field;
}

TEST(DcdParams, BadValuesNameTheirField) {
  EXPECT_NO_THROW(DcdParams().check());
  expect_rejected("orientation_bins", [](DcdParams& p) { p.orientation_bins = 0; });
  expect_rejected("orientation_weight", [](DcdParams& p) { p.orientation_weight = -1.0f; });
  expect_rejected("orientation_weight", [](DcdParams& p) { p.orientation_weight = NAN; });
  expect_rejected("max_distance", [](DcdParams& p) { p.max_distance = 0.0f; });
  expect_rejected("max_distance", [](DcdParams& p) { p.max_distance = INFINITY; });
  expect_rejected("canny_low", [](DcdParams& p) { p.canny_low = -1.0; });
  expect_rejected("canny_high", [](DcdParams& p) { p.canny_high = 30.0; });
  expect_rejected("blur_sigma", [](DcdParams& p) { p.blur_sigma = -0.5; });
}

TEST(DcdTensor, RejectsEdgeMapsThatDoNotFitTogether) {
  EdgeMap edges = edge_map({8, 6}, {});
  EdgeMap wrong_size = edges;
  wrong_size.orientation = cv::Mat::zeros(5, 8, CV_32FC1);
  EXPECT_THROW((void)DcdTensor(wrong_size, DcdParams()), std::invalid_argument);
  EdgeMap wrong_type = edges;
  wrong_type.orientation = cv::Mat::zeros(6, 8, CV_64FC1);
  EXPECT_THROW((void)DcdTensor(wrong_type, DcdParams()), std::invalid_argument);
  EXPECT_THROW((void)DcdTensor(EdgeMap(), DcdParams()), std::invalid_argument);
}

}  // namespace

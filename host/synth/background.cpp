#include "host/synth/background.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

// A rectangle of the source in edge coordinates: pixel i covers [i, i + 1).
struct Crop {
  double x, y, width, height;
};

}  // namespace

cv::Mat draw_background(const BackgroundCropSettings& settings, const BackgroundLibrary& library,
                        const PinholeCamera& camera, const Eigen::Matrix3d& camera_rotation,
                        std::uint32_t seed, std::int64_t image_index) {
  synth_detail::SynthRandom random(seed, image_index, synth_detail::kStreamBackground);
  cv::Mat source = library.load(random.integer(0, library.size() - 1));
  const int W = camera.width, H = camera.height;

  // The largest crop of the drawn aspect that fits, scaled, placed uniformly.
  const double aspect =
      double(W) / H *
      std::exp(random.uniform(-settings.max_crop_aspect_change, settings.max_crop_aspect_change));
  const double fit_height = std::min(double(source.rows), source.cols / aspect);
  const double scale = random.uniform(settings.min_crop_scale, 1.0);
  Crop crop;
  crop.height = scale * fit_height;
  crop.width = crop.height * aspect;
  crop.x = random.uniform(0.0, std::max(source.cols - crop.width, 0.0));
  crop.y = random.uniform(0.0, std::max(source.rows - crop.height, 0.0));
  const bool mirror = random.chance(settings.flip_probability);

  // Shrinking by more than 2 in one bilinear step would alias: area-average first.
  const double shrink = std::min(crop.width / W, crop.height / H);
  if (shrink > 2.0) {
    cv::Mat small;
    cv::resize(source, small,
               cv::Size(std::max(1, int(std::lround(source.cols / shrink))),
                        std::max(1, int(std::lround(source.rows / shrink)))),
               0, 0, cv::INTER_AREA);
    const double fx = double(small.cols) / source.cols, fy = double(small.rows) / source.rows;
    crop = {crop.x * fx, crop.y * fy, crop.width * fx, crop.height * fy};
    source = small;
  }

  // Output pixel q of the rotated picture -> unrotated output pixel p = c + M^T (q - c),
  // M the camera rotation's effect on image offsets (fx == fy) -> mirrored -> source
  // pixel centre s = crop origin + (p + 0.5) * crop / output - 0.5.
  const Eigen::Matrix2d M = camera_rotation.topLeftCorner<2, 2>();
  const Eigen::Vector2d c(camera.cx, camera.cy);
  const double kx = crop.width / W, ky = crop.height / H;
  const Eigen::Matrix2d S = Eigen::Vector2d(mirror ? -kx : kx, ky).asDiagonal();
  const Eigen::Vector2d offset(crop.x + ((mirror ? W - 1 : 0) + 0.5) * kx - 0.5,
                               crop.y + 0.5 * ky - 0.5);
  const Eigen::Matrix2d linear = S * M.transpose();
  const Eigen::Vector2d shift = S * (c - M.transpose() * c) + offset;
  const cv::Matx23d map(linear(0, 0), linear(0, 1), shift.x(), linear(1, 0), linear(1, 1),
                        shift.y());
  cv::Mat background;
  cv::warpAffine(source, background, map, cv::Size(W, H), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REFLECT_101);
  return background;
}

}  // namespace flexsight

#pragma once
// Annotated images of axis-aligned rectangular "parts" at known depths, so that masks,
// occlusion and every gt_info number are known exactly. Shared by the dataset tests and
// flexsight_write_coco_fixture (which links no GoogleTest).
#include <Eigen/Geometry>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/dataset/gt_info.h"

namespace flexsight::dataset_test_support {

// A part seen as a rectangle (which may reach outside the image) at one depth.
struct RectPart {
  int obj_id = 1;
  cv::Rect rect;
  float depth_mm = 500.0f;
};

// An image of `parts` in front of a background at 1500 mm. The nearest part owns a
// pixel (mask_visib); every 7th pixel of the background has no depth (0), as a sensor's
// holes. Poses and the camera are arbitrary but fixed values with long decimal
// expansions, so that a writer that rounds them would be caught.
inline AnnotatedImage rect_image(int scene_id, int im_id, cv::Size size,
                                 const std::vector<RectPart>& parts) {
  AnnotatedImage image;
  image.scene_id = scene_id;
  image.im_id = im_id;
  image.camera.K << 512.123456789 + im_id, 0.0, size.width / 2.0 + 0.25, 0.0, 511.987654321,
      size.height / 2.0 - 0.125, 0.0, 0.0, 1.0;
  image.camera.depth_scale = 0.1;
  if (im_id % 2 == 1) image.camera.extra = {{"flip", "horizontal"}};
  image.rgb.create(size, CV_8UC3);
  image.depth.create(size, CV_32FC1);
  cv::Mat owner(size, CV_32SC1, cv::Scalar(-1));
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      float nearest = 1500.0f;
      for (std::size_t k = 0; k < parts.size(); ++k) {
        if (parts[k].rect.contains({x, y}) && parts[k].depth_mm < nearest) {
          nearest = parts[k].depth_mm;
          owner.at<int>(y, x) = static_cast<int>(k);
        }
      }
      const bool hole = owner.at<int>(y, x) < 0 && (x + y * size.width) % 7 == 0;
      image.depth.at<float>(y, x) = hole ? 0.0f : nearest;
      image.rgb.at<cv::Vec3b>(y, x) =
          cv::Vec3b(static_cast<uchar>(x * 9 + im_id), static_cast<uchar>(y * 11 + scene_id * 50),
                    static_cast<uchar>((x * y) % 256));
    }
  }
  for (std::size_t k = 0; k < parts.size(); ++k) {
    PartAnnotation part;
    part.obj_id = parts[k].obj_id;
    const double angle = 0.3 + 0.7 * static_cast<double>(k) + 0.1 * im_id;
    part.cam_R_m2c =
        Eigen::AngleAxisd(angle, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
    part.cam_t_m2c = Eigen::Vector3d(parts[k].rect.x / 3.0, parts[k].rect.y / 7.0,
                                     parts[k].depth_mm + 1.0 / 3.0);
    part.mask = cv::Mat(size, CV_8UC1, cv::Scalar(0));
    part.mask(parts[k].rect & cv::Rect(cv::Point(0, 0), size)).setTo(255);
    part.mask_visib = (owner == static_cast<int>(k));
    fill_gt_info(part, image.depth);
    image.parts.push_back(part);
  }
  return image;
}

// Smooth colour ramps, distinct per channel (R along x, G along y, B constant): what
// survives JPEG's chroma subsampling, so a JPEG round trip can be held to a tight PSNR
// and a swap of channels shows.
inline cv::Mat smooth_rgb(cv::Size size) {
  cv::Mat rgb(size, CV_8UC3);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      rgb.at<cv::Vec3b>(y, x) =
          cv::Vec3b(static_cast<uchar>(40 + 4 * x), static_cast<uchar>(200 - 5 * y), 90);
    }
  }
  return rgb;
}

// A set of images over two scenes, for round trips and merges: overlapping parts, a part
// hidden behind another, a part partly outside the image, an image with no parts, and
// awkward sizes.
inline std::vector<AnnotatedImage> sample_images() {
  std::vector<AnnotatedImage> images;
  const cv::Size size(33, 25);
  images.push_back(rect_image(0, 0, size, {{1, {2, 3, 10, 8}, 400}, {2, {8, 6, 12, 12}, 300}}));
  images.push_back(rect_image(0, 1, size, {{3, {20, 10, 30, 30}, 450}}));  // partly outside
  images.push_back(rect_image(0, 2, size, {{1, {5, 5, 6, 6}, 600}, {2, {3, 3, 12, 12}, 350}}));
  images.push_back(rect_image(1, 0, size, {}));
  images.push_back(rect_image(1, 4, {17, 9}, {{2, {0, 0, 17, 9}, 700}, {1, {4, 2, 5, 4}, 200}}));
  images.push_back(rect_image(1, 7, size, {{3, {1, 1, 31, 23}, 800}, {1, {9, 9, 3, 2}, 650}}));
  return images;
}

}  // namespace flexsight::dataset_test_support

#pragma once
// The ground truth of a detection evaluation, read by the dataset module's BOP and COCO
// readers: the boxes of every image, the ids a results file names images by, and the
// picture of an image when one is wanted (the montage).
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/eval/detection_metrics.h"

namespace flexsight {

class BopReader;
class CocoReader;

struct DetectionImage {
  std::int64_t coco_id = -1;      // the COCO file's image id; -1 for a BOP folder
  int scene_id = -1, im_id = -1;  // BOP's ids; -1 when a COCO file lacks them
  std::vector<TruthBox> truth;
};

class DetectionGroundTruth {
 public:
  enum class Format { coco, bop };

  // `path` is one of:
  //  * a COCO instances file: boxes are the annotations' bbox, area and iscrowd;
  //  * a folder that holds coco_instances.json (what flexsight synth writes, beside the
  //    BOP scene folders): that file is read, being what COCO tools score against;
  //  * a BOP scene or split folder: boxes are scene_gt_info.json's bbox_visib, without
  //    the parts that have visib_fract 0 or an empty bbox_visib; area = width x height.
  // Throws InputError naming the path for what the readers refuse, and for a BOP scene
  // without scene_gt_info.json. In a BOP folder, parts with a visib_fract below
  // `min_visible_fraction` become crowd regions (neither found nor missed, as eval-pick
  // treats parts less than 10 % visible); a COCO file has no visible fraction, so there
  // it must be 0.
  explicit DetectionGroundTruth(const std::string& path, double min_visible_fraction = 0);
  ~DetectionGroundTruth();
  DetectionGroundTruth(DetectionGroundTruth&&) noexcept;

  Format format() const { return format_; }
  // The COCO file or the BOP folder that was read.
  const std::string& source() const { return source_; }
  // COCO: in ascending image id (COCOeval's order); BOP: in (scene_id, im_id) order.
  const std::vector<DetectionImage>& images() const { return images_; }
  // Ascending id. COCO: the file's categories (or, when it lists none, the ids its
  // annotations use); BOP: the obj_ids its scene_gt.json files name, as "obj_NN" (a BOP
  // folder has no list of objects of its own).
  const std::vector<DetectionCategory>& categories() const { return categories_; }
  // Image i's picture, RGB (CV_8UC3). Throws InputError naming a missing or unreadable
  // image file.
  cv::Mat load_rgb(std::size_t i) const;
  // The up-front pass of a command that will load images 0..loaded_count-1: their sizes
  // read from the files' headers and checked against the boxes (BOP) or the file's sizes
  // (COCO); images past loaded_count are checked when they are there. Throws InputError
  // naming the file, as load_rgb would later. Returns each image's size from its header
  // (empty for an image that was not there, or a BOP scene without scene_gt_info.json).
  std::vector<cv::Size> check_images(std::size_t loaded_count) const;

 private:
  void read_coco_file(const std::string& path);
  void read_bop_folder(const std::string& path, double min_visible_fraction);

  Format format_ = Format::coco;
  std::string source_;
  std::vector<DetectionImage> images_;
  std::vector<DetectionCategory> categories_;
  std::unique_ptr<CocoReader> coco_;
  std::unique_ptr<BopReader> bop_;
  std::vector<std::size_t> reader_index_;  // images_[i] is the readers' image reader_index_[i]
};

}  // namespace flexsight

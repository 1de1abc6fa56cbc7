#include "host/synth/patch_cutting.h"

#include <algorithm>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"
#include "host/synth/patch_library.h"

namespace flexsight {

std::int64_t cut_patches(const BopReader& reader, const std::string& source, const std::string& folder,
                         double min_visible, double min_pixels, ProgressBar& progress) {
  std::int64_t written = 0;
  for (std::size_t i = 0; i < reader.size(); ++i) {
    const AnnotatedImage image = reader.load(i);
    for (std::size_t gt_id = 0; gt_id < image.parts.size(); ++gt_id) {
      PartAnnotation part = image.parts[gt_id];
      if (part.mask_visib.empty()) {
        throw InputError(source, "scene " + std::to_string(image.scene_id) + " has no mask_visib/ "
                                 "(needed to cut patches)");
      }
      if (part.px_count_visib == 0) {
        // No scene_gt_info.json: the counts from the masks. Without the amodal mask
        // the visible fraction is unknown; the part is taken as whole (T-LESS's
        // training images show each part alone).
        part.px_count_visib = cv::countNonZero(part.mask_visib);
        part.visib_fract = part.mask.empty() ? 1.0
                                             : part.px_count_visib /
                                                   std::max(1.0, double(cv::countNonZero(part.mask)));
      }
      if (part.visib_fract < min_visible || part.px_count_visib < min_pixels) continue;
      const cv::Rect box = cv::boundingRect(part.mask_visib);
      const std::string path = folder + "/" +
          patch_file_name(part.obj_id, image.scene_id, image.im_id, static_cast<int>(gt_id));
      std::filesystem::create_directories(std::filesystem::path(path).parent_path());
      write_patch(path, image.rgb(box), part.mask_visib(box));
      ++written;
    }
    progress.advance();
  }
  return written;
}

}  // namespace flexsight

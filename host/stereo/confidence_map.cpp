#include "host/stereo/confidence_map.h"

#include <algorithm>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "fallback/stereo/image_pyramid.h"
#include "fallback/stereo/weight_table.h"
#include "host/stereo/pipeline_rules.h"
#include "kernels/stereo/pms_math.h"
#include "kernels/stereo/postprocess_math.h"

namespace flexsight {

cv::Mat confidence_map(const StereoResult& result, const cv::Mat& left_rgb8,
                       const StereoParams& params) {
  CV_Assert(result.raw_left.type() == CV_32FC1 && result.cost_left.type() == CV_32FC1);
  CV_Assert(result.raw_left.isContinuous() && result.raw_right.isContinuous());
  const int width = result.raw_left.cols;
  const int height = result.raw_left.rows;
  const ViewImage left = make_view_image(left_rgb8);
  const std::vector<float> weights =
      make_support_weight_table(params.gamma, params.gamma_distance);
  const int levels = pipeline_level_count(params, width, height);
  const PmsCostParams cost = plan_level(params, 0, levels, width, height).cost;
  // The census term counts at most census_cap of its 24 bits.
  const float max_dissimilarity = cost.one_minus_alpha * cost.tau_color +
                                  cost.alpha * cost.tau_gradient +
                                  cost.census_weight * cost.census_cap;
  const float* raw_left = result.raw_left.ptr<float>();
  const float* raw_right = result.raw_right.ptr<float>();

  cv::Mat agreement(height, width, CV_32FC1), match(height, width, CV_32FC1);
  cv::parallel_for_(cv::Range(0, height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      for (int x = 0; x < width; ++x) {
        agreement.at<float>(y, x) = pms_confidence(raw_left, raw_right, width, x, y, -1.0f);
        const float weight_sum =
            pms_support_weight_sum(left.color.data(), weights.data(), width, height, cost, x, y);
        const float mean_cost = result.cost_left.at<float>(y, x) / weight_sum;
        match.at<float>(y, x) = std::clamp(
            (max_dissimilarity - mean_cost) / (kMatchSpread * max_dissimilarity), 0.0f, 1.0f);
      }
    }
  });
  cv::Mat neighbourhood;
  cv::blur(agreement, neighbourhood, cv::Size(kAgreementWindow, kAgreementWindow),
           cv::Point(-1, -1), cv::BORDER_REPLICATE);

  cv::Mat confidence(height, width, CV_32FC1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float own = agreement.at<float>(y, x);
      const float around = neighbourhood.at<float>(y, x);
      const float agreed = own > 0.5f ? around : std::min(own, around);
      confidence.at<float>(y, x) = agreed * match.at<float>(y, x);
    }
  }
  return confidence;
}

}  // namespace flexsight

// The reference matcher: the matcher's one schedule (patchmatch_schedule.h) over the
// reference stage set (fallback/stereo/reference_stage_set.h).
#include "host/stereo/stereo_pipeline.h"

#include <omp.h>

#include "fallback/stereo/reference_stage_set.h"
#include "host/stereo/patchmatch_schedule.h"

namespace flexsight {

double StereoResult::total_seconds() const {
  double total = 0;
  for (const StageTiming& t : timings) total += t.seconds;
  return total;
}

StereoResult run_stereo(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                        const StereoParams& params, const ProgressCallback& progress) {
  ReferenceStageSet stages(params.threads > 0 ? params.threads : omp_get_num_procs());
  return PatchMatchSchedule<ReferenceStageSet>(stages, params, progress).run(left_rgb8,
                                                                              right_rgb8);
}

}  // namespace flexsight

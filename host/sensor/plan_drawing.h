#pragma once
// The pictures of a sensor plan, after the paper's Fig. 4: the devices, their frustums
// (green: cameras, orange: projector) and the working volume (grey), red where the
// volume is not seen by all three (the darker, the larger the share of the column).
// Top view: x across, z down the page (the sensor at the top, as in Fig. 4); side view:
// y across, z down the page.
#include <opencv2/core.hpp>

#include "host/sensor/sensor_geometry.h"
#include "host/sensor/volume_coverage.h"

namespace flexsight {

cv::Mat draw_top_view(const StereoRig& rig, const WorkingVolume& volume, const VolumeCoverage& coverage);
cv::Mat draw_side_view(const StereoRig& rig, const WorkingVolume& volume, const VolumeCoverage& coverage);

}  // namespace flexsight

#include "host/pose/pose_drawing.h"

#include <opencv2/imgproc.hpp>

namespace flexsight {

void draw_posed_parts(cv::Mat& bgr, const std::vector<PosedPart>& parts, const PinholeCamera& camera) {
  for (const PosedPart& part : parts) {
    RenderScene scene;
    const int mesh = scene.add_mesh(part.mesh);
    scene.add_instance(mesh, part.pose);
    scene.commit();
    RaycastOptions options;
    options.areas.push_back(projected_area(*part.mesh, part.pose, camera));
    if (options.areas.back().empty()) continue;
    const RaycastImages images = raycast(scene, camera, options);
    cv::Mat mask = images.instance >= 0;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(bgr, contours, -1, part.colour, 2, cv::LINE_AA);
    if (!part.label.empty() && !contours.empty()) {
      const cv::Rect box = cv::boundingRect(contours.front());
      cv::putText(bgr, part.label, cv::Point(box.x, std::max(12, box.y - 4)), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                  part.colour, 1, cv::LINE_AA);
    }
  }
}

}  // namespace flexsight

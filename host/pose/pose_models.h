#pragma once
// What pose estimation reads before it starts (`flexsight pose`, the pick job): the
// template file and the CAD models of the parts it names, checked against each other, so
// that a missing model or template is an error before any work.
#include <map>
#include <memory>
#include <string>

#include "host/dataset/bop_reader.h"
#include "host/geometry/stereo_camera.h"
#include "host/pose/edge_template.h"
#include "host/pose/pose_estimator.h"
#include "host/synth/part_library.h"

namespace flexsight {

// The pinhole camera of a BOP image (its K and size).
PinholeCamera camera_of(const AnnotatedImage& image);

class PoseModels {
 public:
  // Throws InputError naming the file or folder for a template file that cannot be
  // read, a CAD folder that cannot, or a template part without a CAD model.
  PoseModels(const std::string& templates_path, const std::string& cad_dir);
  // The models point into the template set this object holds.
  PoseModels(const PoseModels&) = delete;
  PoseModels& operator=(const PoseModels&) = delete;
  // The model of obj_id; InputError naming `where` when neither templates nor CAD have it.
  const PoseModel& model(int obj_id, const std::string& where) const;
  bool has(int obj_id) const { return models_.count(obj_id) > 0; }
  const Mesh& mesh(int obj_id) const { return *models_.at(obj_id).mesh; }

 private:
  TemplateSet templates_;
  std::map<int, PoseModel> models_;
  std::string templates_path_, cad_dir_;
};

}  // namespace flexsight

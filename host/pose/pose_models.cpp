#include "host/pose/pose_models.h"

#include "host/io/input_error.h"
#include "host/pose/template_file.h"

namespace flexsight {

PinholeCamera camera_of(const AnnotatedImage& image) {
  PinholeCamera camera;
  camera.fx = image.camera.K(0, 0);
  camera.fy = image.camera.K(1, 1);
  camera.cx = image.camera.K(0, 2);
  camera.cy = image.camera.K(1, 2);
  camera.width = image.rgb.cols;
  camera.height = image.rgb.rows;
  return camera;
}

PoseModels::PoseModels(const std::string& templates_path, const std::string& cad_dir)
    : templates_(read_template_set(templates_path)), templates_path_(templates_path), cad_dir_(cad_dir) {
  const PartLibrary library = PartLibrary::load_folder(cad_dir);
  for (const PartTemplates& part : templates_.parts) {
    const int index = library.index_of(part.obj_id);
    if (index < 0) {
      throw InputError(cad_dir, "has no CAD model of object " + std::to_string(part.obj_id) +
                                    " (the templates in " + templates_path + " have one)");
    }
    PoseModel model;
    model.obj_id = part.obj_id;
    model.mesh = library.part(index).mesh;
    model.templates = &part;
    model.in_plane_steps = templates_.params.in_plane_steps;
    if (std::abs(model.mesh->diameter - part.diameter) > 1e-3f * part.diameter) {
      throw InputError(cad_dir, "object " + std::to_string(part.obj_id) + "'s model is not the one the templates in " +
                                    templates_path + " were made from (diameter " +
                                    std::to_string(model.mesh->diameter) + " mm, templates " +
                                    std::to_string(part.diameter) + " mm)");
    }
    models_.emplace(part.obj_id, model);
  }
}

const PoseModel& PoseModels::model(int obj_id, const std::string& where) const {
  auto it = models_.find(obj_id);
  if (it == models_.end()) {
    throw InputError(where, "asks for object " + std::to_string(obj_id) + ", which the templates in " +
                                templates_path_ + " do not have");
  }
  return it->second;
}

}  // namespace flexsight

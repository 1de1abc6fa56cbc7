#include "host/dataset/detection_data.h"

#include <cstdlib>

namespace flexsight {

std::string detection_data_dir() {
  if (const char* folder = std::getenv("FLEXSIGHT_DETECTION_DATA"); folder && *folder) {
    return folder;
  }
  return FLEXSIGHT_DEFAULT_DETECTION_DATA;
}

std::string default_cad_dir() { return detection_data_dir() + "/cad/tless"; }

std::string default_backgrounds_dir() { return detection_data_dir() + "/backgrounds"; }

}  // namespace flexsight

#pragma once
#include <string>
#include <vector>

namespace flexsight {

// Each returns the process exit code; arguments exclude the program and command names.
int run_stereo_command(std::vector<std::string> args);
int run_eval_command(std::vector<std::string> args);
int run_eval_det_command(std::vector<std::string> args);
int run_eval_pose_command(std::vector<std::string> args);
int run_devices_command(std::vector<std::string> args);
int run_cloud_command(std::vector<std::string> args);
int run_render_command(std::vector<std::string> args);
int run_synth_command(std::vector<std::string> args);
int run_detect_command(std::vector<std::string> args);
int run_pose_templates_command(std::vector<std::string> args);
int run_pose_command(std::vector<std::string> args);
int run_pick_command(std::vector<std::string> args);
int run_eval_pick_command(std::vector<std::string> args);
int run_serve_command(std::vector<std::string> args);
int run_sensor_plan_command(std::vector<std::string> args);
int run_projector_command(std::vector<std::string> args);

}  // namespace flexsight

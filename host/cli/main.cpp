// flexsight: command-line entry point. Errors a user can cause (InputError) are printed
// as one line and give exit code 1; anything else is a bug and gives exit code 2.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "host/cli/commands.h"
#include "host/io/input_error.h"

namespace {

void print_usage() {
  std::cout << "usage: flexsight <command> [options]\n"
               "  stereo LEFT RIGHT -o DISP.pfm [options]   match a rectified pair\n"
               "  stereo SCENE_FOLDER -o DISP.pfm [options] match a MiddEval3 scene (ndisp from calib.txt)\n"
               "  eval DATASET_ROOT [options]               score the matcher on a benchmark folder\n"
               "  eval-det DATASET --out DIR [--model M.onnx]  score the detector (VOC, COCO AP)\n"
               "  eval-pose DATASET --results POSES.csv --out DIR  score 6D poses (BOP: ADD(-S), AR)\n"
               "  cloud DISP.pfm LEFT --calib FILE -o CLOUD.ply  disparity to depth and a point cloud\n"
               "  render MESH [MESH ...] -o IMAGE.png       a picture of CAD parts (STL, PLY, OBJ)\n"
               "  synth full|semi|patches|merge|bin ...     synthetic training data (BOP + COCO), stereo bins\n"
               "  detect IMAGE... [-o DETS.json] [options]  find the parts in images (SSD detector)\n"
               "  pose DATASET --gt-boxes --templates T --out DIR  6D poses of parts (D2CO + ICP)\n"
               "  pose-templates CAD_DIR -o TEMPLATES       edge templates of the parts, for pose\n"
               "  pick LEFT RIGHT --calib C --templates T   stereo, detection, poses: the parts ranked for a robot\n"
               "  eval-pick BINS_DIR --out DIR --templates T  pick on simulated bins, scored against their truth\n"
               "  serve --templates T [--port P] [options]  pick as a warm HTTP service (docs/serve.md)\n"
               "  sensor-plan [options] [-o DIR]            camera/projector placement: coverage, depth resolution\n"
               "  projector decode|calibrate ...            the projector as a third view (docs/projector.md)\n"
               "  devices                                   list the OpenCL platforms and devices\n"
               "Run 'flexsight <command> --help' for the options of a command.\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    print_usage();
    return 1;
  }
  const std::string command = argv[1];
  std::vector<std::string> args(argv + 2, argv + argc);
  try {
    if (command == "stereo") return flexsight::run_stereo_command(args);
    if (command == "eval") return flexsight::run_eval_command(args);
    if (command == "eval-det") return flexsight::run_eval_det_command(args);
    if (command == "eval-pose") return flexsight::run_eval_pose_command(args);
    if (command == "cloud") return flexsight::run_cloud_command(args);
    if (command == "devices") return flexsight::run_devices_command(args);
    if (command == "render") return flexsight::run_render_command(args);
    if (command == "synth") return flexsight::run_synth_command(args);
    if (command == "detect") return flexsight::run_detect_command(args);
    if (command == "pose") return flexsight::run_pose_command(args);
    if (command == "pick") return flexsight::run_pick_command(args);
    if (command == "eval-pick") return flexsight::run_eval_pick_command(args);
    if (command == "serve") return flexsight::run_serve_command(args);
    if (command == "pose-templates") return flexsight::run_pose_templates_command(args);
    if (command == "sensor-plan") return flexsight::run_sensor_plan_command(args);
    if (command == "projector") return flexsight::run_projector_command(args);
    if (command == "--help" || command == "-h" || command == "help") {
      print_usage();
      return 0;
    }
    std::cerr << "flexsight: unknown command '" << command << "'\n";
    print_usage();
    return 1;
  } catch (const flexsight::InputError& error) {
    std::cerr << "flexsight " << command << ": error: " << error.what() << "\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "flexsight " << command << ": internal error: " << error.what() << "\n";
    return 2;
  }
}

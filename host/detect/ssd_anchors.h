#pragma once
// SSD anchors: the boxes the network's outputs are relative to, one per output row,
// as N x 4 floats (ycenter, xcenter, height, width) normalised to [0, 1] of the input.
//
// A trained model's anchors come in a sidecar file beside the ONNX file, written by the
// training script; its format (docs/detect.md) is a CSV text file:
//
//   ycenter,xcenter,height,width                    <- this header, exactly
//   0.0263157897,0.0263157897,0.100000001,0.100000001
//   ...                                             <- one anchor a line, in output order
//
// (NumPy writes it with np.savetxt(path, anchors, fmt="%.9g", delimiter=",",
//  header="ycenter,xcenter,height,width", comments=""); 9 significant digits give the
// float32 values back exactly.) generate_ssd_anchors makes the TF OD API's anchor set
// itself, for tests and as the reference the training script must reproduce.
#include <string>
#include <vector>

namespace flexsight {

// The TF OD API's ssd_anchor_generator (create_ssd_anchors in
// anchor_generators/multiple_grid_anchor_generator.py) for a square input, with the
// ssd_mobilenet_v2 config as defaults.
struct SsdAnchorConfig {
  // Side of each square feature map, finest first (300x300 input: 19 ... 1).
  std::vector<int> feature_maps = {19, 10, 5, 3, 2, 1};
  // Layer i's scale is min_scale + (max_scale - min_scale) i / (layers - 1).
  float min_scale = 0.2f;
  float max_scale = 0.95f;
  // One anchor per ratio (width / height) on every layer but a reduced lowest one.
  std::vector<float> aspect_ratios = {1.0f, 2.0f, 0.5f, 3.0f, 0.3333f};
  // Plus one anchor of scale sqrt(s_i s_{i+1}) (s after the last layer: 1) with this
  // ratio; 0 for none.
  float interpolated_scale_aspect_ratio = 1.0f;
  // The lowest layer gets only (scale 0.1, ratio 1), (s_0, 2), (s_0, 0.5).
  bool reduce_boxes_in_lowest_layer = true;
};

// ssd_mobilenet_v2 at 300x300: 19*19*3 + (10*10 + 5*5 + 3*3 + 2*2 + 1*1)*6.
constexpr int kSsdMobileNetV2AnchorCount = 1917;

// The anchors, layer by layer, then row, column, box spec (TF's tile_anchors order):
// centres at (i + 0.5) / side, height = scale / sqrt(ratio), width = scale *
// sqrt(ratio), all in float as TF computes them (TF then goes through corners and back
// to centre and size before decoding, which can change the last bit).
std::vector<float> generate_ssd_anchors(const SsdAnchorConfig& config = {});

// The anchors of a file in the format above. `expected_count` (the model's output rows;
// 0: any) must match. Throws InputError naming the file (and the line) for a missing or
// unreadable file, a wrong header, a malformed line, a value that is not finite, a
// height or width that is not positive, or a count other than expected_count.
std::vector<float> read_anchor_file(const std::string& path, int expected_count);

// Writes `anchors` (N x 4) in the format above (under a temporary name, then renamed).
void write_anchor_file(const std::string& path, const std::vector<float>& anchors);

}  // namespace flexsight

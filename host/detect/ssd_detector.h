#pragma once
// The SSD detector: a trained model folder (detector_model.h) run on images. Built once,
// then detect() per image, by `flexsight detect`, `flexsight eval-det --model` and the
// picking pipeline alike:
//
//   SsdDetector detector("models/tless-ssd/model.onnx");          // loads and checks it all
//   std::vector<ObjectDetection> found = detector.detect(bgr);    // boxes in bgr's pixels
//
// Three stages per image, each timed:
//   1. preprocess: cv::dnn::blobFromImage(bgr, 1 / 127.5, {size, size}, {127.5, 127.5,
//      127.5}, swapRB = true): resized (bilinear, no crop, aspect not kept), RGB, [-1, 1],
//      the training's input (scripts/detect/export_onnx.py);
//   2. forward: OpenCV DNN (readNetFromONNX, backend OpenCV, target CPU or OpenCL) to the
//      outputs "box_encodings" [1, N, 4] and "class_logits" [1, N, C + 1];
//   3. post-process: SsdPostprocessor (decode, scores, per-class NMS, overall cut) on the
//      process's ComputeBackend, with the model's score function (model.json), boxes then
//      scaled to the image's pixels and classes mapped to labels.txt's category ids.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/detect/detection.h"
#include "host/detect/detector_model.h"
#include "host/detect/known_parts.h"
#include "host/detect/ssd_params.h"
#include "host/runtime/compute_backend.h"

namespace flexsight {

// Where OpenCV DNN runs the network.
enum class DnnTarget {
  // OpenCV's CPU layers (threads: cv::setNumThreads).
  Cpu,
  // OpenCV's OpenCL layers on OpenCV's own OpenCL device (its T-API context, not the
  // post-processing's: a GPU unless OPENCV_OPENCL_DEVICE says otherwise). OpenCV 4.6 DNN
  // takes only GPUs unless OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES=1 (on other devices it
  // would fall back to its CPU layers quietly; the detector refuses instead). On PoCL it
  // is some 35x slower than Cpu.
  OpenCl,
};

// "cpu" or "opencl"; InputError naming `subject` otherwise.
DnnTarget parse_dnn_target(const std::string& text,
                           const std::string& subject = "option --dnn-target");
const char* dnn_target_name(DnnTarget target);

struct SsdDetectorOptions {
  // A class's score must exceed this for its box to be a candidate (SsdPostprocessParams;
  // the score function and the box scale are the model's, from model.json).
  float score_threshold = 0.3f;
  // A candidate is suppressed when its IoU with a better survivor of its class exceeds this.
  float iou_threshold = 0.6f;
  // Candidates of each class that enter NMS (1..1024).
  int top_k_per_class = 100;
  // Detections returned at most per image.
  int max_detections = 100;
  // Where the network runs.
  DnnTarget dnn_target = DnnTarget::Cpu;
  // The parts the cell handles (known_parts.h): only their classes are scored and
  // returned; empty: every class of the model.
  KnownParts parts;
};

// One detected object in the pixels of the image given to detect().
struct ObjectDetection {
  // The data set's category id of the class (labels.txt), e.g. COCO's "category_id".
  int category_id = 0;
  // The foreground class, 0-based (logit column class_id + 1, labels.txt index - 1).
  int class_id = 0;
  float score = 0.0f;
  // x_min, y_min, x_max, y_max in pixels of the original image (the normalised box times
  // its width and height), clipped to it.
  float box[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  // The anchor the box was decoded from (ties in score are broken by it).
  int anchor = 0;
};

// Seconds each stage of one detect() took.
struct DetectionTimes {
  double preprocess = 0.0;
  double forward = 0.0;
  double postprocess = 0.0;
};

// The network's outputs for one image, owned: box_encodings N x 4 and class_logits
// N x (C + 1), CV_32F, continuous.
struct SsdNetworkOutputs {
  cv::Mat box_encodings;
  cv::Mat class_logits;
  // The arrays as SsdPostprocessor takes them (valid while this lives).
  SsdOutputs view() const;
};

class SsdDetector {
 public:
  // Loads the model folder of `model_path` and checks it before any image, each problem an
  // InputError naming the file: the ONNX file missing or unreadable by OpenCV, an output
  // missing or not of the shape above, model.json's (detector_model.h), labels.txt's
  // count other than the logit columns - 1, anchors.csv's rows other than the network's
  // output rows; options out of range name the option, a known part that is not a class
  // of the model names --parts. The network runs once on a blank
  // image here, so shapes are known and the first detect() is not slower than the rest.
  // Post-processing runs on `backend` (which must outlive this).
  SsdDetector(const std::string& model_path, ComputeBackend& backend,
              const SsdDetectorOptions& options = {});
  // The same on a ComputeBackend of its own, chosen by `backend_options`.
  explicit SsdDetector(const std::string& model_path, const SsdDetectorOptions& options = {},
                       const BackendOptions& backend_options = {});
  ~SsdDetector();
  SsdDetector(const SsdDetector&) = delete;
  SsdDetector& operator=(const SsdDetector&) = delete;

  // The objects in `bgr` (CV_8UC3, any size), best first; `times` (when given) receives
  // each stage's time. InputError for an empty image or another type.
  std::vector<ObjectDetection> detect(const cv::Mat& bgr, DetectionTimes* times = nullptr);

  // detect()'s stages one by one, for tests and benchmarks.
  cv::Mat preprocess(const cv::Mat& bgr) const;
  SsdNetworkOutputs forward(const cv::Mat& blob);
  std::vector<ObjectDetection> postprocess(const SsdNetworkOutputs& outputs, cv::Size image_size);

  // Rows N of the outputs (= anchors) and foreground classes C.
  int anchor_count() const;
  int class_count() const;
  const std::vector<DetectorLabel>& labels() const;  // C entries, class_id order
  const DetectorSettings& settings() const;
  // The post-processing parameters in use: the options' limits, the model's score
  // function and box scale.
  const SsdPostprocessParams& postprocess_params() const;
  // "network on OpenCV DNN (CPU), post-processing on the OpenCL path on #0 ..." and the
  // like, for the log.
  std::string planned() const;

 private:
  struct Impl;
  void load(const std::string& model_path, ComputeBackend& backend,
            const SsdDetectorOptions& options);
  std::unique_ptr<ComputeBackend> owned_backend_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexsight

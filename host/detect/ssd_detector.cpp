#include "host/detect/ssd_detector.h"

#include <chrono>
#include <cstdlib>
#include <opencv2/core/ocl.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>
#include <utility>

#include "host/detect/ssd_anchors.h"
#include "host/detect/ssd_postprocessor.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

const char* const kInputName = "image";
const char* const kBoxOutput = "box_encodings";
const char* const kLogitOutput = "class_logits";

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// OpenCV logs its own lines for a file it cannot parse or a network it cannot run before
// it throws; our message names the file and carries OpenCV's reason, so its log is
// silenced while loading.
class QuietOpenCvLog {
 public:
  QuietOpenCvLog()
      : previous_(cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT)) {}
  ~QuietOpenCvLog() { cv::utils::logging::setLogLevel(previous_); }
  QuietOpenCvLog(const QuietOpenCvLog&) = delete;
  QuietOpenCvLog& operator=(const QuietOpenCvLog&) = delete;

 private:
  cv::utils::logging::LogLevel previous_;
};

std::string join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

std::string shape_text(const cv::Mat& blob) {
  std::string text = "[";
  for (int d = 0; d < blob.dims; ++d) text += (d ? ", " : "") + std::to_string(blob.size[d]);
  return text + "]";
}

// A [1, N, columns] output as an owned N x columns float matrix (the network's own
// buffers are reused by the next forward).
cv::Mat output_rows(const cv::Mat& blob) {
  cv::Mat rows(blob.size[1], blob.size[2], blob.type(), const_cast<uchar*>(blob.ptr()));
  cv::Mat owned;
  rows.convertTo(owned, CV_32F);
  return owned;
}

cv::dnn::Net read_network(const std::string& path, DnnTarget target) {
  io_detail::require_readable_file(path);
  cv::dnn::Net net;
  try {
    QuietOpenCvLog quiet;
    net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& error) {
    throw InputError(path, "OpenCV cannot read it as an ONNX network: " + error.err);
  }
  if (net.empty()) throw InputError(path, "OpenCV reads no layers from it");
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  if (target == DnnTarget::OpenCl) {
    // useOpenCL() is false when OpenCV has no device context: no runtime, or no device of
    // the kind it looks for (GPUs by default; OPENCV_OPENCL_DEVICE=:CPU: for others).
    if (!cv::ocl::useOpenCL()) {
      throw InputError("option --dnn-target",
                       "opencl: OpenCV has no OpenCL device (it takes GPUs unless "
                       "OPENCV_OPENCL_DEVICE names others, e.g. ':CPU:'); use cpu");
    }
    // OpenCV DNN itself would quietly run on the CPU on any other device than a GPU.
    const cv::ocl::Device& device = cv::ocl::Device::getDefault();
    const char* allow_all = std::getenv("OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES");
    const bool allowed =
        allow_all != nullptr && std::string(allow_all) != "0" && std::string(allow_all) != "";
    if (device.type() != cv::ocl::Device::TYPE_GPU && !allowed) {
      throw InputError("option --dnn-target",
                       "opencl: OpenCV's OpenCL device " + device.name() +
                           " is not a GPU, and OpenCV DNN runs its OpenCL layers on GPUs only "
                           "(OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES=1 overrides that); use cpu");
    }
    net.setPreferableTarget(cv::dnn::DNN_TARGET_OPENCL);
  } else {
    net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  }
  for (const char* name : {kBoxOutput, kLogitOutput}) {
    if (net.getLayerId(name) < 0) {
      throw InputError(path, std::string("has no output '") + name +
                                 "' (its outputs: " + join(net.getUnconnectedOutLayersNames()) +
                                 "); the detector needs box_encodings [1, N, 4] and "
                                 "class_logits [1, N, C + 1]");
    }
  }
  return net;
}

}  // namespace

DnnTarget parse_dnn_target(const std::string& text, const std::string& subject) {
  if (text == "cpu") return DnnTarget::Cpu;
  if (text == "opencl") return DnnTarget::OpenCl;
  throw InputError(subject, "expected cpu or opencl, got '" + text + "'");
}

const char* dnn_target_name(DnnTarget target) {
  return target == DnnTarget::OpenCl ? "opencl" : "cpu";
}

SsdOutputs SsdNetworkOutputs::view() const {
  SsdOutputs outputs;
  outputs.box_encodings = box_encodings.ptr<float>();
  outputs.class_logits = class_logits.ptr<float>();
  outputs.anchors = box_encodings.rows;
  outputs.classes = class_logits.cols - 1;
  return outputs;
}

namespace {

// ", known parts 5,12" for planned(); empty for every class.
std::string known_parts_text(const std::vector<int>& known_classes, const std::vector<DetectorLabel>& labels) {
  if (known_classes.empty()) return "";
  std::string ids;
  for (int c : known_classes) ids += (ids.empty() ? "" : ",") + std::to_string(labels.at(c).category_id);
  return ", known parts " + ids;
}

}  // namespace

struct SsdDetector::Impl {
  DetectorFiles files;
  DetectorSettings settings;
  SsdPostprocessParams params;
  DnnTarget target = DnnTarget::Cpu;
  cv::dnn::Net net;
  int anchors = 0;
  int classes = 0;
  std::vector<DetectorLabel> labels;
  // The known parts' classes (options.parts), ascending; empty: every class.
  std::vector<int> known_classes;
  std::unique_ptr<SsdPostprocessor> post;
};

SsdDetector::SsdDetector(const std::string& model_path, const SsdDetectorOptions& options,
                         const BackendOptions& backend_options)
    : owned_backend_(std::make_unique<ComputeBackend>(backend_options)) {
  load(model_path, *owned_backend_, options);
}

SsdDetector::SsdDetector(const std::string& model_path, ComputeBackend& backend,
                         const SsdDetectorOptions& options) {
  load(model_path, backend, options);
}

void SsdDetector::load(const std::string& model_path, ComputeBackend& backend,
                       const SsdDetectorOptions& options) {
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.files = detector_files(model_path);
  m.settings = read_detector_settings(m.files.settings);
  m.params.score_function = m.settings.score_function;
  m.params.box_scale = m.settings.box_scale;
  m.params.score_threshold = options.score_threshold;
  m.params.iou_threshold = options.iou_threshold;
  m.params.top_k_per_class = options.top_k_per_class;
  m.params.max_detections = options.max_detections;
  m.params.check();
  m.target = options.dnn_target;

  // The network, run once on a mid-grey image: the output shapes it really produces, not
  // what the file claims.
  m.net = read_network(m.files.model, m.target);
  const int size = m.settings.input_size;
  SsdNetworkOutputs blank;
  try {
    QuietOpenCvLog quiet;
    blank = forward(preprocess(cv::Mat(size, size, CV_8UC3, cv::Scalar::all(127.5))));
  } catch (const cv::Exception& error) {
    throw InputError(m.files.model, "OpenCV DNN cannot run it on a [1, 3, " + std::to_string(size) +
                                        ", " + std::to_string(size) + "] input (input_size " +
                                        std::to_string(size) + ", model.json): " + error.err);
  }
  m.anchors = blank.box_encodings.rows;
  m.classes = blank.class_logits.cols - 1;
  if (m.classes < 1 || blank.class_logits.rows != m.anchors) {
    throw InputError(m.files.model,
                     "outputs box_encodings " + shape_text(blank.box_encodings) +
                         " and class_logits " + shape_text(blank.class_logits) +
                         " (as rows x columns); expected N x 4 and N x (C + 1), C >= 1");
  }

  m.labels = read_detector_labels(m.files.labels);
  if (static_cast<int>(m.labels.size()) != m.classes) {
    throw InputError(m.files.labels, "lists " + std::to_string(m.labels.size()) +
                                         " classes besides the background, the model outputs " +
                                         std::to_string(m.classes + 1) + " logit columns (" +
                                         std::to_string(m.classes) +
                                         " classes and the background)");
  }
  m.known_classes = known_part_classes(options.parts, m.labels, m.files.model);
  m.post =
      std::make_unique<SsdPostprocessor>(backend, read_anchor_file(m.files.anchors, m.anchors));
}

SsdDetector::~SsdDetector() = default;

cv::Mat SsdDetector::preprocess(const cv::Mat& bgr) const {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw InputError("detector input", "expected a non-empty 8-bit 3-channel BGR image, got " +
                                           std::to_string(bgr.cols) + "x" +
                                           std::to_string(bgr.rows) + " of type " +
                                           cv::typeToString(bgr.type()));
  }
  const int size = impl_->settings.input_size;
  return cv::dnn::blobFromImage(bgr, 1.0 / 127.5, cv::Size(size, size),
                                cv::Scalar(127.5, 127.5, 127.5), /*swapRB=*/true,
                                /*crop=*/false, CV_32F);
}

SsdNetworkOutputs SsdDetector::forward(const cv::Mat& blob) {
  Impl& m = *impl_;
  m.net.setInput(blob, kInputName);
  std::vector<cv::Mat> blobs;
  m.net.forward(blobs, std::vector<cv::String>{kBoxOutput, kLogitOutput});
  for (size_t i = 0; i < 2; ++i) {
    const int columns = i == 0 ? 4 : 0;  // 0: any
    const cv::Mat& b = blobs[i];
    if (b.dims != 3 || b.size[0] != 1 || b.size[1] < 1 ||
        (columns > 0 ? b.size[2] != columns : b.size[2] < 2)) {
      throw InputError(m.files.model, std::string("output ") +
                                          (i == 0 ? kBoxOutput : kLogitOutput) + " has the shape " +
                                          shape_text(b) + ", expected " +
                                          (i == 0 ? "[1, N, 4]" : "[1, N, C + 1] with C >= 1"));
    }
  }
  SsdNetworkOutputs outputs;
  outputs.box_encodings = output_rows(blobs[0]);
  outputs.class_logits = output_rows(blobs[1]);
  return outputs;
}

std::vector<ObjectDetection> SsdDetector::postprocess(const SsdNetworkOutputs& outputs,
                                                      cv::Size image_size) {
  Impl& m = *impl_;
  // Known parts: the background and their classes' logits only (known_parts.h says why).
  SsdNetworkOutputs known;
  if (!m.known_classes.empty()) {
    known.box_encodings = outputs.box_encodings;
    known.class_logits = known_part_logits(outputs.class_logits, m.known_classes);
  }
  const std::vector<Detection> found =
      m.post->run(m.known_classes.empty() ? outputs.view() : known.view(), m.params);
  std::vector<ObjectDetection> objects;
  objects.reserve(found.size());
  for (const Detection& normalised : found) {
    const Detection d = detection_in_pixels(normalised, image_size.width, image_size.height);
    ObjectDetection object;
    object.class_id = m.known_classes.empty() ? d.class_id : m.known_classes.at(static_cast<size_t>(d.class_id));
    object.category_id = m.labels.at(static_cast<size_t>(object.class_id)).category_id;
    object.score = d.score;
    for (int k = 0; k < 4; ++k) object.box[k] = d.box[k];
    object.anchor = d.anchor;
    objects.push_back(object);
  }
  return objects;
}

std::vector<ObjectDetection> SsdDetector::detect(const cv::Mat& bgr, DetectionTimes* times) {
  auto start = std::chrono::steady_clock::now();
  const cv::Mat blob = preprocess(bgr);
  DetectionTimes spent;
  spent.preprocess = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const SsdNetworkOutputs outputs = forward(blob);
  spent.forward = seconds_since(start);
  start = std::chrono::steady_clock::now();
  std::vector<ObjectDetection> objects = postprocess(outputs, bgr.size());
  spent.postprocess = seconds_since(start);
  if (times) *times = spent;
  return objects;
}

int SsdDetector::anchor_count() const { return impl_->anchors; }
int SsdDetector::class_count() const { return impl_->classes; }
const std::vector<DetectorLabel>& SsdDetector::labels() const { return impl_->labels; }
const DetectorSettings& SsdDetector::settings() const { return impl_->settings; }
const SsdPostprocessParams& SsdDetector::postprocess_params() const { return impl_->params; }

std::string SsdDetector::planned() const {
  const int size = impl_->settings.input_size;
  return "network on OpenCV DNN (" + std::string(dnn_target_name(impl_->target)) + ", " +
         std::to_string(size) + "x" + std::to_string(size) + " input, " +
         std::to_string(impl_->anchors) + " anchors, " + std::to_string(impl_->classes) +
         " classes" + known_parts_text(impl_->known_classes, impl_->labels) + ", " + score_function_name(impl_->params.score_function) +
         " scores), post-processing on the " + impl_->post->planned();
}

}  // namespace flexsight

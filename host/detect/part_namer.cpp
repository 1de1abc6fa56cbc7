#include "host/detect/part_namer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

// OpenCV prints its own parse errors before throwing; ours name the file instead.
class QuietLog {
 public:
  QuietLog() : previous_(cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT)) {}
  ~QuietLog() { cv::utils::logging::setLogLevel(previous_); }
  QuietLog(const QuietLog&) = delete;
  QuietLog& operator=(const QuietLog&) = delete;

 private:
  cv::utils::logging::LogLevel previous_;
};

double number_in(const nlohmann::json& json, const char* key, double low, double high, const std::string& path) {
  const nlohmann::json& value = json.at(key);
  if (!value.is_number() || !(value.get<double>() >= low && value.get<double>() <= high)) {
    throw InputError(path, std::string("\"") + key + "\" must be a number in " + std::to_string(low) + ".." +
                               std::to_string(high) + ", got " + value.dump());
  }
  return value.get<double>();
}

// model.json of a naming model: required, since a detector's folder has one too and its
// network must not be taken for a namer.
NamerSettings read_namer_settings(const std::string& path) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(io_detail::read_whole_file(path));
  } catch (const nlohmann::json::exception& error) {
    throw InputError(path, std::string("is not valid JSON: ") + error.what());
  }
  if (!json.is_object() || json.value("task", "") != "naming") {
    throw InputError(path, "is not a naming model's (\"task\": \"naming\" missing)");
  }
  for (const char* key : {"input_size", "margin", "std_floor"}) {
    if (!json.contains(key)) throw InputError(path, std::string("has no \"") + key + "\"");
  }
  if (json.value("color_order", "") != "grey" || json.value("normalisation", "") != "per_crop_standardise") {
    throw InputError(path, "the namer reads grey crops standardised per crop (\"color_order\": \"grey\", "
                           "\"normalisation\": \"per_crop_standardise\")");
  }
  NamerSettings settings;
  settings.input_size = static_cast<int>(number_in(json, "input_size", 8, 512, path));
  settings.margin = number_in(json, "margin", 0.0, 1.0, path);
  settings.std_floor = number_in(json, "std_floor", 1e-6, 1.0, path);
  return settings;
}

}  // namespace

struct PartNamer::Impl {
  std::string model_path;
  DetectorFiles files;
  NamerSettings settings;
  std::vector<DetectorLabel> labels;
  cv::dnn::Net net;

  std::vector<float> classify(const cv::Mat& crop8) {
    cv::Mat x;
    crop8.convertTo(x, CV_32F, 1.0 / 255.0);
    cv::Scalar mean, stddev;
    cv::meanStdDev(x, mean, stddev);
    x = (x - mean[0]) / (stddev[0] + settings.std_floor);
    const int shape[4] = {1, 1, x.rows, x.cols};
    cv::Mat blob(4, shape, CV_32F, x.ptr<float>());
    net.setInput(blob);
    cv::Mat logits = net.forward();
    logits = logits.reshape(1, 1);
    std::vector<float> p(logits.cols);
    const float* l = logits.ptr<float>();
    const float top = *std::max_element(l, l + logits.cols);
    double sum = 0.0;
    for (int i = 0; i < logits.cols; ++i) sum += p[i] = std::exp(l[i] - top);
    for (float& v : p) v = static_cast<float>(v / sum);
    return p;
  }
};

PartNamer::PartNamer(const std::string& model_path) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.model_path = model_path;
  m.files = detector_files(model_path);
  io_detail::require_readable_file(m.files.model);
  try {
    QuietLog quiet;
    m.net = cv::dnn::readNetFromONNX(m.files.model);
  } catch (const cv::Exception& error) {
    throw InputError(m.files.model, "OpenCV cannot read it as an ONNX network: " + error.err);
  }
  if (m.net.empty()) throw InputError(m.files.model, "OpenCV reads no layers from it");
  m.net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  m.net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  if (!fs::exists(m.files.settings)) throw InputError(m.files.settings, "missing: a naming model needs its model.json");
  m.settings = read_namer_settings(m.files.settings);
  std::vector<float> blank;
  try {
    QuietLog quiet;
    const int s = m.settings.input_size;
    blank = m.classify(cv::Mat(s, s, CV_8UC1, cv::Scalar(128)));
  } catch (const cv::Exception& error) {
    throw InputError(m.files.model, "OpenCV DNN cannot run it on a [1, 1, " + std::to_string(m.settings.input_size) +
                                        ", " + std::to_string(m.settings.input_size) + "] crop: " + error.err);
  }
  m.labels = read_detector_labels(m.files.labels);
  if (blank.size() != m.labels.size()) {
    throw InputError(m.files.labels, "lists " + std::to_string(m.labels.size()) + " parts, the network outputs " +
                                         std::to_string(blank.size()) + " classes");
  }
}

PartNamer::~PartNamer() = default;

cv::Mat PartNamer::crop(const cv::Mat& grey, const float box[4]) const {
  const double w = box[2] - box[0], h = box[3] - box[1];
  const double side = std::max(w, h) * (1.0 + 2.0 * impl_->settings.margin);
  // floor(v + 0.5) on both sides (scripts/detect/naming_data.py's square_crop): the
  // training crops and these must start on the same pixel.
  const int s = std::max(4, static_cast<int>(std::floor(side + 0.5)));
  const int x0 = static_cast<int>(std::floor(box[0] + w / 2.0 - s / 2.0 + 0.5));
  const int y0 = static_cast<int>(std::floor(box[1] + h / 2.0 - s / 2.0 + 0.5));
  const cv::Rect square(x0, y0, s, s);
  const cv::Rect inside = square & cv::Rect(0, 0, grey.cols, grey.rows);
  const int size = impl_->settings.input_size;
  if (inside.empty()) return cv::Mat(size, size, CV_8UC1, cv::Scalar(0));
  cv::Mat patch;
  cv::copyMakeBorder(grey(inside), patch, inside.y - y0, y0 + s - inside.br().y, inside.x - x0, x0 + s - inside.br().x,
                     cv::BORDER_REPLICATE);
  cv::Mat out;
  cv::resize(patch, out, cv::Size(size, size), 0, 0, cv::INTER_AREA);
  return out;
}

std::vector<float> PartNamer::name(const cv::Mat& bgr, const float box[4]) {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw InputError("namer input", "expected a non-empty 8-bit 3-channel BGR image");
  }
  // Only the crop's pixels are converted to grey: a bin has many boxes, each small.
  const double w = box[2] - box[0], h = box[3] - box[1];
  const double reach = std::max(w, h) * (0.5 + impl_->settings.margin) + 2.0;
  const double cx = box[0] + w / 2.0, cy = box[1] + h / 2.0;
  const cv::Rect around = cv::Rect(cv::Point(static_cast<int>(std::floor(cx - reach)), static_cast<int>(std::floor(cy - reach))),
                                   cv::Point(static_cast<int>(std::ceil(cx + reach)), static_cast<int>(std::ceil(cy + reach)))) &
                          cv::Rect(0, 0, bgr.cols, bgr.rows);
  if (around.empty()) return impl_->classify(crop(cv::Mat(1, 1, CV_8UC1, cv::Scalar(0)), box));
  cv::Mat grey;
  cv::cvtColor(bgr(around), grey, cv::COLOR_BGR2GRAY);
  const float shifted[4] = {box[0] - around.x, box[1] - around.y, box[2] - around.x, box[3] - around.y};
  return impl_->classify(crop(grey, shifted));
}

const std::vector<DetectorLabel>& PartNamer::labels() const { return impl_->labels; }
const NamerSettings& PartNamer::settings() const { return impl_->settings; }
const std::string& PartNamer::model_path() const { return impl_->model_path; }

int PartNamer::class_of(int category_id) const {
  for (std::size_t i = 0; i < impl_->labels.size(); ++i) {
    if (impl_->labels[i].category_id == category_id) return static_cast<int>(i);
  }
  return -1;
}

void PartNamer::require_same_parts(const std::vector<DetectorLabel>& detector_labels, const std::string& detector_path) const {
  std::set<int> ours, theirs;
  for (const DetectorLabel& l : impl_->labels) ours.insert(l.category_id);
  for (const DetectorLabel& l : detector_labels) theirs.insert(l.category_id);
  if (ours != theirs) {
    throw InputError(impl_->files.labels, "names " + std::to_string(ours.size()) + " parts that are not the " +
                                              std::to_string(theirs.size()) + " parts of the detector " + detector_path +
                                              ": a namer for other parts");
  }
}

std::string default_namer_model_path() {
  const char* environment = std::getenv("FLEXSIGHT_NAMER_MODEL");
  if (environment != nullptr && *environment != '\0') return environment;
  return FLEXSIGHT_DEFAULT_NAMER_MODEL;
}

}  // namespace flexsight

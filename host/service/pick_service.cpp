#include "host/service/pick_service.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/io/input_error.h"
#include "host/pick/pick_inputs.h"
#include "host/pick/pick_outputs.h"
#include "host/service/pick_request.h"
#include "host/service/request_images.h"
#include "host/stereo/pipeline_rules.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Each stage of a pick (PICKS.json's "seconds") and the pick's own time as /metrics series.
void add_stage_seconds(const PickStageSeconds& s, LatencyMetrics& metrics) {
  const std::pair<const char*, double> stages[] = {
      {"stereo", s.stereo}, {"depth", s.depth}, {"detection", s.detection}, {"naming", s.naming},
      {"segmentation", s.segmentation}, {"pose", s.pose}, {"ranking", s.ranking}, {"pick", s.total()}};
  for (const auto& [stage, seconds] : stages) metrics.add_seconds(stage, seconds);
}

}  // namespace

std::string error_json(int status, const std::string& message) {
  return nlohmann::json{{"error", message}, {"status", status}}.dump() + "\n";
}

PickService::PickService(std::vector<std::string> base_args, PickArgumentParser parser, ServiceLimits limits)
    : base_args_(std::move(base_args)), parser_(std::move(parser)), limits_(limits), queue_(limits.queue) {
  // Without a calibration the parser leaves ndisp alone: each request's sets it.
  loaded_ = parser_(base_args_, "");
  loaded_.quiet = true;
  session_ = std::make_unique<PickSession>(loaded_);
}

PickService::~PickService() { shut_down(); }

void PickService::shut_down() { queue_.close(); }

void PickService::count_answer(int status) { metrics_.count_answer(status); }

std::string PickService::metrics() const { return metrics_.json(); }

std::string PickService::health() const {
  return nlohmann::json{{"status", "ok"},
                        {"models_loaded", session_ != nullptr},
                        {"templates", loaded_.templates},
                        {"model", loaded_.model},
                        {"cad", loaded_.cad},
                        {"queue_depth", queue_.waiting()},
                        {"queue_capacity", limits_.queue},
                        {"running", queue_.busy()}}
             .dump() +
         "\n";
}

ServiceAnswer PickService::pick(const std::string& body) {
  const auto start = Clock::now();
  ServiceAnswer answer;
  try {
    answer = pick_checked(body);
  } catch (const RequestError& e) {
    answer = {e.status(), error_json(e.status(), e.what())};
  } catch (const InputError& e) {
    answer = {400, error_json(400, e.what())};
  } catch (const std::exception& e) {
    answer = {500, error_json(500, std::string("internal error: ") + e.what())};
  }
  // A client told to come back retries after about one pick.
  if (answer.status == 503) answer.retry_after_s = std::max(1, static_cast<int>(std::ceil(metrics_.median("pick"))));
  answer.total_seconds = seconds_since(start);
  metrics_.count_answer(answer.status);
  if (answer.status == 200) metrics_.add_seconds("total", answer.total_seconds);
  return answer;
}

ServiceAnswer PickService::pick_checked(const std::string& body) {
  const auto arrival = Clock::now();
  const PickRequest request = parse_pick_request(body);
  // Image bytes in the body are read through the same files as paths are.
  const RequestImages images_in_body(request);
  const PickInputFiles& files = images_in_body.files();
  PickSettings settings = parser_(merge_pick_arguments(base_args_, request.option_tokens), files.calib);
  settings.quiet = true;
  session_->check_pair_settings(settings);
  PickInputImages images;
  try {
    images = read_pick_inputs(files, settings.detection_tile);
    validate_inputs(images.pair.left, images.pair.right, settings.stereo);
  } catch (const InputError& e) {
    throw RequestError(400, images_in_body.in_request_terms(e.what()));
  }

  ServiceAnswer answer;
  auto job = [&] {
    try {
      session_->set_pair_settings(settings);
      const PickResult result = session_->pick(images.pair.left, images.pair.right, images.rig, images.passive);
      const PickInputsDescription described = {images_in_body.described().left, images_in_body.described().right,
                                               files.calib, settings.model, settings.templates, settings.cad,
                                               images_in_body.described().passive_left, settings.detector.parts.obj_ids};
      answer.body = pick_json(result, described);
      add_stage_seconds(result.seconds, metrics_);
    } catch (const InputError& e) {
      answer = {400, error_json(400, e.what())};
    } catch (const std::exception& e) {
      answer = {500, error_json(500, std::string("internal error: ") + e.what())};
    }
  };
  const auto deadline = arrival + std::chrono::milliseconds(limits_.timeout_ms);
  double waited = 0.0;
  const PickQueue::Outcome outcome = queue_.run(job, deadline, &waited);
  switch (outcome) {
    case PickQueue::Outcome::kDone:
      answer.queue_seconds = waited;
      metrics_.add_seconds("queue_wait", waited);
      return answer;
    case PickQueue::Outcome::kFull:
      throw RequestError(503, "queue: full (" + std::to_string(limits_.queue) + " requests waiting); retry later");
    case PickQueue::Outcome::kTimedOut:
      throw RequestError(503, "queue: not started within --timeout-ms " + std::to_string(limits_.timeout_ms) +
                                  " (waited " + std::to_string(waited) + " s); retry later");
    case PickQueue::Outcome::kClosed:
      throw RequestError(503, "service: shutting down");
  }
  return answer;
}

}  // namespace flexsight

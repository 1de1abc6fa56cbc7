#pragma once
// The pick service without its transport: one PickSession (models loaded once) behind a
// bounded queue, each request's body read into pick's options by pick's own parser, its
// files checked as `flexsight pick` checks them, and its answer the PICKS.json pick -o
// writes. host/service/http_server.h puts it on HTTP; tests call it directly.
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "host/pick/pick_session.h"
#include "host/service/latency_metrics.h"
#include "host/service/pick_queue.h"

namespace flexsight {

// Pick's options (`args`, command-line tokens) read by `flexsight pick`'s parser into the
// settings of one pair whose calibration is `calib` (its ndisp unless --ndisp); InputError
// naming the option for a bad value or an unknown option. The command line hands its
// parser in, so every option pick has works per request without a change here.
using PickArgumentParser = std::function<PickSettings(std::vector<std::string> args, const std::string& calib)>;

struct ServiceLimits {
  // Requests waiting for the pick worker at most; one more is answered 503.
  std::size_t queue = 8;
  // A request not started within this many milliseconds of its arrival leaves the queue
  // unrun and is answered 503.
  long long timeout_ms = 120000;
  // Bodies larger than this many bytes are answered 413.
  std::size_t max_body = 64u << 20;
};

struct ServiceAnswer {
  int status = 200;
  std::string body;          // JSON, one object, ending in a newline
  int retry_after_s = 0;     // > 0: a Retry-After header (503)
  double queue_seconds = 0.0, total_seconds = 0.0;
};

class PickService {
 public:
  // Loads the session from `base_args` (pick's options `flexsight serve` was started
  // with: --templates and the rest) read by `parser`; InputError as pick's.
  PickService(std::vector<std::string> base_args, PickArgumentParser parser, ServiceLimits limits);
  ~PickService();

  // POST /pick: the PICKS.json (200), or a one-line {"error": ...} with 400 (a bad field,
  // option or file), 503 (queue full, not started in time, shutting down) or 500.
  ServiceAnswer pick(const std::string& body);
  // GET /health: {"status": "ok", "models_loaded": true, "queue_depth": n, "running": b, ...}
  std::string health() const;
  // GET /metrics (latency_metrics.h).
  std::string metrics() const;
  // Counts an answer the transport gave itself (413, 404, ...).
  void count_answer(int status);

  // Waiting requests answer 503, the running pick finishes.
  void shut_down();

  const ServiceLimits& limits() const { return limits_; }

 private:
  ServiceAnswer pick_checked(const std::string& body);

  std::vector<std::string> base_args_;
  PickArgumentParser parser_;
  ServiceLimits limits_;
  PickSettings loaded_;
  std::unique_ptr<PickSession> session_;
  LatencyMetrics metrics_;
  PickQueue queue_;
};

// {"error": message, "status": status} on one line.
std::string error_json(int status, const std::string& message);

}  // namespace flexsight

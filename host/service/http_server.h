#pragma once
// The pick service on HTTP (cpp-httplib, docs/serve.md says why): GET /health, POST /pick,
// GET /metrics; 413 for a body over the limit, 404 and 405 for other paths and methods,
// every error a one-line JSON {"error": ...}. SIGTERM and SIGINT stop it cleanly: no new
// connection is taken, waiting requests are answered 503, the running pick finishes.
#include <functional>
#include <string>

#include "host/service/pick_service.h"

namespace flexsight {

struct ServerAddress {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: a free port, chosen when bound
};

// Blocks SIGTERM and SIGINT in the calling thread and in every thread started after it:
// call it first, before any thread exists (the queue's worker, OpenMP's and the OpenCL
// runtime's threads), so that HttpServer::serve's waiter alone takes them; a thread
// that does not block them would let them end the process at once.
void block_stop_signals();

class HttpServer {
 public:
  // `log` receives one line per request (empty: none).
  HttpServer(PickService& service, std::function<void(const std::string&)> log);
  ~HttpServer();

  // Binds `address`; the port bound (the chosen one for port 0). InputError naming
  // --host/--port when it cannot be bound.
  int bind(const ServerAddress& address);
  // Serves until stop() or SIGTERM/SIGINT (block_stop_signals first), then shuts the
  // service down.
  void serve();
  void stop();

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace flexsight

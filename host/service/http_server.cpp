#include "host/service/http_server.h"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <cstdio>
#include <thread>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr const char* kJson = "application/json";

void answer(httplib::Response& res, int status, const std::string& body) {
  res.status = status;
  res.set_content(body, kJson);
}

sigset_t stop_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  return signals;
}

}  // namespace

struct HttpServer::Impl {
  PickService& service;
  std::function<void(const std::string&)> log;
  httplib::Server server;
  std::thread signal_waiter;
  std::atomic<bool> stopping{false};
  std::string where;

  Impl(PickService& s, std::function<void(const std::string&)> l) : service(s), log(std::move(l)) {
    server.set_payload_max_length(service.limits().max_body);
    // SO_REUSEADDR alone: a restart may take its port back from TIME_WAIT, but a port
    // another process listens on is refused (httplib's default, SO_REUSEPORT, would let a
    // second serve share the port and take half of the requests).
    server.set_socket_options([](socket_t sock) {
      int yes = 1;
      ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    // One thread per waiting request, the running one and a few for /health and /metrics.
    const std::size_t threads = service.limits().queue + 4;
    server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
    server.Get("/health", [this](const httplib::Request&, httplib::Response& res) {
      answer(res, 200, service.health());
    });
    server.Get("/metrics", [this](const httplib::Request&, httplib::Response& res) {
      answer(res, 200, service.metrics());
    });
    server.Post("/pick", [this](const httplib::Request& req, httplib::Response& res) {
      const ServiceAnswer a = service.pick(req.body);
      answer(res, a.status, a.body);
      if (a.retry_after_s > 0) res.set_header("Retry-After", std::to_string(a.retry_after_s));
      if (log) {
        char line[160];
        std::snprintf(line, sizeof line, "serve: POST /pick %d %.3f s (queue %.3f s)", a.status, a.total_seconds,
                      a.queue_seconds);
        log(a.status == 200 ? std::string(line) : std::string(line) + " " + a.body.substr(0, a.body.size() - 1));
      }
    });
    // Answers httplib gives itself (413 over the body limit, 404, 405, 400 for a broken
    // request line): a JSON one-liner like every other error, and counted.
    server.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;  // a handler's own answer (POST /pick's 4xx and 5xx)
      std::string message;
      if (res.status == 413) {
        message = "body: larger than --max-body " + std::to_string(service.limits().max_body) + " bytes";
      } else if (res.status == 404) {
        message = req.method + " " + req.path + ": not found (GET /health, POST /pick, GET /metrics)";
      } else if (res.status == 405) {
        message = "method " + req.method + ": not allowed on " + req.path;
      } else {
        message = "request: refused with HTTP " + std::to_string(res.status);
      }
      answer(res, res.status, error_json(res.status, message));
      service.count_answer(res.status);
      if (log) log("serve: " + req.method + " " + req.path + " " + std::to_string(res.status) + " " + message);
    });
  }
};

HttpServer::HttpServer(PickService& service, std::function<void(const std::string&)> log)
    : impl_(new Impl(service, std::move(log))) {}

HttpServer::~HttpServer() {
  stop();
  if (impl_->signal_waiter.joinable()) {
    ::pthread_kill(impl_->signal_waiter.native_handle(), SIGTERM);
    impl_->signal_waiter.join();
  }
  delete impl_;
}

int HttpServer::bind(const ServerAddress& address) {
  impl_->where = address.host + ":" + std::to_string(address.port);
  if (address.port == 0) {
    const int port = impl_->server.bind_to_any_port(address.host);
    if (port <= 0) throw InputError("option --host", "cannot listen on " + address.host);
    return port;
  }
  if (!impl_->server.bind_to_port(address.host, address.port)) {
    throw InputError("option --port", "cannot listen on " + impl_->where + " (in use, or not this machine's address)");
  }
  return address.port;
}

void block_stop_signals() {
  const sigset_t signals = stop_signals();
  ::pthread_sigmask(SIG_BLOCK, &signals, nullptr);
}

void HttpServer::serve() {
  // A thread of its own waits for SIGTERM and SIGINT and stops the server: a signal
  // handler could take no lock.
  const sigset_t signals = stop_signals();
  ::signal(SIGPIPE, SIG_IGN);  // a client gone mid-answer is an error to write, not a death
  impl_->signal_waiter = std::thread([this, signals] {
    int received = 0;
    ::sigwait(&signals, &received);
    stop();
  });
  impl_->server.listen_after_bind();
  impl_->service.shut_down();
}

void HttpServer::stop() {
  if (impl_->stopping.exchange(true)) return;
  impl_->server.stop();
  impl_->service.shut_down();
}

}  // namespace flexsight

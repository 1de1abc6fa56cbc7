// flexsight serve: pick as a warm service on HTTP (host/service/; docs/serve.md).
#include <iostream>
#include <mutex>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/cli/pick_options.h"
#include "host/io/input_error.h"
#include "host/service/http_server.h"
#include "host/service/pick_service.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight serve --templates T [--cad DIR] [--model M] [--host H] [--port P] [options]\n"
               "One warm process that loads the detector, the templates, the CAD parts and the OpenCL\n"
               "context once and answers pick requests over HTTP (docs/serve.md): GET /health,\n"
               "POST /pick with {\"left\": PATH, \"right\": PATH, \"calib\": PATH, ...pick's options}\n"
               "answered with the PICKS.json of flexsight pick -o, GET /metrics. One pick runs at a\n"
               "time; the others wait in a bounded queue.\n"
               "  --host H           the address to listen on (default 127.0.0.1: this machine only)\n"
               "  --port P           the port (default 8080; 0: a free one, printed when ready)\n"
               "  --queue N          requests waiting at most (1..1024, default 8); one more is\n"
               "                     answered 503 with Retry-After\n"
               "  --timeout-ms N     a request not started within N ms of its arrival leaves the\n"
               "                     queue unrun, answered 503 (default 120000); a running pick\n"
               "                     is never cut short\n"
               "  --max-body BYTES   larger request bodies are answered 413 (default 64M; K, M, G)\n"
               "  --quiet            no line per request (the ready line stays)\n"
               "pick's options (flexsight pick --help) are the session's: --templates, --cad, --model,\n"
               "--namer, --parts, --score and the backend's are loaded once and fixed; the others are\n"
               "each request's defaults, which a request's keys override.\n"
            << pick_options_help();
}

// Pick's parser on one request's arguments (host/service/pick_service.h).
PickSettings parse_request_settings(std::vector<std::string> args, const std::string& calib) {
  PickOptions options = take_pick_options(args);
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("option value '" + args.front() + "'", "follows no option that takes a value");
  if (!calib.empty()) options.settings.stereo.ndisp = pick_ndisp(options, calib);
  return options.settings;
}

struct ServeOptions {
  ServerAddress address;
  ServiceLimits limits;
};

ServeOptions take_serve_options(std::vector<std::string>& args) {
  ServeOptions options;
  const std::string host = take_option(args, "--host");
  const std::string port = take_option(args, "--port");
  const std::string queue = take_option(args, "--queue");
  const std::string timeout = take_option(args, "--timeout-ms");
  const std::string max_body = take_option(args, "--max-body");
  if (!host.empty()) options.address.host = host;
  if (!port.empty()) options.address.port = static_cast<int>(parse_whole_number("--port", port, 0, 65535));
  if (!queue.empty()) options.limits.queue = static_cast<std::size_t>(parse_whole_number("--queue", queue, 1, 1024));
  if (!timeout.empty()) options.limits.timeout_ms = parse_whole_number("--timeout-ms", timeout, 1, 86400000);
  if (!max_body.empty()) {
    const std::optional<size_t> bytes = parse_byte_size(max_body);
    if (!bytes) throw InputError("option --max-body", "expected a positive size in bytes (or K, M, G), got '" + max_body + "'");
    options.limits.max_body = *bytes;
  }
  return options;
}

}  // namespace

int run_serve_command(std::vector<std::string> args) {
  block_stop_signals();
  if (auto code = usage_exit_code(args, print_help)) return *code;
  const ServeOptions options = take_serve_options(args);
  // The session's options checked before anything is loaded.
  const bool quiet = parse_request_settings(args, "").quiet;

  PickService service(args, parse_request_settings, options.limits);
  std::mutex log_mutex;
  auto log = [&](const std::string& line) {
    std::lock_guard<std::mutex> lock(log_mutex);
    std::cout << line << std::endl;
  };
  HttpServer server(service, quiet ? std::function<void(const std::string&)>() : log);
  const int port = server.bind(options.address);
  log("serve: listening on http://" + options.address.host + ":" + std::to_string(port) + " (queue " +
      std::to_string(options.limits.queue) + ", timeout " + std::to_string(options.limits.timeout_ms) + " ms, max body " +
      std::to_string(options.limits.max_body) + " bytes)");
  server.serve();
  log("serve: stopped");
  return 0;
}

}  // namespace flexsight

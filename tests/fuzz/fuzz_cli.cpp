// The command line's option parsing (host/cli/arguments.h), as `flexsight stereo` runs
// it, on a token list cut from the input at each newline: --method, the StereoParams
// options (with their check), the options every command takes, flags, whole numbers,
// and the unknown-option check. The record of the parameters (stereo_param_values)
// must read back through the parser to the same fields.
#include "host/cli/arguments.h"
#include "tests/fuzz/fuzz_support.h"

namespace {
void no_help() {}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args = fuzz::split(data, size, '\n');
  fuzz::expect_input_error_only([&] {
    if (flexsight::usage_exit_code(args, no_help)) return;
    flexsight::take_opencv_method(args);
    flexsight::StereoParams params;
    flexsight::consume_stereo_params(args, params);
    params.check();
    // The values a report records read back as the same parameters.
    std::vector<std::string> record;
    for (const auto& [name, value] : flexsight::stereo_param_values(params)) {
      record.push_back("--" + name);
      record.push_back(value);
    }
    flexsight::StereoParams again;
    flexsight::consume_stereo_params(record, again);
    if (!record.empty() || flexsight::stereo_param_values(again) != flexsight::stereo_param_values(params)) {
      std::abort();
    }
    flexsight::take_option(args, "-o");
    flexsight::take_number_option(args, "--scale", 1.0);
    const std::string count = flexsight::take_option(args, "--count");
    if (!count.empty()) {
      const std::int64_t n = flexsight::parse_whole_number("--count", count, -1000, 1000000);
      if (n < -1000 || n > 1000000) std::abort();
    }
    flexsight::take_flag(args, "--quiet");
    flexsight::reject_unknown_options(args);
  });
  return 0;
}

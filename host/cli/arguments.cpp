#include "host/cli/arguments.h"

#include <cmath>
#include <limits>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// The value of option `name` that `parse` (std::stol, std::stof) reads from the whole of
// `text`; InputError "expected <what>" where it reads nothing or stops short.
template <typename Parse>
auto parse_whole(const std::string& name, const std::string& text, const char* what,
                 const Parse& parse) {
  try {
    size_t used = 0;
    const auto value = parse(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  throw InputError(option_subject(name), std::string("expected ") + what + ", got '" + text + "'");
}

}  // namespace

std::string option_subject(const std::string& name) { return "option --" + name; }

float parse_float(const std::string& name, const std::string& text, Infinity infinity) {
  const float value = parse_whole(name, text, "a number",
                                  [](const std::string& t, size_t* used) { return std::stof(t, used); });
  if (std::isnan(value) || (std::isinf(value) && infinity == Infinity::kRejected)) {
    throw InputError(option_subject(name), std::string("expected a finite number") +
                                               (infinity == Infinity::kMeaningful ? " or inf" : "") + ", got '" +
                                               text + "'");
  }
  return value;
}

std::optional<OpenCvMatcher> take_opencv_method(std::vector<std::string>& args) {
  for (size_t i = 0; i + 1 < args.size(); ++i) {
    OpenCvMatcher matcher;
    if (args[i] != "--method" || !parse_opencv_matcher(args[i + 1], matcher)) continue;
    args.erase(args.begin() + i, args.begin() + i + 2);
    return matcher;
  }
  return std::nullopt;
}

double take_number_option(std::vector<std::string>& args, const std::string& name,
                          double fallback) {
  const std::string text = take_option(args, name);
  if (text.empty()) return fallback;
  // Options arrive here with their dashes; messages use the bare name like the others.
  return parse_float(name.substr(name.find_first_not_of('-')), text);
}

std::int64_t parse_whole_number(const std::string& option, const std::string& text,
                                std::int64_t lo, std::int64_t hi) {
  std::size_t used = 0;
  long long value = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;  // not a number, or beyond long long
  }
  if (used == 0 || used != text.size() || value < lo || value > hi) {
    throw InputError("option " + option, "expected a whole number in " + std::to_string(lo) +
                                             ".." + std::to_string(hi) + ", got '" + text + "'");
  }
  return value;
}

std::string take_option(std::vector<std::string>& args, const std::string& name) {
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] != name) continue;
    if (i + 1 >= args.size()) throw InputError("option " + name, "needs a value");
    std::string value = args[i + 1];
    args.erase(args.begin() + i, args.begin() + i + 2);
    return value;
  }
  return "";
}

void take_options(std::vector<std::string>& args,
                  const std::vector<std::pair<std::string, std::string*>>& options) {
  for (const auto& [name, destination] : options) *destination = take_option(args, name);
}

bool take_flag(std::vector<std::string>& args, const std::string& name) {
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == name) {
      args.erase(args.begin() + i);
      return true;
    }
  }
  return false;
}

std::optional<int> usage_exit_code(std::vector<std::string>& args, void (*print_help)()) {
  const bool help = take_flag(args, "--help") || take_flag(args, "-h");
  if (!help && !args.empty()) return std::nullopt;
  print_help();
  return help ? 0 : 1;
}

void reject_unknown_options(const std::vector<std::string>& args) {
  for (const std::string& arg : args) {
    if (arg.size() > 1 && arg[0] == '-') throw InputError("option " + arg, "unknown option");
  }
}

}  // namespace flexsight

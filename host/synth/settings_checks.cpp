#include "host/synth/settings_checks.h"

#include <cmath>
#include <sstream>

#include "host/io/input_error.h"

namespace flexsight::synth_detail {


std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void fail_option(const std::string& option, const std::string& problem) {
  throw InputError("option --" + option, problem);
}

// lo <= value <= hi, finite.
void in_range(const std::string& option, double value, double lo, double hi) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    fail_option(option, "must be in [" + number_text(lo) + ", " + number_text(hi) + "] (got " + number_text(value) + ")");
  }
}

void int_in_range(const std::string& option, int value, int lo, int hi) {
  if (value < lo || value > hi) {
    fail_option(option, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + " (got " +
                     std::to_string(value) + ")");
  }
}

void ordered(const std::string& min_option, double lo, const std::string& max_option, double hi) {
  if (lo > hi) {
    fail_option(min_option, number_text(lo) + " is larger than --" + max_option + " " + number_text(hi));
  }
}

void probability(const std::string& option, double value) { in_range(option, value, 0.0, 1.0); }

void image_size(int width, int height) {
  int_in_range("width", width, 8, 16384);
  int_in_range("height", height, 8, 16384);
}

void part_count(int min_parts, int max_parts) {
  int_in_range("min-parts", min_parts, 1, 100);
  int_in_range("max-parts", max_parts, 1, 100);
  ordered("min-parts", min_parts, "max-parts", max_parts);
}

}  // namespace flexsight::synth_detail

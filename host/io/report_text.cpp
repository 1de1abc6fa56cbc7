#include "host/io/report_text.h"

#include <cmath>
#include <cstdio>

namespace flexsight {

std::string fixed_decimals(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::string fixed_decimals(double value, int decimals, const std::string& undefined,
                           const std::string& unit) {
  return std::isfinite(value) ? fixed_decimals(value, decimals) + unit : undefined;
}

std::string fraction_text(double value) {
  constexpr int kFractionDecimals = 4;
  return fixed_decimals(value, kFractionDecimals, "-");
}

std::string threshold_label(double threshold) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", threshold);
  return buffer;
}

std::string markdown_cell(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '|') escaped += '\\';
    escaped += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return escaped;
}

}  // namespace flexsight

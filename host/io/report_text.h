#pragma once
// Numbers and names as the reports write them (Markdown tables, summaries). Fixed precision
// everywhere, so reports diff cleanly between runs.
#include <string>

namespace flexsight {

// `value` with `decimals` digits after the point ("%.*f"); NaN and infinity as printf writes them.
std::string fixed_decimals(double value, int decimals);

// The same, and `unit` after it, or only `undefined` where the value is NaN or infinite
// (reports write "-" or "n/a" there).
std::string fixed_decimals(double value, int decimals, const std::string& undefined,
                           const std::string& unit = "");

// A fraction or score with four decimals, "-" where it is undefined (NaN, infinity).
std::string fraction_text(double value);

// A threshold as a label, as short as it can be: 0.5 -> "0.5", 2 -> "2" ("%g").
std::string threshold_label(double threshold);

// `text` safe inside a Markdown table cell: '|' escaped, line breaks as spaces.
std::string markdown_cell(const std::string& text);

}  // namespace flexsight

#pragma once
// The range checks of the generators' settings, one message style for all: an
// InputError naming the command-line option ("option --min-parts: must be in 1..100").
#include <string>

namespace flexsight::synth_detail {

[[noreturn]] void fail_option(const std::string& option, const std::string& problem);
// lo <= value <= hi, finite.
void in_range(const std::string& option, double value, double lo, double hi);
void int_in_range(const std::string& option, int value, int lo, int hi);
// lo <= hi, named by the smaller's option.
void ordered(const std::string& min_option, double lo, const std::string& max_option, double hi);
void probability(const std::string& option, double value);
// --size: 8..16384 pixels each way.
void image_size(int width, int height);
// --min-parts and --max-parts: 1..100, in order.
void part_count(int min_parts, int max_parts);
// The shortest text of a value, for messages.
std::string number_text(double value);

}  // namespace flexsight::synth_detail

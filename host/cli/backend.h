#pragma once
// The backend options of the command line (--device, --cl-*): parsed into the
// BackendOptions that host/runtime/compute_backend.h and host/stereo/stereo_backend.h take.
#include <optional>
#include <string>
#include <vector>

#include "host/runtime/compute_backend.h"
#include "host/runtime/device_options.h"

namespace flexsight {

// Removes --device, --cl-platform, --cl-device, --cl-max-memory and --cl-build-options
// with their values from `args`. Throws InputError naming the option for an unknown
// --device value, a --cl-max-memory that is not a positive size, build options that
// would change the results, or a --cl-* option together with --device reference.
BackendOptions take_backend_options(std::vector<std::string>& args);

// "512M" -> 512 MiB: a positive whole number of bytes, or of KiB / MiB / GiB with the
// suffix K, M or G (KiB, MiB, GiB and KB, MB, GB read the same). nullopt otherwise.
std::optional<size_t> parse_byte_size(const std::string& text);

// The --help lines of those options.
std::string backend_options_help();

}  // namespace flexsight

#pragma once
// A POST /pick body read into the pick it asks for: the files of the pair and pick's
// options as command-line tokens, so that pick's own parser reads them (every option of
// `flexsight pick` works per request, with the same one-line message for a bad value).
//
//   {"left": "im0.png", "right": "im1.png", "calib": "calib.txt", "passive_left": "p.png",
//    "score": 0.1, "classes_per_box": 3, "tile": "auto", "half_turns": "off"}
//
// A key names the option without its dashes, '_' for '-': "classes_per_box" is
// --classes-per-box. A string or number is its value, true a flag (--quiet), false leaves
// it out, an array of numbers a comma list (--parts 5,12).
#include <stdexcept>
#include <string>
#include <vector>

#include "host/pick/pick_inputs.h"

namespace flexsight {

// A request the service refuses: the HTTP status and a one-line message naming the
// field, file or option.
class RequestError : public std::runtime_error {
 public:
  RequestError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

struct PickRequest {
  PickInputFiles files;
  // Base64 image bytes given in the body instead of paths ("left_png", "right_png",
  // "passive_left_png"); empty where a path was given.
  std::string left_bytes, right_bytes, passive_left_bytes;
  // pick's options, e.g. {"--score", "0.1", "--quiet"}.
  std::vector<std::string> option_tokens;
};

// The keys a request may not give: what `flexsight serve` loads once at its start, and
// pick's outputs (the answer is the PICKS.json).
const std::vector<std::string>& keys_fixed_at_start();

// `body` read as above; RequestError 400 naming the key for a body that is not a JSON
// object, a missing or doubly given image or calibration, a value of the wrong type, a
// key fixed at the start or not an option's name.
PickRequest parse_pick_request(const std::string& body);

// `base` (the options `flexsight serve` was started with) with each option the request
// gives replaced by the request's: the arguments pick's parser reads for this request.
std::vector<std::string> merge_pick_arguments(const std::vector<std::string>& base,
                                              const std::vector<std::string>& request);

// Standard base64 (RFC 4648, '=' padding, whitespace ignored); RequestError 400 naming
// `field` for anything else.
std::string decode_base64(const std::string& text, const std::string& field);

}  // namespace flexsight

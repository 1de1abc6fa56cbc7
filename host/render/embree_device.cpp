#include "host/render/embree_device.h"

#include <stdexcept>
#include <string>

namespace flexsight::render_detail {
namespace {

const char* error_sentence(RTCError error) {
  switch (error) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "an argument is invalid";
    case RTC_ERROR_INVALID_OPERATION:
      return "the operation is not allowed now";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "this CPU lacks the instructions Embree needs";
    case RTC_ERROR_CANCELLED:
      return "the operation was cancelled";
    default:
      return "unknown error";
  }
}

}  // namespace

RTCDevice embree_device() {
  // A function-local static: created once, thread-safely, on first use.
  static const RTCDevice device = [] {
    RTCDevice created = rtcNewDevice(nullptr);
    if (created == nullptr) {
      throw std::runtime_error(std::string("Embree: cannot create a device: ") +
                               error_sentence(rtcGetDeviceError(nullptr)));
    }
    return created;
  }();
  return device;
}

void check_embree(const char* step) {
  const RTCError error = rtcGetDeviceError(embree_device());
  if (error != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree: ") + step + " failed: " + error_sentence(error));
  }
}

}  // namespace flexsight::render_detail

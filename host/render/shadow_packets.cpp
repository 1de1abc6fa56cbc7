#include "host/render/shadow_packets.h"

#include <limits>

namespace flexsight::render_detail {

ShadowPackets::ShadowPackets(RTCScene scene) : scene_(scene) {
  // Lanes left empty in a last, partial packet are switched off by valid_; their rays
  // still hold finite numbers, so that no lane computes on garbage.
  for (int k = 0; k < kLanes; ++k) {
    packet_.org_x[k] = packet_.org_y[k] = packet_.org_z[k] = 0.0f;
    packet_.dir_x[k] = packet_.dir_y[k] = 0.0f;
    packet_.dir_z[k] = 1.0f;
    packet_.tnear[k] = 0.0f;
    packet_.tfar[k] = 0.0f;
    packet_.time[k] = 0.0f;
    packet_.mask[k] = 0xFFFFFFFFu;
    packet_.id[k] = 0;
    packet_.flags[k] = 0;
    valid_[k] = 0;
    slot_of_lane_[k] = 0;
  }
}

void ShadowPackets::reset(int slots) {
  lanes_ = 0;
  unblocked_.assign(static_cast<size_t>(slots), 0);
}

void ShadowPackets::flush() {
  if (lanes_ == 0) return;
  for (int k = lanes_; k < kLanes; ++k) valid_[k] = 0;
  // Not RTC_INTERSECT_CONTEXT_FLAG_COHERENT: Embree's coherent path (one frustum per
  // packet, made for camera rays from one centre) ran these packets many times slower.
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded16(valid_, scene_, &context, &packet_);
  for (int k = 0; k < lanes_; ++k) {
    // Embree sets tfar to -inf where something blocks the ray.
    if (!(packet_.tfar[k] < 0.0f)) ++unblocked_[slot_of_lane_[k]];
  }
  lanes_ = 0;
}

}  // namespace flexsight::render_detail

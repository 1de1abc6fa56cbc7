#pragma once
// Shadow rays cast sixteen at a time. Shading queues the segments from its surface points
// to the lights (one per hard shadow, several per soft one) and reads back, per slot (a
// pixel and a light), how many of its segments nothing blocks. rtcOccluded16 traces a
// packet of neighbouring pixels' rays to the same light together: on the bin scene of
// bench/render it is about twice as fast as one rtcOccluded1 per ray (docs/render.md).
//
// Each ray is the segment rtcOccluded1 would trace, with the same origin, direction,
// tnear and tfar. Whether something blocks a segment does not depend on the order in
// which Embree meets the triangles (which a packet's other rays may change), so the
// shading is the same bytes as with one call per ray (tested to the bit).
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <vector>

namespace flexsight::render_detail {

class ShadowPackets {
 public:
  explicit ShadowPackets(RTCScene scene);

  // Forgets the queue and the counts, and makes `slots` slots at zero.
  void reset(int slots);
  // Queues the segment from `origin` to `target` (parameters 0 to just below 1, so that
  // the light's own point never blocks it) for slot `slot`; casts the packet when full.
  // Inline: it runs once per shadow ray.
  void add(const Eigen::Vector3f& origin, const Eigen::Vector3f& target, int slot) {
    const int k = lanes_++;
    packet_.org_x[k] = origin.x();
    packet_.org_y[k] = origin.y();
    packet_.org_z[k] = origin.z();
    const Eigen::Vector3f direction = target - origin;
    packet_.dir_x[k] = direction.x();
    packet_.dir_y[k] = direction.y();
    packet_.dir_z[k] = direction.z();
    // The direction spans the whole way to the light: parameters up to just below 1.
    packet_.tnear[k] = 0.0f;
    packet_.tfar[k] = 1.0f - 1e-4f;
    valid_[k] = -1;
    slot_of_lane_[k] = slot;
    if (lanes_ == kLanes) flush();
  }
  // Casts what is queued. Call before reading the counts.
  void flush();
  // Segments of slot `slot` that nothing blocks.
  int unblocked(int slot) const { return unblocked_[slot]; }

 private:
  static constexpr int kLanes = 16;
  alignas(64) RTCRay16 packet_;
  alignas(64) int valid_[kLanes];
  int slot_of_lane_[kLanes];
  int lanes_ = 0;
  RTCScene scene_;
  std::vector<int> unblocked_;
};

}  // namespace flexsight::render_detail

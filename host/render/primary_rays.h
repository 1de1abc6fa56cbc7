#pragma once
// A camera's primary ray in Embree's ray structures: from the camera centre along
// (dx, dy, 1), so the hit parameter t is the depth z; every other field at the value
// that means "nothing hit yet, no mask, no motion". Shared by the ray caster and the
// benchmarks' raw Embree loops, so both cast exactly the same rays.
#include <embree3/rtcore.h>

#include <limits>

namespace flexsight {

inline void set_primary_ray(RTCRayHit16& packet, int lane, float dx, float dy) {
  packet.ray.org_x[lane] = packet.ray.org_y[lane] = packet.ray.org_z[lane] = 0.0f;
  packet.ray.dir_x[lane] = dx;
  packet.ray.dir_y[lane] = dy;
  packet.ray.dir_z[lane] = 1.0f;
  packet.ray.tnear[lane] = 0.0f;
  packet.ray.tfar[lane] = std::numeric_limits<float>::infinity();
  packet.ray.time[lane] = 0.0f;
  packet.ray.mask[lane] = 0xFFFFFFFFu;
  packet.ray.id[lane] = 0;
  packet.ray.flags[lane] = 0;
  packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
  packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
}

inline void set_primary_ray(RTCRayHit& ray_hit, float dx, float dy) {
  ray_hit.ray.org_x = ray_hit.ray.org_y = ray_hit.ray.org_z = 0.0f;
  ray_hit.ray.dir_x = dx;
  ray_hit.ray.dir_y = dy;
  ray_hit.ray.dir_z = 1.0f;
  ray_hit.ray.tnear = 0.0f;
  ray_hit.ray.tfar = std::numeric_limits<float>::infinity();
  ray_hit.ray.time = 0.0f;
  ray_hit.ray.mask = 0xFFFFFFFFu;
  ray_hit.ray.id = 0;
  ray_hit.ray.flags = 0;
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace flexsight

#pragma once
// The random numbers of one synthetic image: a function of (seed, image index, stream),
// never the state of a generator shared between images, so an image is the same bytes
// whichever thread makes it and in whatever order. Each purpose (a part's pose, the
// lights, the background, ...) draws from its own stream, so that a change in how many
// numbers one purpose takes (one more pose attempt) leaves the others as they were.
#include <cmath>
#include <cstdint>

#include "kernels/common/counter_rng.h"

namespace flexsight::synth_detail {

// One stream per purpose; a part's pose stream adds the part's slot to kStreamPart.
enum SynthStream : std::uint32_t {
  kStreamScene = 1,       // how many parts
  kStreamAppearance = 2,  // lights, ambient, camera light, shading seed
  kStreamBackground = 3,  // which image, crop, flip
  kStreamAugment = 4,     // in-plane rotation, flips, blur, noise level
  kStreamNoise = 5,       // the noise pixels
  kStreamPart = 0x100,    // + slot: object, size, position, rotation, material
};

class SynthRandom {
 public:
  // The key mixes every bit of seed, index and stream through fs_hash (the kernels'
  // counter-based hash); the numbers are splitmix64 outputs of key + n * golden ratio,
  // i.e. again a hash of a counter.
  SynthRandom(std::uint32_t seed, std::int64_t image_index, std::uint32_t stream) {
    const auto index = static_cast<std::uint64_t>(image_index);
    fs_u32 h = fs_hash(seed ^ 0x5E1EC7EDU);
    h = fs_hash(h ^ static_cast<fs_u32>(index));
    fs_u32 g = fs_hash(h ^ static_cast<fs_u32>(index >> 32));
    g = fs_hash(g ^ stream);
    state_ = (std::uint64_t(h) << 32) | g;
  }

  std::uint64_t next_u64() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1), 53 bits.
  double uniform() { return double(next_u64() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform in [lo, hi] (inclusive, lo <= hi).
  int integer(int lo, int hi) {
    const std::uint64_t span = std::uint64_t(std::int64_t(hi) - lo + 1);
    return lo + static_cast<int>(next_u64() % span);
  }
  // Equal chances for every factor of two between lo and hi (0 < lo <= hi).
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  bool chance(double probability) { return uniform() < probability; }

 private:
  std::uint64_t state_;
};

}  // namespace flexsight::synth_detail

/*
 * The counter-based random generator's building blocks, for any module whose kernels
 * need random numbers that do not depend on thread order: a value is a hash of its key
 * (seed, pixel, iteration, ...), never the next state of a shared generator. A module
 * composes its own key from these (the stereo module: pms_random_u32 in
 * kernels/stereo/pms_math.h).
 */
#ifndef FLEXSIGHT_COMMON_COUNTER_RNG_H
#define FLEXSIGHT_COMMON_COUNTER_RNG_H

#include "portability.h"

/* A 32-bit integer hash with good avalanche ("lowbias32", C. Wellons). */
FS_INLINE fs_u32 fs_hash(fs_u32 x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

/* Uniform float in [0, 1): the top 24 bits scaled exactly by 2^-24. */
FS_INLINE float fs_u32_to_unit(fs_u32 bits) {
  return (float)(bits >> 8) * (1.0f / 16777216.0f);
}

#endif /* FLEXSIGHT_COMMON_COUNTER_RNG_H */

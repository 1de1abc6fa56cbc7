/*
 * What lets one header be compiled both as OpenCL C (by the device's compiler, inside a
 * kernel) and as C++ (by the reference path): address-space and inline keywords, a
 * 32-bit unsigned type, and the few library functions whose results are exact or
 * correctly rounded on every device (floor, fabs, fmin/fmax, sqrt, popcount). Every
 * module's shared maths header includes it first; nothing else belongs here.
 *
 * FP_CONTRACT OFF (and -ffp-contract=off on the C++ side, set in CMakeLists.txt) keeps
 * a*b+c a rounded product then a rounded sum on both sides, so that the two paths can
 * give the same bytes.
 */
#ifndef FLEXSIGHT_COMMON_PORTABILITY_H
#define FLEXSIGHT_COMMON_PORTABILITY_H

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#define FS_GLOBAL __global
#define FS_INLINE inline
typedef uint fs_u32;
#define FS_FLOOR(x) floor(x)
#define FS_FABS(x) fabs(x)
#define FS_FMIN(x, y) fmin(x, y)
#define FS_FMAX(x, y) fmax(x, y)
#define FS_SQRT(x) sqrt(x)
#define FS_POPCOUNT(x) popcount(x)
#else
#include <cmath>
#include <cstdint>
#define FS_GLOBAL
#define FS_INLINE inline
typedef std::uint32_t fs_u32;
#define FS_FLOOR(x) std::floor(x)
#define FS_FABS(x) std::fabs(x)
#define FS_FMIN(x, y) std::fmin(x, y)
#define FS_FMAX(x, y) std::fmax(x, y)
#define FS_SQRT(x) std::sqrt(x)
#define FS_POPCOUNT(x) __builtin_popcount(x)
#endif

#endif /* FLEXSIGHT_COMMON_PORTABILITY_H */

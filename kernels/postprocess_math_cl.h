/*
 * postprocess_math.h for the kernels. That header names a local variable `half`
 * (pms_weighted_median), which is a reserved type name in OpenCL C, so it does not
 * compile there as it is; this wrapper renames the variable with a macro for the
 * length of the include (no kernel uses the half type). Renaming the variable in
 * postprocess_math.h makes this file a plain include.
 */
#ifndef FLEXSIGHT_POSTPROCESS_MATH_CL_H
#define FLEXSIGHT_POSTPROCESS_MATH_CL_H

#define half pms_half_total
#include "postprocess_math.h"
#undef half

#endif /* FLEXSIGHT_POSTPROCESS_MATH_CL_H */

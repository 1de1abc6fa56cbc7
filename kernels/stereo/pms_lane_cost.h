/*
 * The lane cost of the OpenCL kernels (never compiled as C++): pms_plane_cost for
 * PMS_LANES pixels of a row at once in OpenCL vector types (pms_lanes.h), the other
 * view's match records and the candidate batches. Built from the same
 * per-sample macros of pms_math.h (PMS_MATCH_X, PMS_DISSIMILARITY, ...) as the scalar
 * cost, so the two derive from one definition.
 */
#ifndef FLEXSIGHT_PMS_LANE_COST_H
#define FLEXSIGHT_PMS_LANE_COST_H

#include "pms_lanes.h"

/* ------------------------------------------------- the other view's match records
 *
 * The cost interpolates the other view at a data-dependent x0 per lane, which would
 * take 11 gathers per window sample (three colours and two gradients at x0 and
 * x0 + 1, and a census). pack_match_samples (build_view.cl) stores per pixel one record
 * of PMS_MATCH_RECORD floats with everything a sample needs there, so each lane loads
 * its record with one vector load and a transpose turns the lanes' records into one
 * vector per field. The steps m1 - m0 are computed once there with the same float
 * subtraction pms_plane_cost performs, so the sums keep their bits. */
/* The fields of a match record in their order (pms_match_record writes them). */
#define PMS_MATCH_FIELDS(X)                                                              \
  X(r, 0) X(g, 1) X(b, 2) X(census0, 3) X(dr, 4) X(dg, 5) X(db, 6) X(census1, 7)          \
  X(gx, 8) X(gy, 9) X(dgx, 10) X(dgy, 11)
#define PMS_DECLARE_MATCH_FIELD(name, k) pms_floatv name;
typedef struct {
  PMS_MATCH_FIELDS(PMS_DECLARE_MATCH_FIELD)
} PmsMatchSamples;
#undef PMS_DECLARE_MATCH_FIELD

#if PMS_LANES == 8
/* Lane l gets the fields of record x0[l]. Three rounds of two-source shuffles (24 in
 * all, which LLVM lowers to permutes) transpose the 8 lanes x 16 floats. Always
 * inlined: as a call, its results go through the stack and the first read stalls. */
__attribute__((always_inline)) inline void pms_load_match_samples(
    const __global float* match_row, int8 x0, PmsMatchSamples* m) {
  const float16 v0 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s0);
  const float16 v1 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s1);
  const float16 v2 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s2);
  const float16 v3 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s3);
  const float16 v4 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s4);
  const float16 v5 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s5);
  const float16 v6 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s6);
  const float16 v7 = vload16(0, match_row + PMS_MATCH_RECORD * x0.s7);
  /* Round 1: p<i><s>[2 m + j] = lane (2 i + j), field (2 m + s). */
#define PMS_EVEN2(a, b) (float16)(a.s0, b.s0, a.s2, b.s2, a.s4, b.s4, a.s6, b.s6, \
                                  a.s8, b.s8, a.sa, b.sa, a.sc, b.sc, a.se, b.se)
#define PMS_ODD2(a, b) (float16)(a.s1, b.s1, a.s3, b.s3, a.s5, b.s5, a.s7, b.s7, \
                                 a.s9, b.s9, a.sb, b.sb, a.sd, b.sd, a.sf, b.sf)
  const float16 p00 = PMS_EVEN2(v0, v1), p01 = PMS_ODD2(v0, v1);
  const float16 p10 = PMS_EVEN2(v2, v3), p11 = PMS_ODD2(v2, v3);
  const float16 p20 = PMS_EVEN2(v4, v5), p21 = PMS_ODD2(v4, v5);
  const float16 p30 = PMS_EVEN2(v6, v7), p31 = PMS_ODD2(v6, v7);
  /* Round 2: q<h><s><u>[4 m + j] = lane (4 h + j), field (4 m + 2 u + s). */
#define PMS_PAIRS_U0(a, b) (float16)(a.s01, b.s01, a.s45, b.s45, a.s89, b.s89, a.scd, b.scd)
#define PMS_PAIRS_U1(a, b) (float16)(a.s23, b.s23, a.s67, b.s67, a.sab, b.sab, a.sef, b.sef)
  const float16 q000 = PMS_PAIRS_U0(p00, p10), q001 = PMS_PAIRS_U1(p00, p10);
  const float16 q010 = PMS_PAIRS_U0(p01, p11), q011 = PMS_PAIRS_U1(p01, p11);
  const float16 q100 = PMS_PAIRS_U0(p20, p30), q101 = PMS_PAIRS_U1(p20, p30);
  const float16 q110 = PMS_PAIRS_U0(p21, p31), q111 = PMS_PAIRS_U1(p21, p31);
  /* Round 3: field k = 4 w + 2 u + s of every lane in .lo, field k + 8 in .hi. */
#define PMS_QUADS_W0(a, b) (float16)(a.s0123, b.s0123, a.s89ab, b.s89ab)
#define PMS_QUADS_W1(a, b) (float16)(a.s4567, b.s4567, a.scdef, b.scdef)
  const float16 f0 = PMS_QUADS_W0(q000, q100); /* s 0, u 0, w 0: fields 0 and 8 */
  const float16 f1 = PMS_QUADS_W0(q010, q110); /* fields 1 and 9 */
  const float16 f2 = PMS_QUADS_W0(q001, q101); /* fields 2 and 10 */
  const float16 f3 = PMS_QUADS_W0(q011, q111); /* fields 3 and 11 */
  const float16 f4 = PMS_QUADS_W1(q000, q100); /* fields 4 and 12 */
  const float16 f5 = PMS_QUADS_W1(q010, q110);
  const float16 f6 = PMS_QUADS_W1(q001, q101);
  const float16 f7 = PMS_QUADS_W1(q011, q111);
#undef PMS_EVEN2
#undef PMS_ODD2
#undef PMS_PAIRS_U0
#undef PMS_PAIRS_U1
#undef PMS_QUADS_W0
#undef PMS_QUADS_W1
  /* Field k < 8 is in .lo of f<k>, field k >= 8 in .hi of f<k - 8>. */
  const float16 f[8] = {f0, f1, f2, f3, f4, f5, f6, f7};
#define PMS_TAKE_MATCH_FIELD(name, k) m->name = (k) < 8 ? f[(k) & 7].lo : f[(k) & 7].hi;
  PMS_MATCH_FIELDS(PMS_TAKE_MATCH_FIELD)
#undef PMS_TAKE_MATCH_FIELD
}
#else
inline void pms_load_match_samples(const __global float* match_row, pms_intv x0,
                                   PmsMatchSamples* m) {
  float f[PMS_MATCH_RECORD][PMS_LANES];
  for (int l = 0; l < PMS_LANES; ++l) {
    for (int k = 0; k < PMS_MATCH_RECORD; ++k) {
      f[k][l] = match_row[PMS_MATCH_RECORD * PMS_LANE(x0, l) + k];
    }
  }
#define PMS_LOAD_MATCH_FIELD(name, k) m->name = PMS_VLOAD(0, f[k]);
  PMS_MATCH_FIELDS(PMS_LOAD_MATCH_FIELD)
#undef PMS_LOAD_MATCH_FIELD
}
#endif

/* popcount of every lane in vector operations: PoCL's CPU target (skylake-avx512 here)
 * has no vector popcount instruction and splits popcount() into one scalar popcnt per
 * lane. The classic bit-parallel count; integers, so exact. */
#if PMS_LANES == 1
typedef uint pms_uintv;
#elif PMS_LANES == 4
typedef uint4 pms_uintv;
#elif PMS_LANES == 8
typedef uint8 pms_uintv;
#else
typedef uint16 pms_uintv;
#endif
inline pms_uintv pms_popcount_v(pms_uintv v) {
  v = v - ((v >> 1) & 0x55555555U);
  v = (v & 0x33333333U) + ((v >> 2) & 0x33333333U);
  v = (v + (v >> 4)) & 0x0F0F0F0FU;
  return (v * 0x01010101U) >> 24;
}

/* One candidate plane per lane for a batched evaluation: the kernels fill it lane by
 * lane with the reference's per-pixel rules, then pms_batch_offer costs every trying
 * lane at once and offers the result to that lane's best plane. */
typedef struct {
  float a[PMS_LANES];
  float b[PMS_LANES];
  float c[PMS_LANES];
  float bound[PMS_LANES];
  int tries[PMS_LANES];
  int any;
} PmsCandidateBatch;

/* The start of a dense cost stage's work item (evaluate_costs, init_random_planes): its
 * lanes and an empty candidate batch. Returns 0 when the item has no pixel. */
inline int pms_dense_batch_begin(int width, int height, PmsLanes* lanes, int* y,
                                 PmsCandidateBatch* batch) {
  batch->any = 0;
  return pms_dense_lanes(width, height, lanes, y);
}

/* The most candidate batches one window pass evaluates (pms_cost_lanes_group). The host
 * builds propagate_spatial with its group size (-DPMS_SPATIAL_GROUP, OpenClStages); the
 * other cost kernels pass one batch at a time. */
#ifndef PMS_SPATIAL_GROUP
#define PMS_SPATIAL_GROUP 8
#endif
#if PMS_SPATIAL_GROUP < 1 || PMS_SPATIAL_GROUP > 8
#error "PMS_SPATIAL_GROUP must be 1 to 8"
#endif

/* pms_plane_cost of plane (a[l], b[l], c[l]) of each of `count` batches (at most
 * PMS_SPATIAL_GROUP; a constant at every call site, so the unused slots compile away)
 * at (x[l], py) for every lane, within the early-exit rule above; costs[k] of batch k.
 * Lanes with bound[l] <= 0 are ignored (pass 0 for unused).
 *
 * One window pass serves every batch: the view's own samples (colours, gradients,
 * census, support weights) do not depend on the plane, so they are loaded once per
 * window pixel and only the other view's samples are per batch. Each batch's sums run
 * in pms_plane_cost's order, so its costs keep their bits; a batch stops after every
 * one of its lanes has reached its bound, the pass when every batch has. Batches
 * evaluated together are bounded by the best costs from before any of them, not by what
 * the earlier ones improved: the caller offers them in order afterwards, and a cost that
 * a tighter bound would have cut off is >= that bound either way (pms_group_offer).
 * Kept whole although long: a kernel-like inner loop over the window. */
__attribute__((always_inline)) inline void pms_cost_lanes_group(
    const PmsCostInputs* in, const PmsLanes* lanes, int py, const PmsCandidateBatch* batches,
    const int count, pms_floatv* costs) {
  const int width = in->width;
  const int height = in->height;
  const int radius = in->params.radius;
  const int radius_rows = in->params.radius_rows;
  const int step = in->params.step;
  const float direction = in->direction;
  const PmsCostParams params = in->params;
  const __global float* restrict weights = in->weights;
  pms_floatv a[PMS_SPATIAL_GROUP], b[PMS_SPATIAL_GROUP], c[PMS_SPATIAL_GROUP];
  pms_floatv bound[PMS_SPATIAL_GROUP], sum[PMS_SPATIAL_GROUP], row_term[PMS_SPATIAL_GROUP];
#pragma unroll
  for (int k = 0; k < PMS_SPATIAL_GROUP; ++k) {
    if (k >= count) break;
    a[k] = PMS_VLOAD(0, batches[k].a);
    b[k] = PMS_VLOAD(0, batches[k].b);
    c[k] = PMS_VLOAD(0, batches[k].c);
    bound[k] = PMS_VLOAD(0, batches[k].bound);
    sum[k] = (pms_floatv)(0.0f);
  }
  int live = (1 << count) - 1; /* bit k: some lane of batch k is still below its bound */
  const int* x = lanes->x;
  const pms_intv px = PMS_VLOAD(0, x);
  /* Checkerboard lanes read their window samples with vector loads (fast path below)
   * where every lane's sample lies inside the row. */
#if PMS_LANES == 8
  const int strided = lanes->stride == 2;
#else
  const int strided = 0;
#endif

  float centre_r[PMS_LANES], centre_g[PMS_LANES], centre_b[PMS_LANES];
  for (int l = 0; l < PMS_LANES; ++l) {
    const __global float* centre = in->ref_color + 4 * (py * width + x[l]);
    centre_r[l] = centre[0];
    centre_g[l] = centre[1];
    centre_b[l] = centre[2];
  }
  const pms_floatv cr = PMS_VLOAD(0, centre_r);
  const pms_floatv cg = PMS_VLOAD(0, centre_g);
  const pms_floatv cb = PMS_VLOAD(0, centre_b);

  const int y_begin = pms_first_offset(radius_rows, step, -py);
  const int y_end = radius_rows < height - 1 - py ? radius_rows : height - 1 - py;
  /* The whole window's column grid; each lane keeps the columns inside the image,
   * which are exactly pms_first_offset(.., -x) .. min(radius, width - 1 - x). */
  const int x_begin = pms_first_offset(radius, step, -radius);
  const float max_x = (float)(width - 1);
  const int row_count = pms_window_row_count(radius_rows, step);
  for (int row_index = 0; row_index < row_count; ++row_index) {
    const int dy = pms_window_row(row_index, step);
    if (dy < y_begin || dy > y_end) continue;
    const int qy = py + dy;
#pragma unroll
    for (int k = 0; k < PMS_SPATIAL_GROUP; ++k) {
      if (k < count) row_term[k] = b[k] * (float)qy;
    }
    const __global float* ref_row = in->ref_color + 4 * qy * width;
    const __global float* ref_grad_row = in->ref_grad + 2 * qy * width;
    const __global float* match_row = in->other_match + PMS_MATCH_RECORD * qy * width;
    const __global float* distance_weights = pms_distance_weight_row(weights, dy);
    for (int dx = x_begin; dx <= radius; dx += step) {
      const pms_intv qx = px + dx;
      const pms_intv inside = (qx >= 0) & (qx < width);
      if (!PMS_ANY(inside)) continue;
      const int first_qx = lanes->first + dx;
      const int fast = strided && first_qx >= 0 && first_qx + 2 * (PMS_LANES - 1) <= width - 1;
      const pms_floatv fqx = PMS_TO_FLOATV(qx);
      pms_floatv Q0, Q1, Q2, Q3, G0, G1, W;
#if PMS_LANES == 8
      if (fast) {
        /* Lane l's sample is pixel first_qx + 2 l: every other pixel of 15. The loads
         * stop at the last lane's pixel (never past the row). */
        const __global float* qc = ref_row + 4 * first_qx;
        const float16 c0 = vload16(0, qc), c1 = vload16(1, qc), c2 = vload16(2, qc);
        const float8 c3 = vload8(6, qc);
        const float4 c4 = vload4(14, qc);
        Q0 = (float8)(c0.s0, c0.s8, c1.s0, c1.s8, c2.s0, c2.s8, c3.s0, c4.s0);
        Q1 = (float8)(c0.s1, c0.s9, c1.s1, c1.s9, c2.s1, c2.s9, c3.s1, c4.s1);
        Q2 = (float8)(c0.s2, c0.sa, c1.s2, c1.sa, c2.s2, c2.sa, c3.s2, c4.s2);
        Q3 = (float8)(c0.s3, c0.sb, c1.s3, c1.sb, c2.s3, c2.sb, c3.s3, c4.s3);
        const __global float* qg = ref_grad_row + 2 * first_qx;
        const float16 h0 = vload16(0, qg);
        const float8 h1 = vload8(2, qg);
        const float4 h2 = vload4(6, qg);
        const float2 h3 = vload2(14, qg);
        G0 = (float8)(h0.s0, h0.s4, h0.s8, h0.sc, h1.s0, h1.s4, h2.s0, h3.s0);
        G1 = (float8)(h0.s1, h0.s5, h0.s9, h0.sd, h1.s1, h1.s5, h2.s1, h3.s1);
        /* pms_color_l1(centre, q), lane by lane */
        const int8 wi = convert_int8(fabs(cr - Q0) + fabs(cg - Q1) + fabs(cb - Q2));
        W = PMS_GATHER8(weights, wi);
      } else
#endif
      {
        float q0[PMS_LANES], q1[PMS_LANES], q2[PMS_LANES], q3[PMS_LANES];
        float gq0[PMS_LANES], gq1[PMS_LANES], w[PMS_LANES];
#pragma unroll
        for (int l = 0; l < PMS_LANES; ++l) {
          int sx = x[l] + dx;
          sx = sx < 0 ? 0 : (sx > width - 1 ? width - 1 : sx); /* outside lanes: any pixel */
          const __global float* q = ref_row + 4 * sx;
          const __global float* g = ref_grad_row + 2 * sx;
          q0[l] = q[0];
          q1[l] = q[1];
          q2[l] = q[2];
          q3[l] = q[3];
          gq0[l] = g[0];
          gq1[l] = g[1];
          /* pms_color_l1(centre, q) */
          w[l] = weights[(int)(fabs(centre_r[l] - q[0]) + fabs(centre_g[l] - q[1]) +
                               fabs(centre_b[l] - q[2]))];
        }
        Q0 = PMS_VLOAD(0, q0);
        Q1 = PMS_VLOAD(0, q1);
        Q2 = PMS_VLOAD(0, q2);
        Q3 = PMS_VLOAD(0, q3);
        G0 = PMS_VLOAD(0, gq0);
        G1 = PMS_VLOAD(0, gq1);
        W = PMS_VLOAD(0, w);
      }
      W = W * distance_weights[dx < 0 ? -dx : dx]; /* the same for every lane */
#pragma unroll
      for (int k = 0; k < PMS_SPATIAL_GROUP; ++k) {
        if (k >= count) break;
        if (!((live >> k) & 1)) continue; /* every lane of batch k reached its bound */
        const pms_floatv d = PMS_SAMPLE_DISPARITY(a[k], fqx, row_term[k], c[k]);
        const pms_floatv match_x = PMS_MATCH_X(fqx, direction, d, max_x);
        const pms_floatv x0f = floor(match_x);
        const pms_intv x0 = PMS_TO_INTV(x0f);
        const pms_floatv t = match_x - x0f;
        /* The other view at x0 (x0 is clamped into the row, so every lane's record
         * exists): values there and the steps to x1 = min(x0 + 1, width - 1), which
         * pack_match_samples computed as pms_plane_cost computes m1 - m0. */
        PmsMatchSamples m;
        pms_load_match_samples(match_row, x0, &m);
        const pms_floatv color_diff =
            PMS_COLOR_DIFF(Q0, Q1, Q2, PMS_LERP(m.r, t, m.dr), PMS_LERP(m.g, t, m.dg),
                           PMS_LERP(m.b, t, m.db));
        const pms_floatv grad_diff =
            PMS_GRADIENT_DIFF(G0, G1, PMS_LERP(m.gx, t, m.dgx), PMS_LERP(m.gy, t, m.dgy));
        const pms_floatv nearest_census = select(m.census1, m.census0, isless(t, 0.5f));
        const pms_floatv census_bits =
            PMS_TO_FLOATV(pms_popcount_v(PMS_TO_UINTV(Q3) ^ PMS_TO_UINTV(nearest_census)));
        const pms_floatv dissimilarity =
            PMS_DISSIMILARITY(params, color_diff, grad_diff, census_bits);
        sum[k] = select(sum[k], sum[k] + W * dissimilarity, inside);
      }
    }
#pragma unroll
    for (int k = 0; k < PMS_SPATIAL_GROUP; ++k) {
      if (k < count && PMS_ALL(sum[k] >= bound[k])) live &= ~(1 << k);
    }
    if (live == 0) break;
  }
#pragma unroll
  for (int k = 0; k < PMS_SPATIAL_GROUP; ++k) {
    if (k < count) costs[k] = sum[k];
  }
}


/* Lane `lane` tries `abc` when `tries`, its cost summed until it reaches `bound`. */
inline void pms_batch_put(PmsCandidateBatch* batch, int lane, int tries, const float* abc,
                          float bound) {
  batch->tries[lane] = tries;
  batch->any |= tries;
  batch->a[lane] = abc[0];
  batch->b[lane] = abc[1];
  batch->c[lane] = abc[2];
  batch->bound[lane] = bound;
}

/* Lane `lane` tries `abc` when `tries`, bounded by its current best cost. */
inline void pms_batch_set(PmsCandidateBatch* batch, int lane, int tries, const float* abc,
                          const PmsBestPlane* best) {
  pms_batch_put(batch, lane, tries, abc, tries ? best->cost : 0.0f);
}

/* Offers batch k's trying lanes to their best planes, batches in order, as the
 * reference offers one pixel's candidates one after the other. */
inline void pms_offer_costs(const PmsCandidateBatch* batches, int count,
                            const pms_floatv* costs, PmsBestPlane* best) {
  for (int k = 0; k < count; ++k) {
    for (int l = 0; l < PMS_LANES; ++l) {
      if (!batches[k].tries[l]) continue;
      float candidate[3] = {batches[k].a[l], batches[k].b[l], batches[k].c[l]};
      pms_best_offer(&best[l], candidate, PMS_LANE(costs[k], l));
    }
  }
}

/* `count` batches (a constant at the call site, at most PMS_SPATIAL_GROUP) in one window
 * pass (pms_cost_lanes_group), all bounded by the best costs from before them
 * (pms_batch_set), then offered in order. The same
 * planes win as when each is costed after the previous one was offered: a batch whose
 * cost would win is below every bound it could have had, so its lanes sum the whole
 * window either way and get the same bits; one that would lose is >= the tighter bound
 * whether cut off at the looser one or not (costs are sums of terms >= 0), and
 * pms_best_offer rejects it either way. A plane equal to an earlier batch's winner is
 * costed again instead of skipped (pms_best_same_as), ties, and is rejected. */
__attribute__((always_inline)) inline void pms_group_offer(PmsCandidateBatch* batches,
                                                           const int count,
                                                           const PmsCostInputs* in,
                                                           const PmsLanes* lanes, int y,
                                                           PmsBestPlane* best) {
  int any = 0;
  for (int k = 0; k < count; ++k) any |= batches[k].any;
  if (!any) return;
  pms_floatv costs[PMS_SPATIAL_GROUP];
  pms_cost_lanes_group(in, lanes, y, batches, count, costs);
  pms_offer_costs(batches, count, costs, best);
}

/* One batch: the kernels whose candidates depend on the outcome of the previous one. */
inline void pms_batch_offer(PmsCandidateBatch* batch, const PmsCostInputs* in,
                            const PmsLanes* lanes, int y, PmsBestPlane* best) {
  pms_group_offer(batch, 1, in, lanes, y, best);
}

/* Writes back every active lane's plane (a no-op for lanes whose plane did not change). */
inline void pms_best_store_lanes(const PmsBestPlane* best, const PmsLanes* lanes, int y,
                                 int width, __global float* planes, __global float* cost) {
  for (int l = 0; l < PMS_LANES; ++l) {
    if (lanes->active[l]) pms_best_store(&best[l], planes, cost, y * width + lanes->x[l]);
  }
}


/* Lane `lane` gets the full, unbounded cost of `abc` (bound 0 for an inactive lane, whose
 * result is never stored). */
inline void pms_batch_set_unbounded(PmsCandidateBatch* batch, int lane, int active,
                                    const float* abc) {
  pms_batch_put(batch, lane, active, abc, active ? PMS_NO_BOUND : 0.0f);
}

/* Costs every lane's plane at once and writes the costs of the lanes that try. */
inline void pms_batch_store_costs(PmsCandidateBatch* batch, const PmsCostInputs* in,
                                  const PmsLanes* lanes, int y, int width,
                                  __global float* cost) {
  pms_floatv costs[1];
  pms_cost_lanes_group(in, lanes, y, batch, 1, costs);
  for (int l = 0; l < PMS_LANES; ++l) {
    if (batch->tries[l]) cost[y * width + lanes->x[l]] = PMS_LANE(costs[0], l);
  }
}

#endif /* FLEXSIGHT_PMS_LANE_COST_H */

// The paper's hybrid mean shift on one packet, in fixed point (golden/cluster/mean_shift.h
// states it in floating point). Per sweep and per point i, over every point j:
//   u     = (x_i - x0_j)^2 + (y_i - y0_j)^2 + (p_i - p_j)^2 + (t_i - t_j)^2   (2 kFeatFrac frac)
//   w     = exp(-u)                        kernel table, 1.kWeightFrac
//   sums  += w, w * x0_j, w * y0_j, w * p_j, w * t_j   (products truncated to kSumFrac)
// then x_i' = sum(w x0) / sum(w) and so on through the reciprocal unit (rounded), so positions
// move against the original positions x0, y0 and appearance (p, t) against the previous
// sweep. A point with no weight stays. Sweeps stop when no coordinate moved more than the
// tolerance, or at max_iterations. Sums are exact integers, so the result does not depend
// on how many lanes evaluate the kernel in parallel.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/cluster/tables.h"

namespace evms::hls {

// Moves phi (x, y, p, t) to the modes in place; returns the sweeps performed.
template <class S>
int mean_shift(Features<S>& phi, int n, const Config& cfg) {
  constexpr int kProductShift = S::kWeightFrac + S::kFeatFrac - S::kSumFrac;
  constexpr int kQuotientFrac = S::kFeatFrac + S::kWeightFrac - S::kSumFrac;  // sums / weight -> phi
  static_assert(kProductShift >= 0, "mean_shift: weights and features carry fewer bits than the sums");
  std::uint32_t x0[S::kPacketMax], y0[S::kPacketMax];
  Features<S> next;
#pragma HLS ARRAY_PARTITION variable = x0 cyclic factor = S::kLanes
#pragma HLS ARRAY_PARTITION variable = y0 cyclic factor = S::kLanes
#pragma HLS ARRAY_PARTITION variable = phi.x cyclic factor = S::kLanes
#pragma HLS ARRAY_PARTITION variable = phi.y cyclic factor = S::kLanes
#pragma HLS ARRAY_PARTITION variable = phi.p cyclic factor = S::kLanes
#pragma HLS ARRAY_PARTITION variable = phi.t cyclic factor = S::kLanes
copy:
  for (int j = 0; j < S::kPacketMax; ++j) {
    if (j >= n) break;
    x0[j] = phi.x[j];
    y0[j] = phi.y[j];
  }
  int sweeps = 0;
iterations:
  for (int k = 0; k < S::kIterationsMax; ++k) {
    if (k >= cfg.max_iterations) break;
    std::uint32_t max_move = 0;
  points:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      const std::int64_t xi = phi.x[i], yi = phi.y[i], pi = phi.p[i], ti = phi.t[i];
      std::uint64_t sw = 0, sx = 0, sy = 0, sp = 0, st = 0;
    kernel:
      for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
#pragma HLS UNROLL factor = S::kLanes
        if (j >= n) break;
        const std::int64_t dx = xi - x0[j], dy = yi - y0[j], dp = pi - phi.p[j], dt = ti - phi.t[j];
        const std::uint64_t u = squared_distance(dx, dy, dp, dt);
        const std::uint64_t w = Tables<S>::exp.template lookup<2 * S::kFeatFrac>(u);
        sw += w;
        sx += (w * x0[j]) >> kProductShift;
        sy += (w * y0[j]) >> kProductShift;
        sp += (w * phi.p[j]) >> kProductShift;
        st += (w * phi.t[j]) >> kProductShift;
      }
      if (sw == 0) {
        next.x[i] = phi.x[i], next.y[i] = phi.y[i], next.p[i] = phi.p[i], next.t[i] = phi.t[i];
      } else {
        next.x[i] = static_cast<std::uint32_t>(Tables<S>::recip.template divide<kQuotientFrac>(sx, sw));
        next.y[i] = static_cast<std::uint32_t>(Tables<S>::recip.template divide<kQuotientFrac>(sy, sw));
        next.p[i] = static_cast<std::uint32_t>(Tables<S>::recip.template divide<kQuotientFrac>(sp, sw));
        next.t[i] = static_cast<std::uint32_t>(Tables<S>::recip.template divide<kQuotientFrac>(st, sw));
      }
      const std::uint32_t moves[4] = {next.x[i] > phi.x[i] ? next.x[i] - phi.x[i] : phi.x[i] - next.x[i],
                                      next.y[i] > phi.y[i] ? next.y[i] - phi.y[i] : phi.y[i] - next.y[i],
                                      next.p[i] > phi.p[i] ? next.p[i] - phi.p[i] : phi.p[i] - next.p[i],
                                      next.t[i] > phi.t[i] ? next.t[i] - phi.t[i] : phi.t[i] - next.t[i]};
      for (std::uint32_t m : moves) max_move = m > max_move ? m : max_move;
    }
  swap:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      phi.x[i] = next.x[i], phi.y[i] = next.y[i], phi.p[i] = next.p[i], phi.t[i] = next.t[i];
    }
    sweeps = k + 1;
    if (max_move <= cfg.tolerance) break;
  }
  return sweeps;
}

}  // namespace evms::hls

// Each cluster's measurement: the centre of mass of its events' pixel positions (kPosFrac
// fraction bits, rounded) timed at the rounded mean of their timestamps; with its event count,
// its bounding box, and its spread squared (the mean squared distance of its events from their
// centre of mass, px^2 with kSpreadFrac fraction bits, exact then rounded half up).
//
// With `midpoint_min` > 0 (exact division only), a cluster with at least that many ON and that
// many OFF events is measured at the midpoint of the two polarities' centres of mass instead:
// x = (Sx_on / n_on + Sx_off / n_off) / 2 = (Sx_on n_off + Sx_off n_on) / (2 n_on n_off), one
// exact division rounded half up, as the centre of mass is. An object's leading and trailing
// edges fire opposite polarities; where one fires more (contrast, speed), the centre of mass
// leans towards it and the midpoint does not.
//
// With `first_on_pixel` (exact division only; it takes the place of the midpoint), a cluster is
// measured at the mean of its pixels, each pixel once: the sums and the count of its events that
// are the first of the packet on their pixel (hls/cluster/link.h marks them). An edge moving
// across its normal fires several events on each pixel it crosses, one moving along it few, and
// where the outline is is where its pixels are, not where most events fire. With
// `time_by_pixels` (Config::pixel_time, a build with HasPixelTime; no RTL build holds it) it is
// timed at the rounded mean timestamp of those same events, the time its pixels were where they
// are. A cluster without such an event (none, with the links on) keeps its centre of mass and
// its time.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/core/shape.h"
#include "hls/cluster/tables.h"

namespace evms::hls {

struct Measurement {
  std::uint32_t t = 0;
  std::int32_t x = 0, y = 0;  // kPosFrac fraction bits, px
  std::uint32_t events = 0;
  std::uint16_t x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  std::uint64_t spread2 = 0;  // px^2, kSpreadFrac fraction bits
};

// `exact`: divide exactly (integer division, rounded half up) instead of through the reciprocal
// table; the seeded path does, the RTL's path (the Gaussian one) does not.
template <class S>
void centroids(const PacketEvents<S>& ev, int n, const std::int8_t cluster_of[S::kPacketMax], int clusters,
               Measurement out[S::kClustersMax], bool exact = false, std::uint16_t midpoint_min = 0,
               const bool* first_on_pixel = nullptr, bool time_by_pixels = false) {
  std::uint32_t sx[S::kClustersMax] = {}, sy[S::kClustersMax] = {}, count[S::kClustersMax] = {};
  std::uint32_t sx_on[S::kClustersMax] = {}, sy_on[S::kClustersMax] = {}, count_on[S::kClustersMax] = {};
  std::uint32_t sx_px[S::kClustersMax] = {}, sy_px[S::kClustersMax] = {}, count_px[S::kClustersMax] = {};
  std::uint64_t st[S::kClustersMax] = {}, st_px[S::kClustersMax] = {}, s2[S::kClustersMax] = {};
  std::uint16_t x0[S::kClustersMax], y0[S::kClustersMax], x1[S::kClustersMax], y1[S::kClustersMax];
  const std::uint32_t t0 = ev.t[0];
accumulate:
  for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
    if (i >= n) break;
    const int c = cluster_of[i];
    if (c < 0) continue;
    if (count[c] == 0) x0[c] = x1[c] = ev.x[i], y0[c] = y1[c] = ev.y[i];
    x0[c] = ev.x[i] < x0[c] ? ev.x[i] : x0[c], x1[c] = ev.x[i] > x1[c] ? ev.x[i] : x1[c];
    y0[c] = ev.y[i] < y0[c] ? ev.y[i] : y0[c], y1[c] = ev.y[i] > y1[c] ? ev.y[i] : y1[c];
    sx[c] += ev.x[i];
    sy[c] += ev.y[i];
    if (ev.p[i]) sx_on[c] += ev.x[i], sy_on[c] += ev.y[i], ++count_on[c];
    if (first_on_pixel != nullptr && first_on_pixel[i]) sx_px[c] += ev.x[i], sy_px[c] += ev.y[i], st_px[c] += ev.t[i] - t0, ++count_px[c];
    s2[c] += std::uint64_t{ev.x[i]} * ev.x[i] + std::uint64_t{ev.y[i]} * ev.y[i];
    st[c] += ev.t[i] - t0;
    ++count[c];
  }
divide:
  for (int c = 0; c < S::kClustersMax; ++c) {
    if (c >= clusters) break;
    if (exact) {
      const std::uint64_t n = count[c], n_on = count_on[c], n_off = n - n_on;
      // The x and y quotients' numerators (before the kPosFrac shift) and denominator.
      std::uint64_t num_x = sx[c], num_y = sy[c], den = n;
      // The time's numerator and denominator.
      std::uint64_t num_t = st[c], den_t = n;
      if (first_on_pixel != nullptr && count_px[c] > 0) {
        num_x = sx_px[c], num_y = sy_px[c], den = count_px[c];
        if (time_by_pixels) num_t = st_px[c], den_t = count_px[c];
      } else if (midpoint_min > 0 && n_on >= midpoint_min && n_off >= midpoint_min) {
        num_x = std::uint64_t{sx_on[c]} * n_off + std::uint64_t{sx[c] - sx_on[c]} * n_on;
        num_y = std::uint64_t{sy_on[c]} * n_off + std::uint64_t{sy[c] - sy_on[c]} * n_on;
        den = 2 * n_on * n_off;
      }
      out[c].x = static_cast<std::int32_t>(((num_x << (S::kPosFrac + 1)) + den) / (2 * den));
      out[c].y = static_cast<std::int32_t>(((num_y << (S::kPosFrac + 1)) + den) / (2 * den));
      out[c].t = t0 + static_cast<std::uint32_t>((2 * num_t + den_t) / (2 * den_t));
    } else {
      out[c].x = static_cast<std::int32_t>(Tables<S>::recip.template divide<S::kPosFrac>(sx[c], count[c]));
      out[c].y = static_cast<std::int32_t>(Tables<S>::recip.template divide<S::kPosFrac>(sy[c], count[c]));
      out[c].t = t0 + static_cast<std::uint32_t>(Tables<S>::recip.template divide<0>(st[c], count[c]));
    }
    out[c].events = count[c];
    out[c].x_min = x0[c], out[c].y_min = y0[c], out[c].x_max = x1[c], out[c].y_max = y1[c];
    // n^2 var = n S2 - Sx^2 - Sy^2, exact; then var = that / n^2.
    const std::uint64_t n = count[c];
    const std::uint64_t n2var = n * s2[c] - std::uint64_t{sx[c]} * sx[c] - std::uint64_t{sy[c]} * sy[c];
    out[c].spread2 = ((n2var << (kSpreadFrac + 1)) / (n * n) + 1) >> 1;
  }
}

}  // namespace evms::hls

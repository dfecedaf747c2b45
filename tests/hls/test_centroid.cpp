// The core's exact measurements (hls/cluster/centroid.h) against the real numbers they round:
// the centre of mass, the polarity midpoint and the pixel centre, each within half a unit of
// kPosFrac (the rounding's bound), and their times (the mean timestamp of the events they were
// measured from: with the pixel time, the pixel centre's first events on their pixels, else all) within half a
// microsecond, on dense random clusters of every polarity balance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>

#include "hls/cluster/centroid.h"
#include "hls/core/shape.h"
#include "host/gen/random.h"

namespace evms::hls {
namespace {

using WideShape = RtlHostShape;

TEST(Centroids, ExactCentrePolarityMidpointPixelCentreAndTimesWithinHalfAUnitOfTheirRealValues) {
  gen::Random rng(11);
  const double unit = std::ldexp(1.0, -WideShape::kPosFrac);
  auto ev = std::make_unique<PacketEvents<WideShape>>();
  std::int8_t cluster_of[WideShape::kPacketMax];
  bool first_on_pixel[WideShape::kPacketMax];
  int midpoints = 0, centres = 0, pixel_centres = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(WideShape::kPacketMax));
    const int clusters = 1 + static_cast<int>(rng.below(n < WideShape::kClustersMax ? n : WideShape::kClustersMax));
    const double on_share = rng.uniform();  // from all OFF to all ON
    const std::uint16_t midpoint_min = static_cast<std::uint16_t>(rng.below(3) == 0 ? 0 : 1 + rng.below(24));
    // A third of the trials measure by the pixels: the events marked first on their pixel, a
    // random share of them (a cluster may have none: its centre of mass).
    const bool by_pixels = rng.below(3) == 0;
    const double first_share = rng.uniform();
    const bool time_by_pixels = by_pixels && rng.below(2) == 0;  // Config::pixel_time
    for (int i = 0; i < n; ++i) {
      // Coordinates up to the host sensor's, so the sums reach their widest.
      ev->x[i] = static_cast<std::uint16_t>(rng.below(1280)), ev->y[i] = static_cast<std::uint16_t>(rng.below(720));
      ev->p[i] = rng.uniform() < on_share ? 1 : 0;
      // Ordered times with gaps of up to 2^19 us, so the sums of ages reach well past 32 bits.
      ev->t[i] = i == 0 ? static_cast<std::uint32_t>(rng.below(1u << 28)) : ev->t[i - 1] + static_cast<std::uint32_t>(rng.below(1u << 19));
      // The first event of each cluster is its own (the core measures no empty cluster).
      cluster_of[i] = static_cast<std::int8_t>(i < clusters ? i : rng.below(4) == 0 ? -1 : static_cast<int>(rng.below(clusters)));
      first_on_pixel[i] = rng.uniform() < first_share;
    }
    Measurement out[WideShape::kClustersMax];
    centroids<WideShape>(*ev, n, cluster_of, clusters, out, true, midpoint_min, by_pixels ? first_on_pixel : nullptr, time_by_pixels);
    for (int c = 0; c < clusters; ++c) {
      double sx[2] = {0, 0}, sy[2] = {0, 0}, px = 0, py = 0, age = 0, pixel_age = 0;
      int count[2] = {0, 0}, pixels = 0;
      for (int i = 0; i < n; ++i) {
        if (cluster_of[i] != c) continue;
        sx[ev->p[i]] += ev->x[i], sy[ev->p[i]] += ev->y[i], ++count[ev->p[i]];
        age += ev->t[i] - ev->t[0];
        if (first_on_pixel[i]) px += ev->x[i], py += ev->y[i], pixel_age += ev->t[i] - ev->t[0], ++pixels;
      }
      const int events = count[0] + count[1];
      ASSERT_EQ(out[c].events, static_cast<std::uint32_t>(events));
      const bool pixel_centre = by_pixels && pixels > 0;
      const bool midpoint = !pixel_centre && midpoint_min > 0 && count[0] >= midpoint_min && count[1] >= midpoint_min;
      double x = midpoint ? 0.5 * (sx[0] / count[0] + sx[1] / count[1]) : (sx[0] + sx[1]) / events;
      double y = midpoint ? 0.5 * (sy[0] / count[0] + sy[1] / count[1]) : (sy[0] + sy[1]) / events;
      if (pixel_centre) x = px / pixels, y = py / pixels;
      ++(pixel_centre ? pixel_centres : midpoint ? midpoints : centres);
      ASSERT_LE(std::abs(out[c].x * unit - x), 0.5 * unit * (1 + 1e-9)) << "trial " << trial << " cluster " << c;
      ASSERT_LE(std::abs(out[c].y * unit - y), 0.5 * unit * (1 + 1e-9)) << "trial " << trial << " cluster " << c;
      const double mean_age = pixel_centre && time_by_pixels ? pixel_age / pixels : age / events;
      ASSERT_LE(std::abs(static_cast<double>(out[c].t - ev->t[0]) - mean_age), 0.5 * (1 + 1e-9)) << "trial " << trial << " cluster " << c;
    }
  }
  // Every rule was exercised, many times each.
  EXPECT_GT(midpoints, 700);
  EXPECT_GT(centres, 700);
  EXPECT_GT(pixel_centres, 700);
}

}  // namespace
}  // namespace evms::hls

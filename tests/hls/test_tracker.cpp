// The per-axis Kalman filter: the split is exact, the fixed-point filter follows the double
// one, and its covariance stays symmetric and positive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "golden/track/kalman_filter.h"
#include "golden/track/tracker.h"
#include "hls/fixed/stream.h"
#include "hls/track/tracker.h"
#include "hls/core/shape.h"
#include "hls/track/kalman_axis.h"
#include "hls/track/measurement_variance.h"
#include "host/backend/core_config.h"
#include "host/gen/random.h"

namespace evms::hls {
namespace {

using S = HostShape;

// The 2-state filter of one axis in double precision: the equations of kalman_axis.h.
struct AxisDouble {
  double pos, vel, p00, p01, p11;
  void predict(double dt, double q) {
    pos += vel * dt;
    p00 += 2 * dt * p01 + dt * dt * p11 + q * dt * dt * dt / 3;
    p01 += dt * p11 + q * dt * dt / 2;
    p11 += q * dt;
  }
  void update(double z, double r) {
    const double s = p00 + r, k0 = p00 / s, k1 = p01 / s, e = z - pos;
    pos += k0 * e;
    vel += k1 * e;
    const double old01 = p01;
    p00 = r * k0;
    p01 = r * k1;
    p11 -= k1 * old01;
  }
};

TEST(KalmanSplit, TwoAxisFiltersEqualTheFourStateFilter) {
  Params p = preset("gaussian");
  gen::Random rng(11);
  golden::KalmanFilter four(30, 40, 0, p);
  const double sp2 = p.init_sigma_px * p.init_sigma_px, sv2 = p.init_sigma_vel * p.init_sigma_vel;
  AxisDouble ax{30, 0, sp2, 0, sv2}, ay{40, 0, sp2, 0, sv2};
  TimeUs t = 0;
  const double r = p.meas_sigma_px * p.meas_sigma_px;
  for (int k = 0; k < 5000; ++k) {
    const TimeUs dt = 200 + static_cast<TimeUs>(rng.below(20000));
    t += dt;
    const double zx = 30 + 0.1 * k + rng.normal(), zy = 40 - 0.05 * k + rng.normal();
    four.predict(t);
    four.update(zx, zy);
    ax.predict(dt * 1e-6, p.accel_psd), ay.predict(dt * 1e-6, p.accel_psd);
    ax.update(zx, r), ay.update(zy, r);
    const auto& x = four.state();
    const auto& c = four.covariance();
    ASSERT_NEAR(x(0), ax.pos, 1e-9 * (1 + std::abs(ax.pos)));
    ASSERT_NEAR(x(1), ay.pos, 1e-9 * (1 + std::abs(ay.pos)));
    ASSERT_NEAR(x(2), ax.vel, 1e-9 * (1 + std::abs(ax.vel)));
    ASSERT_NEAR(x(3), ay.vel, 1e-9 * (1 + std::abs(ay.vel)));
    ASSERT_NEAR(c(0, 0), ax.p00, 1e-9 * ax.p00);
    ASSERT_NEAR(c(0, 2), ax.p01, 1e-9 * (1 + std::abs(ax.p01)));
    ASSERT_NEAR(c(2, 2), ax.p11, 1e-9 * ax.p11);
    // The cross-axis terms stay exactly zero: the axes never couple.
    ASSERT_EQ(c(0, 1), 0.0);
    ASSERT_EQ(c(0, 3), 0.0);
    ASSERT_EQ(c(2, 3), 0.0);
  }
}

TEST(KalmanAxisFixed, FollowsTheDoubleFilter) {
  Params p = preset("gaussian");
  const Config cfg = backend::core_config<S>(p, {240, 180});
  const double tick = std::ldexp(1.0, S::kTickLog2) * 1e-6, pos_unit = std::ldexp(1.0, -S::kPosFrac);
  gen::Random rng(12);
  AxisState a{static_cast<std::int32_t>(std::lround(50 / pos_unit)), 0, cfg.p0_pos, 0, cfg.p0_vel};
  AxisDouble d{50, 0, p.init_sigma_px * p.init_sigma_px, 0, p.init_sigma_vel * p.init_sigma_vel};
  double worst_pos = 0, worst_vel = 0;
  double truth = 50;
  for (int k = 0; k < 20000; ++k) {
    const std::uint32_t dt = 500 + static_cast<std::uint32_t>(rng.below(5000));
    truth += 80.0 * dt * 1e-6;
    const double z = truth + 0.7 * rng.normal();
    const auto zq = static_cast<std::int32_t>(std::lround(z / pos_unit));
    KalmanAxis<S>::predict(a, dt, cfg);
    KalmanAxis<S>::update(a, zq, cfg.r);
    d.predict(dt * 1e-6, p.accel_psd);
    d.update(zq * pos_unit, p.meas_sigma_px * p.meas_sigma_px);
    if (k > 100) {
      worst_pos = std::max(worst_pos, std::abs(a.pos * pos_unit - d.pos));
      worst_vel = std::max(worst_vel, std::abs(a.vel * pos_unit / tick - d.vel));
    }
  }
  EXPECT_LT(worst_pos, 0.01);   // px
  EXPECT_LT(worst_vel, 0.5);    // px/s, on a target moving at 80 px/s
}

// The largest process noise the core takes (backend::max_accel_psd): its q/3 times the longest
// step's dt^3, with its rounding half, is the largest number in the filter, and the filter still
// follows the double one over steps up to the longest (kMaxDt); one step more noise is refused.
// After a 262 ms coast, a filter this loose has taken a velocity of 10^4 px/s from 1 px of
// measurement noise over a short step, so its position moves thousands of px, and the gain's 20
// fraction bits of that innovation bound the worst difference; on average it is 1e-4 px.
TEST(KalmanAxisFixed, TheLargestProcessNoiseTheCoreTakesFollowsTheDoubleFilter) {
  Params p;
  p.accel_psd_width = 0;
  p.accel_psd = backend::max_accel_psd<S>();
  const Config cfg = backend::core_config<S>(p, {240, 180});
  EXPECT_GT(cfg.q_third, std::int64_t{1} << 34) << "the largest product is near 2^63";
  Params over = p;
  over.accel_psd *= 1.001;
  EXPECT_THROW(backend::core_config<S>(over, {240, 180}), std::invalid_argument);

  const double pos_unit = std::ldexp(1.0, -S::kPosFrac);
  gen::Random rng(14);
  AxisState a{0, 0, cfg.p0_pos, 0, cfg.p0_vel};
  AxisDouble d{0, 0, p.init_sigma_px * p.init_sigma_px, 0, p.init_sigma_vel * p.init_sigma_vel};
  double truth = 0, v = 0, worst_pos = 0, sum_pos = 0, worst_from_z = 0;
  constexpr int kUpdates = 200000;
  for (int k = 0; k < kUpdates; ++k) {
    const std::uint32_t dt = k % 500 == 0 ? KalmanAxis<S>::kMaxDt : 100 + static_cast<std::uint32_t>(rng.below(20000));
    v += 200 * rng.normal();
    truth += v * dt * 1e-6;
    if (std::abs(truth) > 1000 || std::abs(v) > 5000) truth = 0, v = 0;
    const auto zq = static_cast<std::int32_t>(std::lround((truth + rng.normal()) / pos_unit));
    KalmanAxis<S>::predict(a, dt, cfg);
    KalmanAxis<S>::update(a, zq, cfg.r);
    d.predict(dt * 1e-6, p.accel_psd);
    d.update(zq * pos_unit, p.meas_sigma_px * p.meas_sigma_px);
    ASSERT_GT(a.p00, 0) << k;
    ASSERT_GT(a.p11, 0) << k;
    ASSERT_LT(a.p00, KalmanAxis<S>::kCovMax) << k << ": saturated";
    const double apart = std::abs(a.pos * pos_unit - d.pos);
    worst_pos = std::max(worst_pos, apart);
    sum_pos += apart;
    worst_from_z = std::max(worst_from_z, std::abs(a.pos - zq) * pos_unit);
  }
  EXPECT_LT(worst_pos, 0.05);              // px
  EXPECT_LT(sum_pos / kUpdates, 0.001);    // px
  EXPECT_GT(worst_from_z, 0.01) << "the filter is not just its measurement";
}

// Symmetric by construction (one p01 per axis); positive definite over 10^6 updates with
// steps from 100 us to 60 ms, including long coasts.
TEST(KalmanAxisFixed, CovarianceStaysPositiveOverAMillionUpdates) {
  Params p = preset("gaussian");
  const Config cfg = backend::core_config<S>(p, {240, 180});
  gen::Random rng(13);
  AxisState a{0, 0, cfg.p0_pos, 0, cfg.p0_vel};
  double truth = 0, v = 50;
  for (int k = 0; k < 1000000; ++k) {
    const std::uint32_t dt = 100 + static_cast<std::uint32_t>(rng.below(k % 1000 == 0 ? 60000 : 5000));
    v += 20 * rng.normal();
    truth += v * dt * 1e-6;
    if (std::abs(truth) > 1500) truth = 0, v = 0;
    KalmanAxis<S>::predict(a, dt, cfg);
    KalmanAxis<S>::update(a, static_cast<std::int32_t>(std::lround((truth + rng.normal()) * 4096)), cfg.r);
    const __int128 det = static_cast<__int128>(a.p00) * a.p11 - static_cast<__int128>(a.p01) * a.p01;
    ASSERT_GT(a.p00, 0) << k;
    ASSERT_GT(a.p11, 0) << k;
    ASSERT_GT(det, 0) << k;
  }
}

// measurement_variance against r (spread^2 + 1/6) / events in double precision, densely over
// spreads from 0 to 1,000 px (geometric steps, and every 1/256 px^2 up to 1 px^2), event counts
// from 1 to 4,096 and r from 0.01 to 100 px^2, to the bound stated in
// hls/track/measurement_variance.h.
TEST(MeasurementVarianceFixed, FollowsTheScatterOfTheCentreOfMassWithinItsBound) {
  Config cfg;
  cfg.meas_from_spread = true;
  std::vector<std::uint64_t> spreads2;
  for (std::uint64_t v = 0; v <= 256; ++v) spreads2.push_back(v);
  for (double v = 257; v < 1000.0 * 1000 * 256; v *= 1.05) spreads2.push_back(static_cast<std::uint64_t>(v));
  std::vector<std::uint32_t> counts;
  for (std::uint32_t n = 1; n <= 64; ++n) counts.push_back(n);
  for (double n = 65; n <= 4096; n *= 1.07) counts.push_back(static_cast<std::uint32_t>(n));
  counts.push_back(4096);
  const double unit = std::ldexp(1.0, S::kCovFrac);
  std::int64_t checked = 0;
  for (const double r_px2 : {0.01, 1.0, 100.0}) {
    cfg.r = std::llround(r_px2 * unit);
    for (const std::uint64_t spread2 : spreads2) {
      for (const std::uint32_t n : counts) {
        Measurement z;
        z.events = n, z.spread2 = spread2;
        const double per_event = std::min((std::ldexp(static_cast<double>(spread2), -kSpreadFrac) + 1.0 / 6) / n,
                                          std::ldexp(std::ldexp(1.0, S::kPerEventLog2) - 1, -S::kPerEventFrac));
        const double exact = std::clamp(static_cast<double>(cfg.r) * per_event, 1.0, static_cast<double>(KalmanAxis<S>::kCovMax));
        const double bound = static_cast<double>(cfg.r) * (std::ldexp(1.0, -17) + 1.0 / (768.0 * n)) + 0.5 + 1e-9 * exact;
        const auto got = static_cast<double>(measurement_variance<S>(z, cfg));
        ASSERT_LE(std::abs(got - exact), bound) << "r " << r_px2 << " px^2, spread2 " << spread2 << ", events " << n;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100000);
  // Off, or a measurement without events: r itself.
  Measurement z;
  z.events = 100, z.spread2 = 1 << 20;
  cfg.meas_from_spread = false;
  EXPECT_EQ(measurement_variance<S>(z, cfg), cfg.r);
  cfg.meas_from_spread = true;
  z.events = 0;
  EXPECT_EQ(measurement_variance<S>(z, cfg), cfg.r);
}

// The fixed-point tracker gives every cluster the ID the golden one gives, packet by packet, on
// objects that wander, merge into one cluster (a box over both) and split into fragments, with
// gate_boxes on and off: association against the last measurement on whole-pixel centres is
// exact in both, so the IDs must be equal, not near.
TEST(TrackerFixed, GivesTheGoldenTrackersIdsThroughMergesAndSplits) {
  std::int32_t started[2] = {};
  for (const bool boxes : {false, true}) {
    Params p;  // the defaults: association to the last measurement, the size ratio, eviction
    p.gate_boxes = boxes;
    p.max_tracks = 8;
    const Config cfg = backend::core_config<S>(p, {240, 180});
    golden::MultiTargetTracker gold(p);
    auto fixed = std::make_unique<Tracker<S>>();
    fixed->reset();
    gen::Random rng(boxes ? 21 : 22);
    struct Object { int x, y; };
    std::vector<Object> objects;
    for (int k = 0; k < 5; ++k) objects.push_back({20 + static_cast<int>(rng.below(200)), 20 + static_cast<int>(rng.below(140))});
    std::int64_t compared = 0;
    for (int packet = 0; packet < 3000; ++packet) {
      const std::uint32_t t = 1000u * static_cast<std::uint32_t>(packet + 1);
      std::vector<golden::Measurement> zs;
      const auto add = [&](int x, int y, int half, int events) {
        golden::Measurement z{t, double(x), double(y), events};
        z.x_min = std::max(0, x - half), z.y_min = std::max(0, y - half), z.x_max = x + half, z.y_max = y + half;
        zs.push_back(z);
      };
      for (size_t k = 0; k < objects.size(); ++k) {
        Object& o = objects[k];
        o.x = std::clamp(o.x + static_cast<int>(rng.below(7)) - 3, 10, 230);
        o.y = std::clamp(o.y + static_cast<int>(rng.below(7)) - 3, 10, 170);
        const int mode = static_cast<int>(rng.below(10));
        if (mode == 0 && k + 1 < objects.size()) {  // merged with the next object
          const Object& n = objects[k + 1];
          add((o.x + n.x) / 2, (o.y + n.y) / 2, std::max(std::abs(o.x - n.x), std::abs(o.y - n.y)) / 2 + 8, 200);
          ++k;
        } else if (mode == 1) {  // split into two fragments
          add(o.x - 12, o.y, 6, 40);
          add(o.x + 12, o.y, 6, 40);
        } else if (mode != 2) {  // mode 2: missed
          add(o.x, o.y, 8, 100);
        }
      }
      if (zs.size() > static_cast<size_t>(S::kClustersMax)) zs.resize(S::kClustersMax);
      std::vector<TrackUpdate> updates;
      const std::vector<std::int32_t> want = gold.step(t, zs, updates);
      Measurement z[S::kClustersMax];
      for (size_t k = 0; k < zs.size(); ++k) {
        z[k].t = zs[k].t;
        z[k].x = static_cast<std::int32_t>(zs[k].x) << S::kPosFrac;
        z[k].y = static_cast<std::int32_t>(zs[k].y) << S::kPosFrac;
        z[k].events = static_cast<std::uint32_t>(zs[k].events);
        z[k].x_min = static_cast<std::uint16_t>(zs[k].x_min), z[k].y_min = static_cast<std::uint16_t>(zs[k].y_min);
        z[k].x_max = static_cast<std::uint16_t>(zs[k].x_max), z[k].y_max = static_cast<std::uint16_t>(zs[k].y_max);
      }
      std::int32_t got[S::kClustersMax];
      Stream<TrackWord, S::kClustersMax> words;
      fixed->step(t, z, static_cast<int>(zs.size()), cfg, got, words);
      for (size_t k = 0; k < zs.size(); ++k, ++compared) ASSERT_EQ(got[k], want[k]) << "packet " << packet << ", cluster " << k;
    }
    EXPECT_GT(compared, 10000);
    EXPECT_EQ(fixed->tracks_started(), gold.tracks_started());
    started[boxes] = gold.tracks_started();
  }
  EXPECT_LT(2 * started[1], started[0]) << "with the boxes, merges and splits keep their IDs";
}

}  // namespace
}  // namespace evms::hls

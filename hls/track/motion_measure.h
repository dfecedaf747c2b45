// A fast object's cluster measured from the pixels its own motion explains: the fixed-point
// form of golden/track/motion_measure.h (Config::motion_speed; a build with HasMotionMeasure).
//
// A cluster whose bounding box, grown by 2 px, holds the prediction of a confirmed track that
// was matched in the packet before and moves at least motion_speed (of those, the one nearest
// the cluster's measurement, squared distances in kPosFrac units, ties to the lower slot), and
// the prediction of another confirmed track (coasting or not, at any speed), is measured at the
// mean of the pixels of its events whose time-surface slopes that track's
// velocity explains (hls/cluster/time_surface_slopes.h), each pixel once, when those are at
// least half of its pixels (each counted for the packet's first event of such a cluster on it).
// The tracks are predicted to the packet's middle event, as golden's are. The mean is one exact
// division rounded half up, as the pixel centre's (hls/cluster/centroid.h).
#pragma once

#include <cstdint>

#include "hls/cluster/centroid.h"
#include "hls/cluster/features.h"
#include "hls/cluster/time_surface_slopes.h"
#include "hls/core/config.h"
#include "hls/track/tracker.h"

namespace evms::hls {

template <class S>
class MotionMeasure {
 public:
  static constexpr int kTrackInBoxMarginPx = 2;
  static constexpr int kPixels = S::kHasMotionMeasure ? S::kMaxWidth * S::kMaxHeight : 1;

  void reset() {
    slopes_.reset();
  unmark:
    for (int i = 0; i < kPixels; ++i) pixel_marks_[i] = 0;
  }

  // Replaces the x and y of each measurement z[0..clusters) the rule holds for; cluster_of: per
  // event of the packet ev[0..n), its cluster or -1.
  void measure(const PacketEvents<S>& ev, int n, const std::int8_t cluster_of[S::kPacketMax], int clusters, const Tracker<S>& tracker,
               const Config& cfg, Measurement z[S::kClustersMax]) {
    TrackPoint confirmed[S::kTracksMax];
    const int tracks = tracker.confirmed_tracks(ev.t[n / 2], cfg, confirmed);
    bool fast[S::kTracksMax];
    const std::uint64_t least2 = std::uint64_t{cfg.motion_speed} * cfg.motion_speed;
  speeds:
    for (int k = 0; k < S::kTracksMax; ++k) {
#pragma HLS PIPELINE II = 1
      if (k >= tracks) break;
      // Squares of 32-bit words: their sum fits 64 unsigned bits.
      const std::uint64_t vx = static_cast<std::uint64_t>(confirmed[k].vx < 0 ? -std::int64_t{confirmed[k].vx} : confirmed[k].vx);
      const std::uint64_t vy = static_cast<std::uint64_t>(confirmed[k].vy < 0 ? -std::int64_t{confirmed[k].vy} : confirmed[k].vy);
      fast[k] = confirmed[k].matched && vx * vx + vy * vy >= least2;
    }
    std::int16_t track_of[S::kClustersMax];
    bool any = false;
  nearest:
    for (int c = 0; c < S::kClustersMax; ++c) {
      if (c >= clusters) break;
      track_of[c] = -1;
      std::int64_t nearest2 = 0;
      bool in_box[S::kTracksMax];
    fast_in_box:
      for (int k = 0; k < S::kTracksMax; ++k) {
#pragma HLS PIPELINE II = 1
        if (k >= tracks) break;
        const TrackPoint& track = confirmed[k];
        in_box[k] = in_grown_box<S::kPosFrac>(track, z[c].x_min, z[c].y_min, z[c].x_max, z[c].y_max, kTrackInBoxMarginPx);
        if (!fast[k] || !in_box[k]) continue;
        const std::int64_t dx = std::int64_t{track.x} - z[c].x, dy = std::int64_t{track.y} - z[c].y;
        const std::int64_t d2 = dx * dx + dy * dy;
        if (track_of[c] < 0 || d2 < nearest2) track_of[c] = static_cast<std::int16_t>(k), nearest2 = d2;
      }
      bool beside_another = false;
    another_in_box:
      for (int k = 0; k < S::kTracksMax; ++k) {
#pragma HLS PIPELINE II = 1
        if (k >= tracks) break;
        if (k != track_of[c] && in_box[k]) beside_another = true;
      }
      if (!beside_another) track_of[c] = -1;
      any = any || track_of[c] >= 0;
    }
    if (!any) return;
    slopes_.add(ev, n);
    std::uint32_t pixels[S::kClustersMax] = {}, kept[S::kClustersMax] = {}, kept_x[S::kClustersMax] = {}, kept_y[S::kClustersMax] = {};
  keep:
    for (int i = 0; i < S::kPacketMax; ++i) {
      if (i >= n) break;
      const int c = cluster_of[i];
      if (c < 0 || track_of[c] < 0) continue;
      std::uint8_t& marks = pixel_marks_[pixel(ev.x[i], ev.y[i])];
      if (!(marks & kCounted)) marks |= kCounted, ++pixels[c];
      if (marks & kKept) continue;
      const TrackPoint& track = confirmed[track_of[c]];
      if (!slopes_.explains(ev.p[i], ev.x[i], ev.y[i], track.vx, track.vy, cfg)) continue;
      marks |= kKept;
      kept_x[c] += ev.x[i], kept_y[c] += ev.y[i], ++kept[c];
    }
  unmark_packet:
    for (int i = 0; i < S::kPacketMax; ++i) {
#pragma HLS PIPELINE II = 1
      if (i >= n) break;
      pixel_marks_[pixel(ev.x[i], ev.y[i])] = 0;
    }
    slopes_.clear(n);
  replace:
    for (int c = 0; c < S::kClustersMax; ++c) {
      if (c >= clusters) break;
      if (kept[c] == 0 || 2 * kept[c] < pixels[c]) continue;
      const std::uint64_t den = kept[c];
      z[c].x = static_cast<std::int32_t>(((std::uint64_t{kept_x[c]} << (S::kPosFrac + 1)) + den) / (2 * den));
      z[c].y = static_cast<std::int32_t>(((std::uint64_t{kept_y[c]} << (S::kPosFrac + 1)) + den) / (2 * den));
    }
  }

 private:
  static constexpr std::uint8_t kCounted = 1, kKept = 2;
  static int pixel(int x, int y) { return S::kHasMotionMeasure ? y * S::kMaxWidth + x : 0; }

  TimeSurfaceSlopes<S> slopes_;
  std::uint8_t pixel_marks_[kPixels];  // per pixel, within one packet: kCounted, kKept
};

}  // namespace evms::hls

// Multi-target tracking of cluster centres.
//
// Each packet's clusters are measurements. Per packet:
//  1. Tracks whose last measurement is older than coast_us at the packet's newest event end.
//  2. Every (track, measurement) pair whose distance between the measurement and the track's
//     prediction at the measurement's time is within the gate is a candidate. Pairs are
//     taken greedily, nearest first (ties: lower track slot, then lower measurement), each
//     track and each measurement at most once, so no two clusters share an ID.
//  3. A matched track is predicted to its measurement's time and updated. After confirm_hits
//     measurements it is confirmed, and every update of a confirmed track is reported.
//  4. An unmatched tentative track ends at once; an unmatched confirmed track coasts.
//  5. Each unmatched measurement starts a tentative track in the lowest free slot, with a new
//     ID from a counter that never repeats. With every slot taken, the measurement gets no
//     track and its events are labelled noise (counted in unassigned_clusters).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "golden/event.h"
#include "golden/params.h"
#include "golden/track/kalman_filter.h"

namespace evms::golden {

struct Measurement {
  TimeUs t = 0;        // mean timestamp of the cluster's events
  double x = 0, y = 0; // centre of mass of the cluster's events, px
};

class MultiTargetTracker {
 public:
  explicit MultiTargetTracker(const Params& params);

  // Returns the track ID assigned to each measurement (kNoiseLabel when none) and appends
  // the updates of confirmed tracks to `updates`.
  std::vector<std::int32_t> step(TimeUs packet_time, std::span<const Measurement> measurements,
                                 std::vector<TrackUpdate>& updates);

  int live_tracks() const;
  std::int64_t unassigned_clusters() const { return unassigned_clusters_; }
  std::int32_t tracks_started() const { return next_id_; }

 private:
  struct Track {
    std::int32_t id;
    KalmanFilter filter;
    int hits;
    bool confirmed;
  };

  Params params_;
  std::vector<std::optional<Track>> slots_;
  std::int32_t next_id_ = 0;
  std::int64_t unassigned_clusters_ = 0;
};

}  // namespace evms::golden

// Identities across packets: each packet's clusters are measurements, and each gets the ID of a
// track (or none, and its events become noise).
//
// MultiTargetTracker (association kalman), per packet:
//  1. Confirmed tracks whose last measurement is older than coast_us at the packet's newest
//     event, or that missed more than coast_packets packets in a row (when set), end.
//  2. Every (track, measurement) pair whose distance between the measurement and the track's
//     prediction at the measurement's time is within the gate is a candidate. The gate is
//     gate_px, or gate_spread times the measurement's spread (the RMS distance of its events
//     from their centre) when that is larger. With gate_boxes, a pair beyond the gate is a
//     candidate too when the track's last measurement lies in the measurement's bounding box or
//     the measurement in the box of the track's last one, taken only after every pair within
//     the gate: when an object merges with a neighbour into one cluster, or a cluster splits
//     into its objects, the centre jumps farther than the gate, and the cluster keeps the ID of
//     a track it covers instead of starting a new one. Pairs are taken greedily, nearest first
//     (ties: lower track slot, then lower measurement), each track and each measurement at most
//     once, so no two clusters share an ID. With size_ratio, a pair whose event counts (the
//     measurement's and the track's last) differ by more than that factor is taken only after
//     every pair within it: a faint object's track does not take a bright cluster that passes
//     over it while the bright cluster's own track wants it, yet an object that grows or shrinks
//     fast (entering or leaving the view) keeps its track when nothing else claims it.
//  3. A matched track is predicted to its measurement's time and updated, and reported (a
//     tentative one only with report_tentative). After confirm_hits measurements it is
//     confirmed.
//  4. An unmatched tentative track ends at once; an unmatched confirmed track coasts.
//  5. Each unmatched measurement starts a tentative track in the lowest free slot, with a new
//     ID from a counter that never repeats, and is reported as in 3. With every slot taken, it takes
//     the slot of the unmatched track measured longest ago when evict_stale is set; otherwise
//     it gets no track and its events are labelled noise (counted in unassigned_clusters).
//
// NearestCentreIds (association nearest-centre) is the authors' rule: each cluster takes the
// ID of the nearest cluster of the previous packet within gate_px (several may take the same
// one), or a new ID. It has no filter: a track's estimate is its cluster's centre.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "types/event.h"
#include "types/params.h"
#include "golden/track/kalman_filter.h"

namespace evms::golden {

struct Box {
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;  // px, inclusive
  // Whether the pixel a point falls in (its coordinates' whole parts) is one of the box's.
  bool holds(double x, double y) const {
    const double px = std::floor(x), py = std::floor(y);
    return px >= x_min && px <= x_max && py >= y_min && py <= y_max;
  }
};

struct Measurement {
  TimeUs t = 0;         // mean timestamp of the cluster's events
  double x = 0, y = 0;  // centre of mass of the cluster's events, px
  int events = 0;
  double spread = 0;    // RMS distance of the events from (x, y), px
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  Box box() const { return {x_min, y_min, x_max, y_max}; }
};

// A track's predicted position (px) and its velocity (px/s).
struct TrackPrediction {
  Eigen::Vector2d position, velocity;
  bool matched = true;   // measured in the last packet; false: coasting
  std::int32_t id = -1;  // the ID its events are labelled with
};

// What every identity rule does with a packet's measurements.
class Tracker {
 public:
  virtual ~Tracker() = default;
  // Returns the ID given to each measurement (kNoiseLabel when none) and appends the updates
  // to report to `updates`.
  virtual std::vector<std::int32_t> step(TimeUs packet_time, std::span<const Measurement> measurements,
                                         std::vector<TrackUpdate>& updates) = 0;
  virtual std::int32_t tracks_started() const = 0;
  virtual std::int64_t unassigned_clusters() const { return 0; }
  // The confirmed tracks, coasting ones too, predicted to t (where Params::motion_split looks for
  // two tracks meeting, and Params::motion_measure for a fast one beside another); none for a
  // rule without a filter.
  virtual std::vector<TrackPrediction> confirmed_predictions(TimeUs /*t*/) const { return {}; }
};

// The tracker `params` choose, its filters' process noise that of `sensor` (accel_psd_at).
std::unique_ptr<Tracker> make_tracker(const Params& params, SensorSize sensor);

class MultiTargetTracker final : public Tracker {
 public:
  explicit MultiTargetTracker(const Params& params);

  std::vector<std::int32_t> step(TimeUs packet_time, std::span<const Measurement> measurements,
                                 std::vector<TrackUpdate>& updates) override;

  int live_tracks() const;
  std::vector<TrackPrediction> confirmed_predictions(TimeUs t) const override;
  std::int64_t unassigned_clusters() const override { return unassigned_clusters_; }
  std::int32_t tracks_started() const override { return next_id_; }

 private:
  struct Track {
    std::int32_t id;
    KalmanFilter filter;
    int hits;
    bool confirmed;
    int missed = 0;  // packets in a row without a measurement
    Eigen::Vector2d last_z;  // the last measurement's position
    int last_events = 0;     // ... its event count
    Box last_box;            // ... and its bounding box
  };

  double gate(const Measurement& z) const;
  // The variance (px^2 per axis) of measurement z's position (Params::meas_noise_from_spread).
  double measurement_variance(const Measurement& z) const;
  bool sizes_match(int track_events, int measurement_events) const;
  // gate_boxes: one of the two lies in the other's bounding box.
  bool boxes_cover(const Track& track, const Measurement& z) const;
  std::optional<size_t> slot_for_new_track(const std::vector<bool>& matched) const;
  void report(const Track& track, const Measurement& z, std::vector<TrackUpdate>& updates) const;

  Params params_;
  std::vector<std::optional<Track>> slots_;
  std::int32_t next_id_ = 0;
  std::int64_t unassigned_clusters_ = 0;
};

class NearestCentreIds final : public Tracker {
 public:
  explicit NearestCentreIds(const Params& params) : params_(params) {}
  std::vector<std::int32_t> step(TimeUs packet_time, std::span<const Measurement> measurements,
                                 std::vector<TrackUpdate>& updates) override;
  std::int32_t tracks_started() const override { return next_id_; }

 private:
  Params params_;
  std::vector<Measurement> previous_;
  std::vector<std::int32_t> previous_ids_;
  std::int32_t next_id_ = 0;
};

}  // namespace evms::golden

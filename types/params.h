// Every tunable of the method, with its unit and default. The defaults were chosen on the scene
// family's tuning split (docs/sweep.md). The table in params.cpp is the one place that names,
// documents and bounds them: the CLI builds its options from it and docs/parameters.md is
// generated from it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "types/event.h"

namespace evms {

// The kernel's profile k(u) of u = |f_i - f_j|^2 / h^2 (golden/cluster/kernel.h).
enum class Kernel : std::uint8_t { kGaussian, kFlat, kEpanechnikov };
// Which points climb to a mode, and how an event finds its cluster (golden/cluster/).
enum class Seeding : std::uint8_t {
  kEvery,   // every event climbs; its own mode is its cluster (the paper's text)
  kEvents,  // the first event no climb has reached yet seeds the next climb (the authors' code)
  kGrid,    // one seed per occupied cell of a grid on (x, y), most populated first
};
enum class Labelling : std::uint8_t {
  kVotes,    // the cluster whose climbs reached the event most often (the authors' code)
  kNearest,  // the nearest mode within label_reach bandwidths, else noise
  kFirst,    // the cluster of the first climb that reached the event
};
// How x and y are normalized: x/W and y/H (the paper), or both by the larger side.
enum class XyScale : std::uint8_t { kAxes, kIsotropic };
// Where a cluster is: the centre of mass of its events, the centre of their bounding box, the
// midpoint of its ON events' and its OFF events' centres of mass (the centre of mass where either
// polarity has fewer than midpoint_min_events), or the mean of the pixels its events fall on, each
// pixel once (a pixel counts for the cluster of the packet's first clustered event on it).
enum class Measure : std::uint8_t { kCentroid, kBoxCentre, kPolarityMidpoint, kPixelCentre };
// How clusters get their IDs across packets.
enum class Association : std::uint8_t {
  kKalman,         // one-to-one, nearest first, against each track's Kalman prediction
  kNearestCentre,  // the nearest previous cluster centre within the gate (the authors' code)
  kLastMeasurement,  // one-to-one, nearest first, against each track's last measurement
};

struct Params {
  // --- background-activity filter -------------------------------------------------------
  TimeUs filter_window_us = 30000;  // neighbour support window; 0 turns the filter off
  int filter_support = 1;            // neighbours that must have fired within the window
  TimeUs filter_warm_up_us = 10000;  // keep every event of the stream's first this long; 0 = off
  double filter_noise_hz = 0.7;      // unsupported events a pixel a second that make the filter ask
                                     // one more neighbour (filter_noise_count); 0 = off
  double filter_noise_pixels = 43200;  // ... on a sensor of up to this many pixels; on a larger one the
                                       // rate scales by sqrt(this / its pixels); 0 = on every sensor
  double filter_quiet_hz = 0.25;     // unsupported events a pixel a second below which the next
                                     // interval's window is filter_quiet_window_us; 0 = off
  TimeUs filter_quiet_window_us = 100000;  // the window after a quiet interval
  TimeUs filter_look_ahead_us = 0;   // a dropped event is kept after all when neighbours fired
                                     // within this long after it, before its packet closed; 0 = off
  int packet_support = 0;            // neighbours that must have fired while the packet was open

  // --- packets --------------------------------------------------------------------------
  int packet_size = 3000;            // events (that passed the filter) per mean-shift packet
  TimeUs packet_max_span_us = 33333; // close a packet early once it spans this long; 0 = never
  double packet_span_edge_px = 0;    // lengthen that span while the edges move slowly: the time
                                     // the edges take to move this many px (golden only); 0 = off

  // --- features [x/W, y/H, p, exp(-dt/tau)], each scaled --------------------------------
  XyScale xy_scale = XyScale::kAxes;
  double scale_xy = 1.0;             // weight of the two position dimensions
  double scale_p = 0.0;              // weight of polarity; 0 switches it off
  double scale_t = 0.0;              // weight of the time decay; 0 switches it off
  double tau_us = 10000.0;           // time constant of exp(-dt/tau), dt from packet's newest event

  // --- mean shift -----------------------------------------------------------------------
  Kernel kernel = Kernel::kFlat;
  Seeding seeding = Seeding::kEvents;
  Labelling labelling = Labelling::kFirst;  // for seeded climbs (not kEvery)
  bool warm_start = true;            // the previous packet's modes seed the first climbs
  double warm_scale = 2;             // ... each with bandwidth max(h, this times its cluster's spread)
  double warm_max_bandwidth = 0.14;  // ... but at most this
  double warm_reach = 0;             // ... taking the events within max(h, this times the spread); 0 = the ball
  double label_reach = 1.0;          // labelling nearest: events this many h from every mode are noise
  double bandwidth = 0.04;           // kernel bandwidth h on the normalized feature space
  int max_iterations = 8;            // iteration cap
  double tolerance = 4e-5;           // stop when no coordinate moves more than this (h / 1000)
  double merge_radius = 0.04;        // modes closer than this are one cluster: one bandwidth, so a
                                     // climb that ends inside an earlier mode's ball joins it
  int min_cluster_size = 8;          // smaller clusters become noise
  double min_density = 2;            // seeded climbs: a mode whose ball holds fewer than this many
                                     // times the events a uniform spread would put there is noise
  bool density_after_links = true;   // ... tested on each set of linked modes after the links (noise
                                     // when none of its modes is dense, or when it holds fewer events
                                     // than a dense ball), not on each mode before them
  double link_px = 4;                // seeded climbs: clusters with events this close become one, ...
  double link_px_width = 320;        // ... on a sensor up to this wide; on a wider one W px wide,
                                     // link_px min(2, W / this) (link_px_at); 0 = link_px on every sensor
  bool join_boxes = false;           // seeded climbs: clusters whose bounding boxes overlap become one
  int max_clusters = 128;            // modes beyond this many clusters become noise
  double split_balance = 0.3;        // seeded climbs: a cluster of two or more separate parts that each
                                     // hold both polarities is split (golden/cluster/polarity_split.h); 0 = off
  double split_share = 0.05;         // ... counting the parts of at least this share of its events
  int split_min_events = 64;         // ... and of at least this many events
  double split_cell = 0.4;           // ... parts of 8-connected cells this many bandwidths a side
  bool split_partial = true;         // ... and each part that holds both polarities leaves a cluster whose
                                     // other large parts hold one, which stay one cluster; false: a cluster
                                     // splits only when every large part holds both
  bool split_concentric = true;      // ... and two of its groups stay one cluster when each one's centre
                                     // lies in the middle half of the other's bounding box (a ring's two
                                     // circles, about one centre)
  double motion_split = 0.4;         // seeded climbs: a cluster where two confirmed tracks meet is split
                                     // by its events' motion when two velocities leave at most this
                                     // share of one velocity's residual (golden/cluster/motion_split.h,
                                     // hls/cluster/motion_split.h); 0 = off
  double edge_join = 5;              // seeded climbs: a cluster of mostly ON events and one of mostly OFF
                                     // events whose centres lie within this many bandwidths of the larger
                                     // side, each the other's nearest, become one (golden/cluster/edge_join.h); 0 = off
  double edge_balance = 0.5;         // ... mostly one polarity: |ON - OFF| at least this times its events
  int edge_min_events = 16;          // ... in a cluster of at least this many events

  // --- tracker --------------------------------------------------------------------------
  Measure measure = Measure::kPixelCentre;
  int midpoint_min_events = 16;      // polarity midpoint: events each polarity needs
  bool time_by_pixels = true;        // pixel centre: timed at the mean timestamp of the events that
                                     // placed its pixels (each pixel's first of the packet), not of all
  Association association = Association::kLastMeasurement;
  double gate_px = 20.0;             // association gate around the predicted position
  double gate_spread = 0.0;          // ... widened to this many times the cluster's spread
  bool gate_boxes = true;            // a pair beyond the gate is a candidate after every pair
                                     // within it when the track's last cluster centre lies in the
                                     // cluster's box, or the cluster's centre in that cluster's box
  double size_ratio = 4.0;           // a (track, cluster) pair whose cluster has more than this
                                     // many times the track's last cluster's events, or fewer than
                                     // 1/this, is taken after every pair within it; 0 = off
  int confirm_hits = 3;              // measurements before a track is confirmed
  bool report_tentative = true;      // tentative tracks report their updates (state tentative)
  TimeUs coast_us = 200000;          // a confirmed track ends after this long without a match
  int coast_packets = 0;             // ... or after missing this many packets; 0 = no limit
  bool evict_stale = true;           // with every slot taken, a new cluster takes the stalest
                                     // unmatched track's slot
  double accel_psd = 100000.0;       // white-noise-acceleration spectral density, px^2/s^3, ...
  double accel_psd_width = 240;      // ... on a sensor this wide, scaled by (W / this)^2 on a sensor
                                     // W px wide (accel_psd_at); 0 = accel_psd on every sensor
  double meas_sigma_px = 1.0;        // centroid measurement noise (R = sigma^2 I)
  bool meas_noise_from_spread = true;   // R = sigma^2 (spread^2 + 1/6) / events I: the scatter
                                        // of the cluster's centre of mass, times sigma^2; else sigma^2 I
  double init_sigma_px = 2.0;        // initial position uncertainty (P0)
  double init_sigma_vel = 200.0;     // initial velocity uncertainty (P0), px/s
  int max_tracks = 128;              // tracks held at once

  double motion_measure = 1000;      // with the pixel centre: a cluster that holds a confirmed track at
                                     // least this fast (px/s) is measured from the pixels whose slopes
                                     // its velocity explains (golden/track/motion_measure.h); other
                                     // measures leave it off; 0 = off
  double outline_split_us = 0;       // a cluster where two confirmed tracks meet is parted by where
                                     // each track's events fell over this long
                                     // (golden/track/outline_split.h; golden only); 0 = off

  // --- labels -----------------------------------------------------------------------------
  int rescue_px = 1;                 // an event the filter dropped takes the label of the nearest
                                     // labelled event of its packet within this many px; 0 = off

  friend bool operator==(const Params&, const Params&) = default;
};

// The spellings of an enumerated parameter's values, in the enum's order.
struct Choices {
  std::span<const char* const> names;
};

// One row of the parameter table.
struct ParamInfo {
  const char* name;      // CLI spelling without the leading dashes
  const char* unit;
  const char* help;
  std::variant<double Params::*, int Params::*, TimeUs Params::*, bool Params::*, Kernel Params::*, Seeding Params::*,
               Labelling Params::*, XyScale Params::*, Association Params::*, Measure Params::*>
      member;
  double min;            // inclusive bounds checked by validate() (numbers only)
  double max;
  Choices choices = {};  // enumerated parameters: the value names
};

// The filter's noise check, in intervals of 2^kFilterNoiseIntervalLog2 us of event time (32.8 ms):
// when an interval held at least filter_noise_count(...) events that no neighbour supported, the
// next interval's events need one more supporting neighbour. The count is --filter-noise-hz a
// pixel a second over the sensor and the interval, rounded down, at least 1; 0 = off. On a sensor
// of more than filter_noise_pixels pixels the rate is filter_noise_hz sqrt(filter_noise_pixels /
// pixels): noise that passes the filter does so at a rate about the square of its own, and a
// kernel ball of the same h on (x/W, y/H) spans as many more pixels as the sensor has, so the
// noise one ball gathers in a packet stays the same at the scaled rate.
inline constexpr int kFilterNoiseIntervalLog2 = 15;
std::int64_t filter_noise_count(const Params& p, SensorSize sensor);
std::int64_t filter_quiet_count(const Params& p, SensorSize sensor);

// The process noise of the tracks' filters on `sensor`, px^2/s^3: accel_psd, scaled by the
// square of the sensor's width over accel_psd_width when that is set. A scene seen by a sensor
// with k times the pixels across moves k times as many pixels a second, so its accelerations'
// spectral density is k^2 times larger.
double accel_psd_at(const Params& p, SensorSize sensor);

// The distance in pixels within which the seeded climbs' clusters link on `sensor`: link_px, scaled
// by the sensor's width over link_px_width when that is wider, up to twice link_px. A finer
// sensor spreads a packet's events along an outline over more pixels, so the gaps a link must
// bridge grow with it (docs/sweep.md, "Links on large sensors"); the family's sensors reach
// 640 px, twice the reference width, and no wider sensor was measured.
double link_px_at(const Params& p, SensorSize sensor);

// The sensor's side, in pixels, that one x and one y feature unit span before scale_xy: its width
// and height, or its larger side for both with --xy-scale isotropic. Golden's features
// (golden/cluster/features.cpp), the core's registers (host/backend/core_config.h) and the rules
// below take it from here.
struct FeatureSides {
  double x = 0, y = 0;
};
FeatureSides feature_sides(const Params& p, SensorSize sensor);

// min_density times the events a uniform spread of one event over `sensor` puts in a ball of
// radius h on the feature plane (x/W, y/H): a packet of n events makes a mode noise whose
// support is below n times this. Golden (golden/cluster/clustering.cpp) and the fixed-point core's
// register (host/backend/core_config.h) both take it from here.
double least_support_per_event(const Params& p, SensorSize sensor);

// The polarity split's rule in integers, which golden (golden/cluster/polarity_split.h) and the
// fixed-point core (hls/cluster/polarity_split.h) share so that they find the same parts:
//   - an event at (x, y) px lies in cell ((x * cell_scale_x) >> kSplitCellFrac, (y * cell_scale_y)
//     >> kSplitCellFrac): cells of split_cell bandwidths a side on the (x, y) features, at least two
//     pixels along each axis (neighbouring pixels then lie in the same or neighbouring cells);
//   - a part of `events` events, `on` of them ON, of a cluster of `size` events is large when
//     events << kSplitFractionFrac >= share * size and events >= min_events, and holds both
//     polarities when |2 on - events| << kSplitFractionFrac < balance * events. A cluster of fewer
//     than 2 min_events events has no two large parts, so it is not looked at.
// balance = 0 turns the split off.
inline constexpr int kSplitCellFrac = 16;
inline constexpr int kSplitFractionFrac = 8;
// The mean of `count` pixel coordinates from their sum, in 1/16 px, rounded half up: the centres
// of the polarity split's parts and the edge join's clusters (hls/math/round.h has the same).
constexpr std::int64_t mean_sixteenths(std::int64_t sum, int count) { return (32 * sum + count) / (2 * std::int64_t{count}); }
struct SplitRule {
  std::uint32_t cell_scale_x = 0, cell_scale_y = 0;  // 2^kSplitCellFrac / cell side in px, rounded
  std::uint32_t balance = 0, share = 0;              // split_balance, split_share: kSplitFractionFrac fraction bits
  std::uint32_t min_events = 0;                      // the larger of split_min_events and min_cluster_size
  bool partial = false;                              // split_partial
  bool concentric = false;                           // split_concentric
};
SplitRule split_rule(const Params& p, SensorSize sensor);

// The split by motion's gain in integers, which golden (golden/cluster/motion_split.h) and the
// fixed-point core (hls/cluster/motion_split.h) share so that they split at the same share: a
// cluster splits when its two velocities' summed residual << kMotionGainFrac <= gain times one
// velocity's. The share is motion_split rounded to kMotionGainFrac fraction bits, at least 1 when
// on; 0 = off.
inline constexpr int kMotionGainFrac = 8;
std::uint32_t motion_split_gain(const Params& p);

// The edge join's rule in integers (golden/cluster/edge_join.h, hls/cluster/edge_join.h): two
// centres (1/16 px) lie within reach when dx^2 + dy^2 <= radius2.
inline constexpr int kEdgeSizeRatio = 4;  // neither cluster of a pair holds more than this many times the other's events
struct EdgeRule {
  std::uint64_t radius2 = 0;     // (16 edge_join h max(W, H) / scale_xy)^2, rounded; 0 = off
  std::uint32_t balance = 0;     // edge_balance, kSplitFractionFrac fraction bits (at least 1)
  std::uint32_t min_events = 0;  // the larger of edge_min_events and min_cluster_size
};
EdgeRule edge_rule(const Params& p, SensorSize sensor);

std::span<const ParamInfo> param_table();
const ParamInfo* find_param(const std::string& name);

// Reads a parameter as a double (an enumerated one as its index; for reports and comparisons).
double param_value(const Params& p, const ParamInfo& info);
// Reads a parameter as text: a number, "true"/"false", or a value name.
std::string param_text(const Params& p, const ParamInfo& info);
// Sets a parameter from text; returns an error message, or an empty string on success.
std::string set_param(Params& p, const ParamInfo& info, const std::string& text);
// Checks every parameter against its bounds; returns an error message or an empty string.
std::string validate(const Params& p);

// Named settings of the whole method (types/presets.cpp): "evms" (the defaults), "paper"
// (the authors' published code), "gaussian" (the paper's text: the method the RTL implements).
std::span<const char* const> preset_names();
// Throws std::invalid_argument naming the presets for an unknown name. `sensor` picks the
// packet size where a preset ties it to the sensor (the authors' 1500 or 1800 events).
Params preset(const std::string& name, SensorSize sensor = {240, 180});

// A preset and the parameters set on top of it, as a command line gives them: the settings
// override the preset whatever their order. Resolved once the sensor is known.
struct Method {
  std::string preset = "evms";
  std::vector<std::pair<std::string, std::string>> settings;  // parameter name, value text

  // Throws std::invalid_argument with the offending option's message.
  Params resolve(SensorSize sensor) const;
  // "--preset paper --bandwidth 0.1", for reports.
  std::string describe() const;
  // Whether the command line set parameter `name` (a preset's value does not count).
  bool sets(const std::string& name) const;
};

}  // namespace evms

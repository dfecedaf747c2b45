#include "golden/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "golden/cluster/clustering.h"
#include "golden/cluster/features.h"

namespace evms::golden {
namespace {

// The wall clock between laps, for the stage split that `evms run` and bench_backends report
// (three clock reads a packet).
class StageClock {
 public:
  std::int64_t lap() {
    const auto now = std::chrono::steady_clock::now();
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_).count();
    last_ = now;
    return ns;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

Pipeline::Pipeline(const Params& params, SensorSize sensor)
    : params_(params),
      sensor_(sensor),
      filter_(sensor, params.filter_window_us, params.filter_support, params.filter_warm_up_us, filter_noise_count(params, sensor),
              filter_quiet_count(params, sensor), params.filter_quiet_window_us),
      clusterer_(params, sensor),
      tracker_(make_tracker(params, sensor)) {
  packet_.reserve(static_cast<size_t>(params.packet_size));
  if (params.measure == Measure::kPixelCentre) {
    pixel_taken_.assign((static_cast<size_t>(sensor.width) * static_cast<size_t>(sensor.height) + 63) / 64, 0);
    if (params.motion_measure > 0) motion_measure_.emplace(params, sensor);
  }
  if (params.outline_split_us > 0) outline_split_.emplace(params, sensor);
}

void Pipeline::push(const Event& e, OutputSink& out) {
  ++stats_.events_in;
  if (params_.packet_span_edge_px > 0) record_edge_slope(e);
  if (!filter_.accept(e)) {
    pending_.push_back({e, -1, filter_.support_asked()});
    if (packet_.empty()) flush_settled_noise(e.t, out);  // no packet to wait for
    return;
  }
  ++stats_.events_kept;
  if (!packet_.empty() && params_.packet_max_span_us > 0 &&
      e.t - packet_.front().t > std::max(params_.packet_max_span_us, stretched_span_us_)) {
    close_packet(out);
  }
  pending_.push_back({e, static_cast<int>(packet_.size()), 0});
  packet_.push_back(e);
  if (static_cast<int>(packet_.size()) >= params_.packet_size) close_packet(out);
}

void Pipeline::finish(OutputSink& out) { close_packet(out); }

void Pipeline::record_edge_slope(const Event& e) {
  // A neighbour's time counts when it fired within this long before e; an edge slower than a
  // pixel in this long gives no slope.
  constexpr TimeUs kSlopeWindowUs = 50000;
  auto recent = [&](int x, int y) {
    const TimeUs t = filter_.latest(x, y);
    return e.t - t <= kSlopeWindowUs ? t : TimeUs{-1};
  };
  // The slope along one axis: the central difference where both neighbours fired, else the time
  // since the one that did (the pixel ahead of a moving edge has not fired yet).
  auto axis_slope = [&](TimeUs before, TimeUs after, double& slope) {
    if (before >= 0 && after >= 0) slope = static_cast<double>(after - before) / 2.0;
    else if (before >= 0 || after >= 0) slope = static_cast<double>(e.t - std::max(before, after));
    else return false;
    return true;
  };
  // Events the filter drops open no packet, so a long stretch of them would grow the slopes
  // without bound; the first this many since the last packet are plenty for a quantile.
  constexpr size_t kMostSlopes = size_t{1} << 16;
  if (edge_slopes_.size() >= kMostSlopes) return;
  double gx = 0, gy = 0;
  if (axis_slope(recent(e.x - 1, e.y), recent(e.x + 1, e.y), gx) && axis_slope(recent(e.x, e.y - 1), recent(e.x, e.y + 1), gy)) {
    const double slope = std::hypot(gx, gy);
    if (slope > 0) edge_slopes_.push_back(slope);
  }
}

void Pipeline::stretch_span() {
  // Fewer slopes than this say little about the scene's edges: the packet keeps its usual span.
  constexpr size_t kLeastSlopes = 64;
  constexpr double kSpeedQuantile = 0.9, kMostStretch = 4.0;
  stretched_span_us_ = 0;
  if (edge_slopes_.size() >= kLeastSlopes) {
    // The edge at the 90th percentile of the speeds is the one at the 10th of the slopes.
    const size_t n = edge_slopes_.size();
    const size_t fast = n - 1 - std::min(n - 1, static_cast<size_t>(kSpeedQuantile * static_cast<double>(n)));
    std::nth_element(edge_slopes_.begin(), edge_slopes_.begin() + static_cast<std::ptrdiff_t>(fast), edge_slopes_.end());
    const double base = static_cast<double>(params_.packet_max_span_us);
    const double px = params_.packet_span_edge_px * sensor_.width / 240.0;
    stretched_span_us_ = static_cast<TimeUs>(std::clamp(px * edge_slopes_[fast], base, kMostStretch * base));
  }
  edge_slopes_.clear();
}

void Pipeline::flush_settled_noise(TimeUs now, OutputSink& out) {
  // Without the look-ahead a dropped event is settled at once; with it, once its neighbours' time is up.
  size_t settled = pending_.size();
  if (params_.filter_look_ahead_us > 0) {
    settled = 0;
    while (settled < pending_.size() && pending_[settled].event.t + params_.filter_look_ahead_us < now) ++settled;
  }
  if (settled > 0) hand_out_as_noise(settled, out);
}

void Pipeline::hand_out_as_noise(size_t count, OutputSink& out) {
  labelled_.clear();
  for (size_t k = 0; k < count; ++k) labelled_.push_back({pending_[k].event, kNoiseLabel});
  out.on_events(labelled_);
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(count));
}

// A sparse object fires too few events for the filter's window: its neighbours' events came
// longer ago than the window, or come after it. Those events have no history to be judged by,
// but the packet they waited in holds their object's labelled events beside them (docs/sweep.md,
// "An event the filter dropped, labelled by its neighbours").
void Pipeline::rescue_dropped() {
  const size_t width = static_cast<size_t>(sensor_.width);
  if (label_at_pixel_.empty()) label_at_pixel_.assign(width * static_cast<size_t>(sensor_.height), kNoiseLabel);
  const auto pixel_of = [&](const Event& e) { return static_cast<size_t>(e.y) * width + e.x; };
  for (size_t k = 0; k < pending_.size(); ++k) {
    if (pending_[k].packet_index >= 0 && labelled_[k].label >= 0) label_at_pixel_[pixel_of(labelled_[k].event)] = labelled_[k].label;
  }
  const int reach = params_.rescue_px;
  for (size_t k = 0; k < pending_.size(); ++k) {
    if (pending_[k].packet_index >= 0) continue;
    const Event& e = pending_[k].event;
    int nearest = std::numeric_limits<int>::max();
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const int x = e.x + dx, y = e.y + dy;
        if (x < 0 || y < 0 || x >= sensor_.width || y >= sensor_.height || dx * dx + dy * dy >= nearest) continue;
        const std::int32_t label = label_at_pixel_[static_cast<size_t>(y) * width + static_cast<size_t>(x)];
        if (label >= 0) nearest = dx * dx + dy * dy, labelled_[k].label = label;
      }
    }
  }
  for (size_t k = 0; k < pending_.size(); ++k) {
    if (pending_[k].packet_index >= 0) label_at_pixel_[pixel_of(pending_[k].event)] = kNoiseLabel;
  }
}

void Pipeline::look_ahead() {
  packet_.clear();
  for (Pending& p : pending_) {
    if (p.packet_index < 0) {
      if (filter_.neighbours_fired_after(p.event.x, p.event.y, p.event.t, p.event.t + params_.filter_look_ahead_us) < p.support_asked) continue;
      ++stats_.events_kept;
    }
    p.packet_index = static_cast<int>(packet_.size());
    packet_.push_back(p.event);
  }
}

void Pipeline::close_packet(OutputSink& out) {
  if (params_.filter_look_ahead_us > 0) look_ahead();
  label_of_packet_event_.assign(packet_.size(), kNoiseLabel);
  std::vector<std::int32_t>& label_of_packet_event = label_of_packet_event_;
  if (!packet_.empty()) {
    StageClock clock;
    // Events whose neighbours stayed quiet while the packet was open are noise.
    std::span<const Event> supported = packet_;
    index_of_.clear();  // in packet_, per supported event, when some are left out
    if (params_.packet_support > 0) {
      supported_.clear();
      for (size_t i = 0; i < packet_.size(); ++i) {
        if (filter_.neighbours_fired_since(packet_[i].x, packet_[i].y, packet_.front().t) >= params_.packet_support) {
          supported_.push_back(packet_[i]);
          index_of_.push_back(static_cast<int>(i));
        }
      }
      supported = supported_;
    }
    const auto packet_index = [&](size_t i) { return index_of_.empty() ? i : static_cast<size_t>(index_of_[i]); };
    const FeatureMatrix features = packet_features(supported, sensor_, params_);
    // The tracks as they stand before this packet, at its middle event: where the splits and
    // measurements by motion look for them.
    const std::vector<TrackPrediction> tracks = (params_.motion_split > 0 || motion_measure_ || outline_split_) && !supported.empty()
                                                    ? tracker_->confirmed_predictions(supported[supported.size() / 2].t)
                                                    : std::vector<TrackPrediction>{};
    std::vector<Eigen::Vector2d> meeting_points;
    for (const TrackPrediction& track : tracks) {
      if (track.matched) meeting_points.push_back(track.position);
    }
    PacketClusters clusters = clusterer_.cluster(supported, features, modes_, spreads_, meeting_points);
    if (outline_split_) outline_split_->split(supported, features, tracks, clusters);
    modes_ = clusters.modes;
    spreads_ = clusters.spreads;
    stats_.cluster_ns += clock.lap();

    // A cluster's measurement: the centre of mass of its events (or the midpoint of its two
    // polarities' centres of mass), timed at their mean timestamp, or the mean of its pixels, timed
    // at the mean timestamp of the events that placed them (time_by_pixels: each pixel's first of
    // the packet, as an edge that fires a burst on a pixel was at the pixel when the burst began,
    // and a busy pixel's later events would time the measurement after its position); with their
    // count, spread (about the centre of mass) and bounding box.
    std::vector<Measurement> measurements(static_cast<size_t>(clusters.count));
    std::vector<double> sum_t(measurements.size(), 0.0), sum_r2(measurements.size(), 0.0);
    std::vector<double> on_x(measurements.size(), 0.0), on_y(measurements.size(), 0.0);
    std::vector<int> on_events(measurements.size(), 0);
    std::vector<double> pixel_x(measurements.size(), 0.0), pixel_y(measurements.size(), 0.0);
    std::vector<double> pixel_t(measurements.size(), 0.0);
    std::vector<int> pixels(measurements.size(), 0);
    const TimeUs t0 = packet_.front().t;
    const auto pixel_of = [&](const Event& e) { return static_cast<size_t>(e.y) * static_cast<size_t>(sensor_.width) + e.x; };
    for (size_t i = 0; i < supported.size(); ++i) {
      const int c = clusters.cluster_of[i];
      if (c < 0) continue;
      auto& m = measurements[static_cast<size_t>(c)];
      const Event& e = supported[i];
      if (m.events == 0) m.x_min = m.x_max = e.x, m.y_min = m.y_max = e.y;
      m.x_min = std::min<int>(m.x_min, e.x), m.x_max = std::max<int>(m.x_max, e.x);
      m.y_min = std::min<int>(m.y_min, e.y), m.y_max = std::max<int>(m.y_max, e.y);
      m.x += e.x;
      m.y += e.y;
      if (e.p) on_x[static_cast<size_t>(c)] += e.x, on_y[static_cast<size_t>(c)] += e.y, ++on_events[static_cast<size_t>(c)];
      sum_r2[static_cast<size_t>(c)] += static_cast<double>(e.x) * e.x + static_cast<double>(e.y) * e.y;
      sum_t[static_cast<size_t>(c)] += static_cast<double>(e.t - t0);
      ++m.events;
      if (!pixel_taken_.empty()) {
        const size_t pixel = pixel_of(e);
        const std::uint64_t bit = std::uint64_t{1} << (pixel % 64);
        if (!(pixel_taken_[pixel / 64] & bit)) {
          pixel_taken_[pixel / 64] |= bit;
          pixel_x[static_cast<size_t>(c)] += e.x, pixel_y[static_cast<size_t>(c)] += e.y, ++pixels[static_cast<size_t>(c)];
          pixel_t[static_cast<size_t>(c)] += static_cast<double>(e.t - t0);
        }
      }
    }
    if (!pixel_taken_.empty()) {
      for (size_t i = 0; i < supported.size(); ++i) {
        pixel_taken_[pixel_of(supported[i]) / 64] = 0;
      }
    }
    for (size_t c = 0; c < measurements.size(); ++c) {
      Measurement& m = measurements[c];
      const int on = on_events[c], off = m.events - on;
      const bool midpoint = params_.measure == Measure::kPolarityMidpoint && on >= params_.midpoint_min_events &&
                            off >= params_.midpoint_min_events;
      const double mid_x = midpoint ? 0.5 * (on_x[c] / on + (m.x - on_x[c]) / off) : 0.0;
      const double mid_y = midpoint ? 0.5 * (on_y[c] / on + (m.y - on_y[c]) / off) : 0.0;
      m.x /= m.events;
      m.y /= m.events;
      m.spread = std::sqrt(std::max(0.0, sum_r2[c] / m.events - m.x * m.x - m.y * m.y));
      if (params_.measure == Measure::kBoxCentre) m.x = (m.x_min + m.x_max) / 2.0, m.y = (m.y_min + m.y_max) / 2.0;
      if (midpoint) m.x = mid_x, m.y = mid_y;
      // A cluster whose every pixel an earlier cluster's event took (only where clusters share
      // pixels, as without links) keeps its centre of mass.
      const bool by_pixels = params_.measure == Measure::kPixelCentre && pixels[c] > 0;
      if (by_pixels) m.x = pixel_x[c] / pixels[c], m.y = pixel_y[c] / pixels[c];
      m.t = t0 + static_cast<TimeUs>((by_pixels && params_.time_by_pixels ? pixel_t[c] / pixels[c] : sum_t[c] / m.events) + 0.5);
    }

    if (motion_measure_) motion_measure_->measure(supported, clusters.cluster_of, tracks, measurements);

    updates_.clear();
    const std::vector<std::int32_t> ids = tracker_->step(packet_.back().t, measurements, updates_);
    if (params_.packet_span_edge_px > 0) stretch_span();
    for (size_t i = 0; i < supported.size(); ++i) {
      const int c = clusters.cluster_of[i];
      if (c >= 0) label_of_packet_event[packet_index(i)] = ids[static_cast<size_t>(c)];
    }
    if (outline_split_) {
      supported_labels_.resize(supported.size());
      for (size_t i = 0; i < supported.size(); ++i) supported_labels_[i] = label_of_packet_event[packet_index(i)];
      outline_split_->remember(supported, supported_labels_);
    }
    stats_.track_ns += clock.lap();

    ++stats_.packets;
    stats_.clusters += clusters.count;
    stats_.iterations += clusters.iterations;
    stats_.kernel_evaluations += clusters.kernel_evaluations;
    labelled_.resize(pending_.size());
    for (size_t k = 0; k < pending_.size(); ++k) {
      const Pending& p = pending_[k];
      labelled_[k].event = p.event;
      labelled_[k].label = p.packet_index < 0 ? kNoiseLabel : label_of_packet_event[static_cast<size_t>(p.packet_index)];
    }
    if (params_.rescue_px > 0) rescue_dropped();
    out.on_events(labelled_);
    for (const TrackUpdate& u : updates_) out.on_track(u);
    out.on_packet({packet_.front().t, packet_.back().t, static_cast<int>(packet_.size()),
                   clusters.count, clusters.iterations});
  } else {
    hand_out_as_noise(pending_.size(), out);
  }
  pending_.clear();
  packet_.clear();
}

}  // namespace evms::golden

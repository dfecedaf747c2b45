#include "golden/pipeline.h"

#include "golden/cluster/features.h"
#include "golden/cluster/mean_shift.h"

namespace evms::golden {

Pipeline::Pipeline(const Params& params, SensorSize sensor)
    : params_(params),
      sensor_(sensor),
      filter_(sensor, params.filter_window_us),
      tracker_(params) {
  packet_.reserve(static_cast<size_t>(params.packet_size));
}

void Pipeline::push(const Event& e, OutputSink& out) {
  ++stats_.events_in;
  if (!filter_.accept(e)) {
    pending_.push_back({e, -1});
    if (packet_.empty()) close_packet(out);  // nothing to wait for: flush at once
    return;
  }
  ++stats_.events_kept;
  if (!packet_.empty() && params_.packet_max_span_us > 0 &&
      e.t - packet_.front().t > params_.packet_max_span_us) {
    close_packet(out);
  }
  pending_.push_back({e, static_cast<int>(packet_.size())});
  packet_.push_back(e);
  if (static_cast<int>(packet_.size()) >= params_.packet_size) close_packet(out);
}

void Pipeline::finish(OutputSink& out) { close_packet(out); }

void Pipeline::close_packet(OutputSink& out) {
  std::vector<std::int32_t> label_of_packet_event(packet_.size(), kNoiseLabel);
  if (!packet_.empty()) {
    const FeatureMatrix features = packet_features(packet_, sensor_, params_);
    const MeanShiftResult shifted = hybrid_mean_shift(features, params_);
    const ModeClusters clusters = merge_modes(shifted.modes, params_);

    // Centre of mass and mean time of each cluster's events are its measurement.
    std::vector<Measurement> measurements(static_cast<size_t>(clusters.count));
    std::vector<double> sum_t(measurements.size(), 0.0);
    std::vector<int> members(measurements.size(), 0);
    const TimeUs t0 = packet_.front().t;
    for (size_t i = 0; i < packet_.size(); ++i) {
      const int c = clusters.cluster_of[i];
      if (c < 0) continue;
      auto& m = measurements[static_cast<size_t>(c)];
      m.x += packet_[i].x;
      m.y += packet_[i].y;
      sum_t[static_cast<size_t>(c)] += static_cast<double>(packet_[i].t - t0);
      ++members[static_cast<size_t>(c)];
    }
    for (size_t c = 0; c < measurements.size(); ++c) {
      measurements[c].x /= members[c];
      measurements[c].y /= members[c];
      measurements[c].t = t0 + static_cast<TimeUs>(sum_t[c] / members[c] + 0.5);
    }

    updates_.clear();
    const std::vector<std::int32_t> ids = tracker_.step(packet_.back().t, measurements, updates_);
    for (size_t i = 0; i < packet_.size(); ++i) {
      const int c = clusters.cluster_of[i];
      if (c >= 0) label_of_packet_event[i] = ids[static_cast<size_t>(c)];
    }

    ++stats_.packets;
    stats_.clusters += clusters.count;
    stats_.iterations += shifted.iterations;
    for (const Pending& p : pending_) {
      out.on_event({p.event, p.packet_index < 0 ? kNoiseLabel
                                                : label_of_packet_event[static_cast<size_t>(p.packet_index)]});
    }
    for (const TrackUpdate& u : updates_) out.on_track(u);
    out.on_packet({packet_.front().t, packet_.back().t, static_cast<int>(packet_.size()),
                   clusters.count, shifted.iterations});
  } else {
    for (const Pending& p : pending_) out.on_event({p.event, kNoiseLabel});
  }
  pending_.clear();
  packet_.clear();
}

}  // namespace evms::golden

// The whole method in floating point: filter -> packets -> mean shift -> clusters -> tracking
// -> one label per event. This is the reference the fixed-point core is measured against.
//
// Events that pass the background-activity filter fill a packet of packet_size events. A
// full packet (or one that would span more than packet_max_span_us, or the last one at the
// end of the stream) is clustered and its clusters are tracked; then every event that came
// in since the previous packet closed, filtered or not, leaves in input order with its
// label.
//
// With packet_span_edge_px the span limit stretches while the edges move slowly: each event's
// normal speed is the inverse of the slope of the filter's time map at it (its four neighbours'
// latest times), and the next packet may span as long as an edge at the 90th percentile of the
// last packet's speeds takes to move packet_span_edge_px (scaled by the sensor's width over 240),
// up to 4 times packet_max_span_us. A slow edge fires its pixels far apart in time, and a packet
// of the usual span holds too few of them to keep a large outline in one cluster
// (docs/sweep.md, "Away from the simulator's settings").
//
// With outline_split_us, a cluster where two tracks meet is parted by where each track's own
// events fell before it is measured (golden/track/outline_split.h), and every packet's labelled
// events are remembered for the next.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "golden/cluster/clustering.h"
#include "types/event.h"
#include "golden/filter/background_activity_filter.h"
#include "types/output.h"
#include "types/params.h"
#include "golden/track/motion_measure.h"
#include "golden/track/outline_split.h"
#include "golden/track/tracker.h"

namespace evms::golden {

struct PipelineStats {
  std::int64_t events_in = 0;
  std::int64_t events_kept = 0;     // passed the filter
  std::int64_t packets = 0;
  std::int64_t clusters = 0;        // summed over packets
  std::int64_t iterations = 0;      // mean-shift sweeps or climb steps, summed over packets
  std::int64_t kernel_evaluations = 0;  // point-to-point distances the mean shift took
  std::int64_t cluster_ns = 0;          // wall clock spent clustering packets (features, mean shift, labels)
  std::int64_t track_ns = 0;            // ... and measuring clusters and tracking them
};

class Pipeline {
 public:
  Pipeline(const Params& params, SensorSize sensor);

  void push(const Event& e, OutputSink& out);
  // Clusters the last, partial packet and flushes every pending event.
  void finish(OutputSink& out);

  const PipelineStats& stats() const { return stats_; }
  const Tracker& tracker() const { return *tracker_; }

 private:
  void close_packet(OutputSink& out);
  // --packet-span-edge-px: records the slope of the filter's time map at e, before e is recorded.
  void record_edge_slope(const Event& e);
  // ... and at a packet's close, the span the next packet may reach.
  void stretch_span();
  // With --filter-look-ahead-us: puts back into the packet, in input order, the pending events
  // the filter dropped whose neighbours have fired since.
  void look_ahead();
  // Hands out, as noise, the pending events (all dropped, no packet being open) whose verdict can
  // no longer change at time `now`.
  void flush_settled_noise(TimeUs now, OutputSink& out);
  // Hands out the first `count` pending events as noise.
  void hand_out_as_noise(size_t count, OutputSink& out);
  // With --rescue-px: gives each pending event the filter dropped the label of the nearest of
  // the packet's labelled events within rescue_px (labelled_ holds the pending events' labels).
  void rescue_dropped();

  Params params_;
  SensorSize sensor_;
  BackgroundActivityFilter filter_;
  PacketClusterer clusterer_;
  std::unique_ptr<Tracker> tracker_;
  std::vector<Eigen::Vector4d> modes_;   // the previous packet's, for warm starts
  std::vector<double> spreads_;          // ... and their clusters' spreads
  std::vector<Event> packet_;
  // --packet-span-edge-px: the slopes (us/px) of the time map at the events since the last packet
  // closed, and the span the next packet may reach (0: packet_max_span_us).
  std::vector<double> edge_slopes_;
  TimeUs stretched_span_us_ = 0;
  struct Pending {
    Event event;
    int packet_index;  // index into packet_, or -1 when filtered
    int support_asked; // the neighbours the filter asked of it
  };
  std::vector<Pending> pending_;
  std::vector<TrackUpdate> updates_;
  std::vector<LabelledEvent> labelled_;  // the pending events with their labels, handed out at once
  // Working memory of close_packet, kept from packet to packet.
  std::vector<std::int32_t> label_of_packet_event_;
  std::vector<Event> supported_;
  std::vector<int> index_of_;
  std::vector<std::int32_t> supported_labels_;  // --outline-split-us: the labels of `supported`, in its order
  // --measure pixel-centre: one bit a pixel, set where the packet's clustered events fell and
  // cleared again after the packet, so the map stays small enough for the cache (115 kB at 1280x720).
  std::vector<std::uint64_t> pixel_taken_;
  std::optional<MotionMeasure> motion_measure_;  // with params.motion_measure and the pixel centre
  std::optional<OutlineSplit> outline_split_;    // with params.outline_split_us
  // --rescue-px: the label of the packet's last labelled event on each pixel, or kNoiseLabel;
  // cleared again after the packet.
  std::vector<std::int32_t> label_at_pixel_;
  PipelineStats stats_;
};

}  // namespace evms::golden

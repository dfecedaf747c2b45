// The output side of the backend seam: every backend (golden, fixed, rtl, board) reports
// labelled events, track updates and per-packet summaries through this interface.
#pragma once

#include <span>

#include "types/event.h"

namespace evms {

struct PacketSummary {
  TimeUs t_first = 0;      // oldest and newest event of the packet
  TimeUs t_last = 0;
  int events = 0;          // events in the packet (all passed the filter)
  int clusters = 0;        // clusters that survived the minimum size
  int iterations = 0;      // mean-shift sweeps
};

class OutputSink {
 public:
  virtual ~OutputSink() = default;
  // Exactly once per input event, in input order.
  virtual void on_event(const LabelledEvent& e) = 0;
  // Several at once, in input order: the same as on_event for each.
  virtual void on_events(std::span<const LabelledEvent> events) {
    for (const LabelledEvent& e : events) on_event(e);
  }
  virtual void on_track(const TrackUpdate& u) = 0;
  virtual void on_packet(const PacketSummary&) {}
};

}  // namespace evms

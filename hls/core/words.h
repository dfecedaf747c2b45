// The words on the core's streams: events in; labelled events, track updates and packet
// summaries out. Times are microseconds modulo 2^32 (the host keeps the epoch).
#pragma once

#include <cstdint>

namespace evms::hls {

// The labels that are not a track's ID: noise, and what a board whose core is cut
// (EVMS_BOARD_BUILDS, hls/core/configs.h) gives an event that passed its filter, whose cluster
// the host finds (Core::process_decided, process_climbed). host/tools/rtl_gen writes both for the RTL
// (rtl/generated/evms_core_labels.svh).
inline constexpr std::int32_t kLabelNoise = -1;
inline constexpr std::int32_t kLabelPassedFilter = -3;

// The fields of the event and label streams, described once, as X(name, type, bits, reset):
// the C++ type and the width of the RTL port. The words below, the RTL's stream ports and their
// connections (in_<name>, lab_<name>; host/tools/rtl_gen writes rtl/generated/evms_stream_*.svh)
// and the testbenches' port assignments (sim/rtl_core.h, sim/systemc/sc_core_tb.cpp) are made
// from them. An event word with flush set is not an event: it closes the open packet and
// flushes everything held.
#define EVMS_EVENT_WORD_FIELDS(X) \
  X(t, std::uint32_t, 32, 0) X(x, std::uint16_t, 16, 0) X(y, std::uint16_t, 16, 0) X(p, std::uint8_t, 1, 0) X(flush, bool, 1, false)
#define EVMS_LABEL_WORD_FIELDS(X)                                                                                      \
  X(t, std::uint32_t, 32, 0) X(x, std::uint16_t, 16, 0) X(y, std::uint16_t, 16, 0) X(p, std::uint8_t, 1, 0)        \
  X(label, std::int32_t, 32, kLabelNoise)

// The fields of the track-update and packet-summary streams, in the order of the RTL's trk_
// and pkt_ ports (rtl/core/evms_core.sv), as X(name, type, bits, reset). Track updates: the
// measurement time; the ID; the filtered position and velocity (Shape::kPosFrac fraction bits,
// px and px per tick); the measurement, the cluster's centre (kPosFrac, px); confirmed, else
// tentative (reported with Config::report_tentative); the cluster's event count and bounding
// box (px); the position variances (kCovFrac fraction bits, px^2). Packet summaries: the first
// and last event's times, the kept events, the clusters, and the Gaussian sweeps or seeded climb
// steps (saturating).
#define EVMS_TRACK_WORD_FIELDS(X)                                                                                        \
  X(t, std::uint32_t, 32, 0) X(id, std::int32_t, 32, 0) X(x, std::int32_t, 32, 0) X(y, std::int32_t, 32, 0)             \
  X(vx, std::int32_t, 32, 0) X(vy, std::int32_t, 32, 0) X(zx, std::int32_t, 32, 0) X(zy, std::int32_t, 32, 0)           \
  X(confirmed, bool, 1, true) X(events, std::uint32_t, 16, 0) X(x_min, std::uint16_t, 16, 0)                             \
  X(y_min, std::uint16_t, 16, 0) X(x_max, std::uint16_t, 16, 0) X(y_max, std::uint16_t, 16, 0)                           \
  X(var_x, std::int64_t, 64, 0) X(var_y, std::int64_t, 64, 0)
#define EVMS_PACKET_WORD_FIELDS(X)                                                                                       \
  X(t_first, std::uint32_t, 32, 0) X(t_last, std::uint32_t, 32, 0) X(events, std::uint16_t, 16, 0)                      \
  X(clusters, std::uint8_t, 8, 0) X(iterations, std::uint16_t, 16, 0)

#define EVMS_WORD_MEMBER(name, type, bits, reset) type name = reset;
struct EventWord {
  EVMS_EVENT_WORD_FIELDS(EVMS_WORD_MEMBER)
};

struct LabelWord {
  EVMS_LABEL_WORD_FIELDS(EVMS_WORD_MEMBER)
};

struct TrackWord {
  EVMS_TRACK_WORD_FIELDS(EVMS_WORD_MEMBER)
};

struct PacketWord {
  EVMS_PACKET_WORD_FIELDS(EVMS_WORD_MEMBER)
};
#undef EVMS_WORD_MEMBER

}  // namespace evms::hls

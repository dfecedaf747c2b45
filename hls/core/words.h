// The words on the core's streams: events in; labelled events, track updates and packet
// summaries out. Times are microseconds modulo 2^32 (the host keeps the epoch).
#pragma once

#include <cstdint>

namespace evms::hls {

// The labels that are not a track's ID: noise, and what a board whose core stops at the filter
// (EVMS_BOARD_BUILDS, hls/core/configs.h) gives an event that passed it, whose cluster the host
// finds (Core::process_decided). host/tools/rtl_gen writes both for the RTL
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

#define EVMS_WORD_MEMBER(name, type, bits, reset) type name = reset;
struct EventWord {
  EVMS_EVENT_WORD_FIELDS(EVMS_WORD_MEMBER)
};

struct LabelWord {
  EVMS_LABEL_WORD_FIELDS(EVMS_WORD_MEMBER)
};
#undef EVMS_WORD_MEMBER

struct TrackWord {
  std::uint32_t t = 0;      // measurement time
  std::int32_t id = 0;
  std::int32_t x = 0, y = 0;    // filtered position, Shape::kPosFrac fraction bits, px
  std::int32_t vx = 0, vy = 0;  // filtered velocity, kPosFrac fraction bits, px per tick
  std::int32_t zx = 0, zy = 0;  // the measurement (cluster centre of mass), kPosFrac, px
  bool confirmed = true;        // else tentative (reported with Config::report_tentative)
  std::uint32_t events = 0;     // the cluster's events
  std::uint16_t x_min = 0, y_min = 0, x_max = 0, y_max = 0;  // its bounding box, px
  std::int64_t var_x = 0, var_y = 0;  // the position variances, kCovFrac fraction bits, px^2
};

struct PacketWord {
  std::uint32_t t_first = 0, t_last = 0;
  std::uint16_t events = 0;
  std::uint8_t clusters = 0;
  std::uint16_t iterations = 0;  // Gaussian sweeps, or seeded climb steps (saturating)
};

}  // namespace evms::hls

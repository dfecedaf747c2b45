// The serial link between the host and the board top (docs/link.md), in C++: frame encoding
// for the host's side and a decoder for the board's frames. The RTL implements the same
// protocol in rtl/board/evms_link_rx.sv and evms_link_tx.sv; both sides take the frame types
// and lengths from host/link/link_frames.h.
//
//   frame = 0xA5 0x5A TYPE LEN PAYLOAD[LEN] CRC16_LO CRC16_HI
//   CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF) over TYPE, LEN and PAYLOAD
//   host -> board: 0x01 events (up to 32, numbered from the first), 0x02 flush (seq u16: the
//                  next event's), 0x03 reset (mode u8: labels or tracks)
//   board -> host: 0x81 labelled event (with the label's seq u16), 0x82 track update,
//                  0x83 packet summary, 0x84 status, 0x85 resend (seq u16 the board expects),
//                  0x86 progress (the board's counts, when the line is free), 0x87 verdicts (up
//                  to 32 events with their verdicts, from a board whose core is cut), 0x88-0x8A
//                  a climbs frame's words (a head, a mode, up to 32 events' modes: a core cut
//                  after its climbs)
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "hls/cluster/climbs_words.h"
#include "hls/core/words.h"
#include "host/link/link_frames.h"

namespace evms::link {

enum FrameType : std::uint8_t {
#define EVMS_LINK_FRAME_TYPE(name, type, length, what) k##name = type,
  EVMS_LINK_FRAMES(EVMS_LINK_FRAME_TYPE)
#undef EVMS_LINK_FRAME_TYPE
};

// What the board sends back for a run, chosen by the reset frame that starts it.
enum class LinkMode : std::uint8_t {
  kLabels = 0,  // a label frame for every event, and every track update and packet summary
  kTracks = 1,  // labels stay on the board; whole packets' track updates and summaries when the
                // line is free, and progress frames in place of the labels
};

// Events and labels are numbered modulo 2^16 from the reset on; the host unwraps the numbers
// against what it has outstanding (never more than the link's window, far below 2^15).
using Sequence = std::uint16_t;

std::uint16_t crc16(std::span<const std::uint8_t> bytes);

// An entry of an events frame or a verdict frame, and its u32 (host/link/link_frames.h).
struct BatchEntry {
  std::uint8_t x = 0, y = 0, p = 0;
  bool passed = false;   // verdicts: passed the filter
  bool present = false;
  std::uint32_t gap = 0;  // microseconds since the previous entry, below 2^kBatchGapBits
};
std::uint32_t pack_entry(const BatchEntry& e);
BatchEntry unpack_entry(std::uint32_t word);

// Events numbered from `first` on, in events frames of up to kBatchEntries (fewer when an event
// comes more than kBatchGapMax us after the previous one).
void append_events(std::vector<std::uint8_t>& out, std::span<const hls::EventWord> events, Sequence first);
void append_flush(std::vector<std::uint8_t>& out, Sequence next_event);
void append_reset(std::vector<std::uint8_t>& out, LinkMode mode);

struct Status {
  std::uint32_t timestamp_us = 0, events_received = 0, crc_errors = 0, framing_errors = 0, overruns = 0, external_events = 0,
                tracks_started = 0, unassigned_clusters = 0;
  // Since the run's reset: events labelled with a track, labelled noise, and packets whose
  // track updates and summary were not sent (tracks mode: the line was busy).
  std::uint32_t labelled = 0, noise = 0, packets_skipped = 0;
};

// Since the run's reset: the link's events the core took (in tracks mode they acknowledge the
// host's events in place of their labels), and the events labelled with a track or as noise.
struct Progress {
  std::uint32_t taken = 0, labelled = 0, noise = 0;
};

struct Frame {
  FrameType type;
  std::vector<std::uint8_t> payload;
  std::uint64_t bad_before = 0;  // the decoder's bad frames before this frame: one that grew lost something in between
};

// Finds frames in a byte stream, checking length and CRC; bad frames are counted and skipped.
class FrameDecoder {
 public:
  void push(std::span<const std::uint8_t> bytes);
  bool next(Frame& out);
  std::uint64_t bad_frames() const { return bad_; }

 private:
  std::deque<std::uint8_t> buf_;
  std::deque<Frame> frames_;
  std::uint64_t bad_ = 0;
};

// A label and its number (modulo 2^16 from the reset on).
struct NumberedLabel {
  Sequence seq;
  hls::LabelWord label;
};
// A label frame's label, or a verdict frame's verdicts (a board whose core is cut:
// label -1 or hls::kLabelPassedFilter), in order. Empty for a verdict frame that breaks its
// layout (none present, a present entry after an absent one): a corruption the CRC missed.
std::vector<NumberedLabel> decode_labels(const Frame& f);
Sequence decode_resend(const Frame& f);
hls::TrackWord decode_track(const Frame& f);
hls::PacketWord decode_packet(const Frame& f);
Status decode_status(const Frame& f);
Progress decode_progress(const Frame& f);
// A climbs frame's words as the board's core sent them (hls/cluster/climbs_words.h): a head's or
// a mode's (frames 0x88 and 0x89: the word's bits 79-64, then 63-0), or the events' of a climbs
// events frame (0x8A: each event's mode in 7 bits, which hold it, as a board's climbs open at
// most 64 modes). Empty for an events frame that breaks its layout (an absent entry that is not
// zero, a present one after an absent one): a corruption the CRC missed.
std::vector<hls::ClimbsWord> decode_climbs(const Frame& f);

}  // namespace evms::link

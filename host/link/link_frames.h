// The serial link's frames (docs/link.md), described once: X(Name, type code, payload length
// in bytes, what it carries). host/link/link_protocol.* takes the frame types and lengths from
// here, and host/tools/rtl_gen writes them for the board's RTL (rtl/generated/evms_link_frames.svh:
// Frame<Name>Type and Frame<Name>Len, used by rtl/board/evms_link_rx.sv and evms_link_tx.sv).
// The payloads' layouts are in docs/link.md.
#pragma once

#include <cstdint>

#define EVMS_LINK_FRAMES(X)                                                                                      \
  X(Events, 0x01, 134, "host to board: up to 32 events, and the first one's number (the length says how many)")   \
  X(Flush, 0x02, 2, "host to board: the next event's number; answered by a status frame once all is released") \
  X(Reset, 0x03, 1, "host to board: restart the core and the link; the run's mode (labels or tracks)")          \
  X(Label, 0x81, 15, "board to host: a labelled event, with the label's number")                                \
  X(Track, 0x82, 33, "board to host: a track update")                                                           \
  X(Packet, 0x83, 12, "board to host: a packet summary")                                                        \
  X(Status, 0x84, 44, "board to host: the board's counters")                                                    \
  X(Resend, 0x85, 2, "board to host: the number of the event the board expects")                                \
  X(Progress, 0x86, 12, "board to host: the link's events the core took, events labelled, noise")               \
  X(Verdict, 0x87, 134, "board to host: up to 32 events with the filter's verdicts, and the first one's label number (a cut core)") \
  X(ClimbsHead, 0x88, 10, "board to host: a packet's climbs frame opens: its events, modes, steps, climbs and modes lost (a core cut after its climbs)") \
  X(ClimbsMode, 0x89, 10, "board to host: a mode of the packet's climbs frame: its x, y and support")                               \
  X(ClimbsEvents, 0x8A, 32, "board to host: up to 32 events of the packet's climbs frame, in packet order: each its mode in a byte (bit 7 present, bits 6-0 the mode, -1: none)")

// The events frame and the verdict frame carry a batch of events (docs/link.md): the first
// event's time (u32) and number (u16), then an entry of a u32 for each event: x in bits 0-7, y in
// 8-15, the polarity in bit 16, passed the filter in bit 17 (verdicts; 0 in events frames),
// present in bit 18, and in bits 19-31 the microseconds since the previous event of the batch (0
// for the first). An events frame holds 1 to kBatchEntries entries, all present, and its length
// says how many; a verdict frame always holds kBatchEntries, the present ones first and the
// others zeros. An event more than kBatchGapMax microseconds after the previous one starts the
// next frame. The boards that speak it are 256x256 at most.
#define EVMS_LINK_BATCH_LAYOUT(X) \
  X(BatchEntries, 32)             \
  X(BatchHeaderBytes, 6)          \
  X(BatchEntryBytes, 4)           \
  X(BatchGapBits, 13)

namespace evms::link {
#define EVMS_LINK_BATCH_CONSTANT(name, value) inline constexpr int k##name = value;
EVMS_LINK_BATCH_LAYOUT(EVMS_LINK_BATCH_CONSTANT)
#undef EVMS_LINK_BATCH_CONSTANT
inline constexpr std::uint32_t kBatchGapMax = (std::uint32_t{1} << kBatchGapBits) - 1;
static_assert(kBatchHeaderBytes + kBatchEntries * kBatchEntryBytes <= 255, "a frame's length is a byte");
// A climbs events frame (0x8A) holds kBatchEntries entries of a byte, one for each event of the
// packet in packet order: bit 7 present, bits 6-0 the event's mode in two's complement (-1: none;
// a board's climbs open at most 64 modes); the present entries first, the others zeros.
inline constexpr std::uint8_t kClimbsEntryPresent = 0x80;
}  // namespace evms::link

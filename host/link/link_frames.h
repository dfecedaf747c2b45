// The serial link's frames (docs/link.md), described once: X(Name, type code, payload length
// in bytes, what it carries). host/link/link_protocol.* takes the frame types and lengths from
// here, and host/tools/rtl_gen writes them for the board's RTL (rtl/generated/evms_link_frames.svh:
// Frame<Name>Type and Frame<Name>Len, used by rtl/board/evms_link_rx.sv and evms_link_tx.sv).
// The payloads' layouts are in docs/link.md.
#pragma once

#define EVMS_LINK_FRAMES(X)                                                                                      \
  X(Event, 0x01, 11, "host to board: an event (t u32, x u16, y u16, p u8, seq u16)")                            \
  X(Flush, 0x02, 2, "host to board: the next event's number; answered by a status frame once all is released") \
  X(Reset, 0x03, 1, "host to board: restart the core and the link; the run's mode (labels or tracks)")          \
  X(Label, 0x81, 15, "board to host: a labelled event, with the label's number")                                \
  X(Track, 0x82, 33, "board to host: a track update")                                                           \
  X(Packet, 0x83, 12, "board to host: a packet summary")                                                        \
  X(Status, 0x84, 44, "board to host: the board's counters")                                                    \
  X(Resend, 0x85, 2, "board to host: the number of the event the board expects")                                \
  X(Progress, 0x86, 12, "board to host: the link's events the core took, events labelled, noise")               \
  X(Verdict, 0x87, 9, "board to host: the filter's verdict on an event, with the label's number (a core that stops at the filter)")

// libFuzzer target for the byte-stream decoders that have no file around them: the USB cameras'
// (DVS128 and DAVIS words, usb_decoders.h) and the board link's frame parser (link_protocol.h),
// fed in pieces whose sizes the input's first byte chooses, as transfers and reads cut them;
// and the UDP source's datagrams (jaer_datagram.h), each piece one datagram.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "host/link/link_protocol.h"
#include "host/read/live/jaer_datagram.h"
#include "host/read/live/usb_decoders.h"

namespace {

struct CountingSink final : evms::read::DecodedSink {
  void event(evms::TimeUs, std::uint16_t, std::uint16_t, std::uint8_t) override { ++events; }
  void skip(const char*) override { ++skipped; }
  long events = 0, skipped = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const size_t piece = 1 + data[0] % 61;
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  CountingSink sink;
  evms::read::Dvs128Decoder dvs(sink);
  evms::read::DavisDecoder davis(sink);
  evms::link::FrameDecoder frames;
  evms::read::JaerDatagramDecoder dvs_datagrams(evms::read::JaerLayout::kDvs128, {128, 128});
  evms::read::JaerDatagramDecoder davis_datagrams(evms::read::JaerLayout::kDavis, {240, 180});
  std::vector<evms::Event> events;
  const auto skip = [&sink](const char* kind) { sink.skip(kind); };
  for (size_t at = 0; at < bytes.size(); at += piece) {
    const auto part = bytes.subspan(at, std::min(piece, bytes.size() - at));
    dvs.feed(part);
    davis.feed(part);
    frames.push(part);
    events.clear();
    dvs_datagrams.decode(part, events, skip);
    davis_datagrams.decode(part, events, skip);
    evms::link::Frame f;
    while (frames.next(f)) {
      switch (f.type) {
        case evms::link::kLabel:
        case evms::link::kVerdict: (void)evms::link::decode_labels(f); break;
        case evms::link::kResend: (void)evms::link::decode_resend(f); break;
        case evms::link::kTrack: (void)evms::link::decode_track(f); break;
        case evms::link::kPacket: (void)evms::link::decode_packet(f); break;
        case evms::link::kStatus: (void)evms::link::decode_status(f); break;
        case evms::link::kProgress: (void)evms::link::decode_progress(f); break;
        default: break;
      }
    }
  }
  return 0;
}

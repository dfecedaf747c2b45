// The board backend: the board top (rtl/board/) on an FPGA, or `evms vboard` behind a
// pseudo-terminal, over the framed serial link of docs/link.md.
//
// A run starts with a reset frame, which the board answers with a status frame once it is
// ready: a board that ran before (or was left mid-run) starts clean, and a missing or silent
// board is found at once. Events go out as event frames while fewer than the link window are unanswered; every event
// comes back as one label frame, so labels are the acknowledgements. finish() sends a flush
// and waits for the status frame that follows everything before it. The board runs its
// build's register values: the iCE40 build's limits (128x128, packets of 64, 8 clusters, 8
// tracks) and the method's defaults. Parameters that differ are refused, not ignored.
#include <cstdio>
#include <stdexcept>

#include "hls/core/configs.h"
#include "host/backend/core_backend.h"
#include "host/backend/registry.h"
#include "host/link/link_protocol.h"
#include "host/link/serial_port.h"

namespace evms::backend {
namespace {

using S = hls::Ice40Shape;
constexpr size_t kLinkWindow = 512;  // LINK_FIFO_DEPTH of the iCEBreaker top
constexpr int kSilenceMs = 10000;    // no frame for this long while waiting: the board is gone

class BoardBackend final : public Backend {
 public:
  explicit BoardBackend(const BackendOptions& o) : port_(check(o), o.baud) {
    // Let what the board is still sending from before go by (up to 2 s of it).
    std::uint8_t old[4096];
    for (int i = 0; i < 100 && port_.read_some(old, 20) > 0; ++i) {
    }
    std::vector<std::uint8_t> reset;
    link::append_reset(reset);
    port_.write_all(reset);
    // Whatever the board sent before the reset is stale; the status frame marks the start.
    DiscardSink stale;
    status_seen_ = false;
    while (!status_seen_) receive(stale, true);
    at_start_ = status_;
  }

  void push(std::span<const Event> events, OutputSink& out) override {
    std::vector<std::uint8_t> frames;
    for (const Event& e : events) {
      while (mapper_.waiting() >= kLinkWindow) receive(out, true);
      link::append_event(frames, mapper_.to_word(e));
      ++stats_.s.events_in;
      if (frames.size() >= 64 * 15 || mapper_.waiting() >= kLinkWindow) {
        port_.write_all(frames);
        frames.clear();
      }
      receive(out, false);
    }
    port_.write_all(frames);
  }

  void finish(OutputSink& out) override {
    std::vector<std::uint8_t> flush;
    link::append_flush(flush);
    port_.write_all(flush);
    status_seen_ = false;
    while (!status_seen_) receive(out, true);
    if (mapper_.waiting() != 0) {
      throw std::runtime_error(port_.path() + ": the board answered the flush with " + std::to_string(mapper_.waiting()) +
                               " events still unlabelled");
    }
    const std::uint32_t crc = status_.crc_errors - at_start_.crc_errors, framing = status_.framing_errors - at_start_.framing_errors,
                        overruns = status_.overruns - at_start_.overruns;
    if (crc || framing || overruns || decoder_.bad_frames() > bad_at_start_) {
      throw std::runtime_error(port_.path() + ": link errors during the run: the board saw " + std::to_string(crc) + " CRC errors, " +
                               std::to_string(framing) + " framing errors and " + std::to_string(overruns) + " overruns; the host saw " +
                               std::to_string(decoder_.bad_frames() - bad_at_start_) + " bad frames");
    }
  }

  BackendStats stats() const override {
    BackendStats s = stats_.s;
    s.tracks_started = status_.tracks_started;
    s.unassigned_clusters = status_.unassigned_clusters;
    return s;
  }

 private:
  static const std::string& check(const BackendOptions& o) {
    if (o.device.empty()) throw std::invalid_argument("the board backend needs --device (e.g. /dev/ttyUSB1, or the path evms vboard prints)");
    if (std::string unsupported = rtl_unsupported(o.params); !unsupported.empty()) throw std::invalid_argument(unsupported);
    if (!(o.params == build_default_params<S>()) || !(o.sensor == SensorSize{S::kMaxWidth, S::kMaxHeight})) {
      throw std::invalid_argument("the board runs its build's settings: a " + std::to_string(S::kMaxWidth) + "x" + std::to_string(S::kMaxHeight) +
                                  " sensor, --packet-size " + std::to_string(S::kPacketMax) + " --max-clusters " +
                                  std::to_string(S::kClustersMax) + " --max-tracks " + std::to_string(S::kTracksMax) +
                                  " and --preset gaussian otherwise; run with exactly those");
    }
    return o.device;
  }

  struct DiscardSink final : OutputSink {
    void on_event(const LabelledEvent&) override {}
    void on_track(const TrackUpdate&) override {}
    void on_packet(const PacketSummary&) override {}
  };

  // Reads what the board has sent; with `wait`, blocks until at least one frame came.
  void receive(OutputSink& out, bool wait) {
    std::uint8_t buf[4096];
    for (;;) {
      const size_t n = port_.read_some(buf, wait ? kSilenceMs : 0);
      if (n == 0 && wait) {
        throw std::runtime_error(port_.path() + ": the board sent nothing for " + std::to_string(kSilenceMs / 1000) + " s (" +
                                 std::to_string(mapper_.waiting()) + " events unanswered)");
      }
      decoder_.push(std::span(buf, n));
      bool any = false;
      link::Frame f;
      while (decoder_.next(f)) {
        any = true;
        if (!started_ && f.type != link::kStatus) {
          continue;  // output of an earlier run, before the reset's status frame
        }
        switch (f.type) {
          case link::kLabel: out.on_event(mapper_.label(link::decode_label(f))); break;
          case link::kTrack: out.on_track(mapper_.track(link::decode_track(f))); break;
          case link::kPacket: {
            const hls::PacketWord p = link::decode_packet(f);
            stats_.on_packet(p);
            out.on_packet(mapper_.packet(p));
            break;
          }
          case link::kStatus:
            status_ = link::decode_status(f), status_seen_ = true;
            if (!started_) started_ = true, bad_at_start_ = decoder_.bad_frames();
            break;
          default: break;
        }
      }
      if (!wait || any || n == 0) return;
    }
  }

  link::SerialPort port_;
  link::FrameDecoder decoder_;
  CoreWordMapper<S> mapper_;
  CoreStats stats_;
  link::Status status_, at_start_;
  std::uint64_t bad_at_start_ = 0;
  bool status_seen_ = false, started_ = false;
};

}  // namespace

std::unique_ptr<Backend> make_board_backend(const BackendOptions& o) { return std::make_unique<BoardBackend>(o); }

}  // namespace evms::backend

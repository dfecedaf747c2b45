// The board backend: the board top (rtl/board/) on an FPGA, or `evms vboard` behind a
// pseudo-terminal, over the framed serial link of docs/link.md.
//
// A run starts with a reset frame, which the board answers with a status frame once it is
// ready: a board that ran before (or was left mid-run) starts clean, and a missing or silent
// board is found. Events go out numbered, while fewer than the link window are unanswered;
// every event comes back as one numbered label frame, so labels are the acknowledgements.
// finish() sends a flush carrying the count of events and waits for the status frame that
// follows everything before it.
//
// The line may flip, drop or repeat bytes. The board takes events in sequence only and asks
// for the first one it is missing (a resend frame); the host then sends again everything from
// there (go-back-N), so the core sees exactly the host's stream. A label frame the line
// destroys cannot be asked for again (the board keeps no labels): the next label's number
// shows the gap, and the events in it are output with kLabelLostOnLink and counted. When the
// board says nothing for kResendMs while something is outstanding (its resend request, or the
// status, was lost), the host sends the outstanding frames again; the board drops copies it
// already has, so this never duplicates an event or a label.
//
// In tracks mode (BackendOptions::board_keeps_labels) the reset frame asks the board to keep
// the labels: the core then never waits for the line. Progress frames, which count the link's
// events the core took, stand in for the labels as acknowledgements; the track updates and
// summaries of whole packets come when the line is free, and the packets the board skipped are
// counted in the status. No event comes back labelled. Listening (listen()), the host pushes no
// events at all: they enter at the board's AER pins, and the host takes the track updates,
// packet summaries and progress frames they bring, for as long as the caller listens.
//
// A board runs its build's register values: on the Arty the default method in the Arty build's
// limits (240x180, packets of 512, 16 clusters and tracks). Parameters that differ are refused.
// A board whose core is cut holds only its cut's registers: the host runs any other setting of
// the rest that its C++ core implements.
//
// A board whose core is cut after its climbs (the iCEBreaker: EVMS_BOARD_BUILDS,
// hls/core/configs.h) answers each event with its filter's verdict and each packet with its
// climbs frame, and the host runs the rest of the build's fixed core (Ice40ClimbsShape) on them,
// so the output is `--backend fixed --core <build>`'s, word for word: it completes each packet
// from its frame (hls::Core::process_climbed), and an event waits on the host until the frames
// of the packets it closes have come. An event whose verdict the line lost goes on as noise, and its
// row says lost (-2). From the first loss on (a verdict, or a frame the check failed), the
// host's packets may no longer be the board's, so it climbs every packet whose frame it does
// not hold yet itself, as process_decided does: the same words the board's frames would give
// where the packets are the same. Tracks mode needs a whole core on the board, and is refused.
// Listening to a cut board, every event that enters at its AER pins comes back with its
// verdict, and the host completes them as they come, at the line's rate.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <set>
#include <stdexcept>
#include <type_traits>

#include "hls/core/configs.h"
#include "host/backend/core_backend.h"
#include "host/backend/fixed_backend.h"
#include "host/backend/registry.h"
#include "host/link/find_bridge.h"
#include "host/link/link_protocol.h"
#include "host/link/serial_port.h"

namespace evms::backend {
namespace {

constexpr int kResendMs = 500;       // silence while waiting: send what is outstanding again
constexpr int kSilenceMs = 10000;    // no frame for this long while waiting: the board is gone

// The full number of a frame numbered modulo 2^16, at or after `oldest`.
std::uint64_t unwrap(link::Sequence seq, std::uint64_t oldest) {
  return oldest + static_cast<link::Sequence>(seq - static_cast<link::Sequence>(oldest));
}

// S: the board's RTL Shape. Rest: the C++ core that completes a board whose core is cut (the
// build's fixed Shape, which holds the whole method), else S.
// LinkWindow: the events the board's link queue holds (board_of, host/backend/core_config.h);
// the host keeps at most this many unanswered. It must exceed what the core can hold unlabelled
// (its pending queue and its intake's packet), or a noisy stretch would leave the host waiting
// for labels of a packet that only more events can close.
template <class S, class Rest, size_t LinkWindow>
class BoardBackend final : public Backend {
  static_assert(LinkWindow > static_cast<size_t>(S::kPendingDepth + S::kPacketMax), "the link window must exceed what the core holds unlabelled");
  static_assert(Rest::kModesMax <= 64, "a climbs events frame carries an event's mode in 7 bits (host/link/link_frames.h)");

 public:
  BoardBackend(const BackendOptions& o, const char* build)
      : port_(check(o, build), o.baud > 0 ? o.baud : static_cast<int>(board_of(build).baud())),
        mode_(o.board_keeps_labels ? link::LinkMode::kTracks : link::LinkMode::kLabels) {
    if (board_of(build).cut()) rest_ = std::make_unique<HostCore<Rest>>(core_config<Rest>(o.params, o.sensor));
    // Let what the board is still sending from before go by (up to 2 s of it).
    std::uint8_t old[4096];
    for (int i = 0; i < 100 && port_.read_some(old, 20) > 0; ++i) {
    }
    send_reset();
    // Whatever the board sent before the reset is stale; the status frame marks the start.
    DiscardSink stale;
    while (!started_) receive(stale, true);
  }

  void push(std::span<const Event> events, OutputSink& out) override {
    for (const Event& e : events) {
      while (unanswered_.size() >= LinkWindow) {
        send_unsent();
        receive(out, true);
      }
      unanswered_.push_back(mapper_.to_word(e));
      ++unsent_;
      ++stats_.s.events_in;
      if (unsent_ >= static_cast<size_t>(link::kBatchEntries)) send_unsent();
      receive(out, false);
    }
    send_unsent();
  }

  void finish(OutputSink& out) override {
    // Listening ends where the user stops it, while the board goes on with its sensor's events:
    // there is no end of input to flush to (a flush's status waits for an idle core). The rest
    // of the core on the host closes its open packet on the events that came.
    if (listening_) {
      if (rest_) {
        climbs_lost_ = true;  // the board closes no packet for the host's flush
        advance(out);
        rest_->flush();
        drain_rest(out);
      }
      return;
    }
    flushing_ = true;
    send_flush();
    while (flushing_) receive(out, true);
    // The board labelled every event before the status: labels still missing were lost (in
    // tracks mode, the core took every event, and their labels stayed on the board).
    while (!unanswered_.empty()) mode_ == link::LinkMode::kTracks ? take_oldest() : lose_oldest(out);
    if (rest_) {
      // The board's core closed its packet on the flush, and sent every frame before the status.
      hls::EventWord flush;
      flush.flush = true;
      complete(flush, false, false, out);
      climbs_lost_ = true;  // a frame still missing was lost
      advance(out);
    }
  }

  // Listening: the events enter at the board's AER pins and none go out, so only track
  // updates, packet summaries and progress frames come. A sensor that sees nothing moving
  // sends nothing, so silence here is not a lost board.
  void listen(OutputSink& out, int wait_ms, std::int64_t limit) override {
    if (mode_ != link::LinkMode::kTracks && !rest_) {
      throw std::invalid_argument("listening to the board's AER pins needs --board-link tracks: only track updates cross the line");
    }
    listening_ = true;
    listen_limit_ = limit;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(wait_ms);
    std::uint8_t buf[4096];
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now()).count();
      if (left <= 0 || (limit > 0 && stats().events_in >= limit)) return;
      const size_t n = port_.read_some(buf, static_cast<int>(left));
      decoder_.push(std::span(buf, n));
      take_frames(out);
    }
  }

  BackendStats stats() const override {
    BackendStats s = stats_.s;
    // Listening, no status follows a flush: the tracks started are those whose updates came.
    s.tracks_started = listening_ ? static_cast<std::int64_t>(listened_ids_.size()) : status_.tracks_started;
    s.unassigned_clusters = status_.unassigned_clusters;
    if (rest_) rest_->add_tracker_stats(s);
    s.link_bad_frames = static_cast<std::int64_t>(decoder_.bad_frames() - bad_at_start_) + (status_.crc_errors - at_start_.crc_errors) +
                        (status_.framing_errors - at_start_.framing_errors) + unbelieved_;
    s.link_events_resent = resent_;
    s.link_labels_lost = lost_;
    if (mode_ == link::LinkMode::kTracks) {
      // The latest of the counts the status and progress frames carry (they only grow in a run).
      s.board_labelled = std::max<std::int64_t>(status_.labelled, progress_.labelled);
      s.board_noise = std::max<std::int64_t>(status_.noise, progress_.noise);
      s.link_packets_skipped = status_.packets_skipped;
      // Listening, the events in are those the board took at its AER pins, as it counts them.
      if (listening_) s.events_in = s.board_labelled + s.board_noise;
      s.labels_kept_on_board = s.events_in;
    }
    return s;
  }

 private:
  // The device to open, once the settings are ones the board runs: --device, or the one board's
  // UART connected (host/link/find_bridge.h).
  static std::string check(const BackendOptions& o, const char* build) {
    if (board_of(build).cut() && o.board_keeps_labels) {
      throw std::invalid_argument(std::string("the ") + build + " board's core is cut and the host completes its verdicts, so " +
                                  "they must cross the link: --board-link tracks needs a board with the whole core (--core arty)");
    }
    const SensorSize board_sensor{S::kMaxWidth, S::kMaxHeight};
    const std::string board = std::string("the ") + build + " board";
    if (!(o.sensor == board_sensor)) {
      throw std::invalid_argument(board + " is built for a " + std::to_string(S::kMaxWidth) + "x" + std::to_string(S::kMaxHeight) +
                                  " sensor, but the source is " + std::to_string(o.sensor.width) + "x" + std::to_string(o.sensor.height) +
                                  " (--roi X,Y," + std::to_string(S::kMaxWidth) + "," + std::to_string(S::kMaxHeight) + " takes a part of it)");
    }
    // The board's registers are its build's. A cut core holds only its cut's (the values of the
    // build's fixed core, which completes it), and the host's C++ core runs any other setting
    // it implements.
    const bool cut = board_of(build).cut();
    const Params held = cut ? build_default_params<Rest>() : build_default_params<S>();
    auto refuse = [&](const ParamInfo& info, const std::string& what) {
      throw std::invalid_argument(board + " runs its build's " + what + ", but --" + info.name + " is " + param_text(o.params, info) +
                                  ", the board's " + param_text(held, info));
    };
    if (cut) {
      if (std::string unsupported = core_unsupported(o.params); !unsupported.empty()) throw std::invalid_argument(unsupported);
      if (const char* name = first_climbs_difference(o.params, held)) {
        refuse(*find_param(name), "filter, packet and climbs settings, without warm seeds (the host runs any other)");
      }
    } else {
      if (std::string unsupported = rtl_unsupported(o.params, build); !unsupported.empty()) throw std::invalid_argument(unsupported);
      if (const auto differ = differing_params(o.params, held); !differ.empty()) {
        refuse(*differ.front(), "settings: --packet-size " + std::to_string(S::kPacketMax) + " --max-clusters " +
                                    std::to_string(S::kClustersMax) + " --max-tracks " + std::to_string(S::kTracksMax) +
                                    " and the method its registers hold");
      }
    }
    return o.device.empty() ? link::the_board_uart() : o.device;
  }

  struct DiscardSink final : OutputSink {
    void on_event(const LabelledEvent&) override {}
    void on_track(const TrackUpdate&) override {}
    void on_packet(const PacketSummary&) override {}
  };

  void send_reset() {
    std::vector<std::uint8_t> reset;
    link::append_reset(reset, mode_);
    port_.write_all(reset);
  }
  void send_flush() {
    std::vector<std::uint8_t> flush;
    link::append_flush(flush, static_cast<link::Sequence>(answered_ + unanswered_.size()));
    port_.write_all(flush);
  }
  // Every event from number `from` on again (go-back-N), and the flush if it was sent. Each
  // lost events frame costs a resend of everything in flight after it. The window stays whole:
  // the core holds the events of an open packet (and the filtered ones among them) unlabelled
  // until the packet closes, so a window below what it can hold would wait forever.
  // The events not yet sent go with them.
  void resend_from(std::uint64_t from) {
    const size_t at = static_cast<size_t>(from - answered_), sent = unanswered_.size() - unsent_;
    if (at < sent) resent_ += static_cast<std::int64_t>(sent - at);
    send_from(at);
    if (flushing_) send_flush();
  }
  // The unanswered events that were never sent (the last unsent_ of them).
  void send_unsent() {
    if (unsent_ > 0) send_from(unanswered_.size() - unsent_);
  }
  // The unanswered events from the at-th on, in events frames.
  void send_from(size_t at) {
    const std::vector<hls::EventWord> words(unanswered_.begin() + static_cast<std::ptrdiff_t>(at), unanswered_.end());
    std::vector<std::uint8_t> frames;
    link::append_events(frames, words, static_cast<link::Sequence>(answered_ + at));
    port_.write_all(frames);
    unsent_ = 0;
  }
  static bool echoes(const hls::LabelWord& label, const hls::EventWord& event) {
    return label.t == event.t && label.x == event.x && label.y == event.y && label.p == event.p;
  }
  // Tracks mode: the oldest unanswered event, which the core took; its label stays on the board.
  void take_oldest() {
    mapper_.forget_oldest();
    unanswered_.pop_front();
    ++answered_;
  }
  void lose_oldest(OutputSink& out) {
    if (rest_) {
      complete(unanswered_.front(), false, true, out);
    } else {
      out.on_event(mapper_.lost());
    }
    unanswered_.pop_front();
    ++answered_, ++lost_;
  }
  // A cut core: the rest of the core on the host takes the event (or the closing flush word)
  // with its verdict (a lost one as noise, its row marked lost), and releases what it can.
  void complete(const hls::EventWord& event, bool kept, bool lost, OutputSink& out) {
    if (!event.flush) {
      if (!lost) ++(kept ? stats_.s.board_passed : stats_.s.board_filtered);
      rest_lost_.push_back(lost);
    }
    if (lost) climbs_lost_ = true;  // the board's packets may hold it: the host's no longer
    decided_.push_back({event, kept});
    advance(out);
  }
  // The decided words, in order, into the rest of the core: each as soon as it can go. The board
  // sends the frame of each packet the word closes after the word's verdict, so the word waits
  // for them; once the line has lost something, the host climbs every packet whose frame it
  // does not hold itself.
  void advance(OutputSink& out) {
    while (!decided_.empty()) {
      const Decided d = decided_.front();
      const int needed = rest_->climbs_needed(d.event, d.kept);
      if (needed > static_cast<int>(frames_.size())) {
        if (!climbs_lost_) return;
        frames_.clear();  // a word that closes two packets, one frame here: the host climbs both
      }
      if (needed > 0 && !frames_.empty()) {
        for (int k = 0; k < needed; ++k) {
          rest_->give_climbs(frames_.front());
          frames_.pop_front();
        }
        rest_->process_climbed(d.event, d.kept);
        stats_.s.board_climbed_packets += needed;
      } else {
        stats_.s.host_climbed_packets += needed;
        rest_->process_decided(d.event, d.kept);
      }
      decided_.pop_front();
      drain_rest(out);
    }
  }
  // A climbs frame's words: a whole frame waits for the words that close its packet. A word the
  // assembler cannot place, or an events frame that breaks its layout (a corruption the check
  // missed), means the line lost some.
  void take_climbs(const link::Frame& f, OutputSink& out) {
    const std::vector<hls::ClimbsWord> words = link::decode_climbs(f);
    if (words.empty()) ++unbelieved_, climbs_lost_ = true;
    const long broken = assembler_.broken();
    for (const hls::ClimbsWord& w : words) {
      if (assembler_.take(w) && !climbs_lost_) frames_.push_back(assembler_.frame());
    }
    if (assembler_.broken() != broken) climbs_lost_ = true;
    advance(out);
  }
  void drain_rest(OutputSink& out) {
    rest_->drain(out, mapper_, stats_, [this](const hls::LabelWord& l) {
      const bool lost = rest_lost_.front();
      rest_lost_.pop_front();
      return lost ? mapper_.lost() : mapper_.label(l);
    });
  }

  // Listening to a board whose core is cut: each verdict frame brings an event the board
  // took at its AER pins, with its verdict, and the rest of the core on the host takes it. A gap
  // in the numbers is events the line destroyed; no one has them to send again, so they are
  // counted as labels lost, and their rows are missing.
  void take_stamped(const link::NumberedLabel& numbered, OutputSink& out) {
    if (listen_limit_ > 0 && stats_.s.events_in >= listen_limit_) return;  // the user's --limit: the sensor goes on
    const hls::LabelWord& label = numbered.label;
    const std::uint64_t number = unwrap(numbered.seq, answered_);
    // The run starts at the first event after the reset's status: the sensor never stopped, and
    // events the board labelled before it said it was ready went by as stale.
    if (!stamped_any_) answered_ = number, stamped_any_ = true;
    lost_ += static_cast<std::int64_t>(number - answered_);
    if (number != answered_) climbs_lost_ = true;
    answered_ = number + 1;
    ++stats_.s.events_in;
    const hls::EventWord event{label.t, label.x, label.y, label.p, false};
    mapper_.stamped(event);
    complete(event, label.label == hls::kLabelPassedFilter, false, out);
  }

  // A label of an event the host sent.
  void take_label(const link::NumberedLabel& numbered, OutputSink& out) {
    const std::uint64_t number = unwrap(numbered.seq, answered_);
    const hls::LabelWord& label = numbered.label;
    // A frame whose corruption the check missed (one in 2^16 corrupt frames) names no
    // event of ours, or not the event its number says: it is dropped, not believed.
    if (number >= answered_ + unanswered_.size() || !echoes(label, unanswered_[number - answered_])) {
      ++unbelieved_;
      return;
    }
    while (answered_ < number) lose_oldest(out);
    if (rest_) {
      complete(unanswered_.front(), label.label == hls::kLabelPassedFilter, false, out);
    } else {
      out.on_event(mapper_.label(label));
    }
    unanswered_.pop_front();
    ++answered_;
  }

  // Reads what the board has sent; with `wait`, blocks until at least one frame came or, after
  // kResendMs of silence, the outstanding frames were sent again.
  void receive(OutputSink& out, bool wait) {
    std::uint8_t buf[4096];
    for (;;) {
      const size_t n = port_.read_some(buf, wait ? kResendMs : 0);
      if (n == 0 && wait) {
        silent_ms_ += kResendMs;
        if (silent_ms_ >= kSilenceMs) {
          throw std::runtime_error(port_.path() + ": the board sent nothing for " + std::to_string(kSilenceMs / 1000) + " s (" +
                                   std::to_string(unanswered_.size()) + " events unanswered)");
        }
        if (!started_) {
          send_reset();
        } else {
          resend_from(answered_);
        }
        return;
      }
      decoder_.push(std::span(buf, n));
      const bool any = take_frames(out);
      if (!wait || any || n == 0) return;
    }
  }

  // Acts on every whole frame the decoder holds; says whether there was one.
  bool take_frames(OutputSink& out) {
    bool any = false;
    link::Frame f;
    while (decoder_.next(f)) {
      any = true;
      silent_ms_ = 0;
      // Frames the check failed before this one: what they carried is lost.
      if (f.bad_before > bad_seen_) bad_seen_ = f.bad_before, climbs_lost_ = climbs_lost_ || started_;
      if (!started_ && f.type != link::kStatus) continue;  // output of an earlier run, before the reset's status frame
      const bool climbs_word = f.type == link::kClimbsHead || f.type == link::kClimbsMode || f.type == link::kClimbsEvents;
      if ((rest_ && (f.type == link::kTrack || f.type == link::kPacket)) || (climbs_word && !rest_)) {
        ++unbelieved_;  // a cut core sends no track or packet frames, and a whole core no climbs words:
        continue;       // a corruption the check missed
      }
      switch (f.type) {
        case link::kLabel:
        case link::kVerdict: {
          // A cut core sends verdicts (noise or passed, nothing else), a whole
          // core labels: the other is a corruption the check missed.
          if ((f.type == link::kVerdict) != (rest_ != nullptr)) {
            ++unbelieved_;
            break;
          }
          const std::vector<link::NumberedLabel> labels = link::decode_labels(f);
          if (labels.empty()) ++unbelieved_;
          if (listening_ && rest_) {
            for (const link::NumberedLabel& l : labels) take_stamped(l, out);
            break;
          }
          if (mode_ == link::LinkMode::kTracks) {  // not a frame of this run's mode: a corruption the check missed
            ++unbelieved_;
            break;
          }
          for (const link::NumberedLabel& l : labels) take_label(l, out);
          break;
        }
        case link::kResend: {
          const std::uint64_t from = unwrap(link::decode_resend(f), answered_);
          if (from <= answered_ + unanswered_.size()) resend_from(from);
          break;
        }
        case link::kProgress: {
          // In labels mode it only says the board is working: the labels acknowledge. Before
          // the reset's status frame it is stale.
          if (mode_ != link::LinkMode::kTracks || !started_) break;
          // The core took the link's events up to this count (numbers since the reset, modulo
          // 2^32; a run's unanswered events are far fewer).
          const link::Progress p = link::decode_progress(f);
          progress_.labelled = p.labelled, progress_.noise = p.noise;
          const std::uint64_t taken = answered_ + static_cast<std::uint32_t>(p.taken - static_cast<std::uint32_t>(answered_));
          if (taken > answered_ + unanswered_.size()) {
            ++unbelieved_;
            break;
          }
          while (answered_ < taken) take_oldest();
          break;
        }
        case link::kTrack: {
          const TrackUpdate u = mapper_.track(link::decode_track(f));
          if (listening_) listened_ids_.insert(u.id);
          out.on_track(u);
          break;
        }
        case link::kPacket: {
          const hls::PacketWord p = link::decode_packet(f);
          stats_.on_packet(p);
          out.on_packet(mapper_.packet(p));
          break;
        }
        case link::kClimbsHead:
        case link::kClimbsMode:
        case link::kClimbsEvents: take_climbs(f, out); break;
        case link::kStatus: {
          const link::Status status = link::decode_status(f);
          if (!started_) {
            // The run starts here. The frames after it wait in the decoder for the run to take
            // them: a listening run's first verdicts can come in the same read.
            started_ = true, bad_at_start_ = decoder_.bad_frames(), status_ = at_start_ = status;
            return true;
          } else if (flushing_ && status.events_received - at_start_.events_received == static_cast<std::uint32_t>(answered_ + unanswered_.size())) {
            // The flush's status: the board took every event (a reset's status, repeated
            // when the first was slow, comes before any).
            status_ = status, flushing_ = false;
          }
          break;
        }
        default: break;
      }
    }
    return any;
  }

  link::SerialPort port_;
  link::LinkMode mode_;
  link::FrameDecoder decoder_;
  CoreWordMapper<Rest> mapper_;  // Rest's formats: a cut core sends no track words, and a whole core's has Rest = S
  CoreStats stats_;
  // The rest of the core, when the board's is cut; whether each event it holds lost its verdict
  // on the line.
  std::unique_ptr<HostCore<Rest>> rest_;
  std::deque<bool> rest_lost_;
  // The decided words waiting for their packets' frames, the whole frames waiting for their
  // words, and whether the line lost something since the run's start.
  struct Decided {
    hls::EventWord event;
    bool kept;
  };
  std::deque<Decided> decided_;
  std::deque<hls::ClimbsFrame<Rest>> frames_;
  hls::ClimbsFrameAssembler<Rest> assembler_;
  bool climbs_lost_ = false;
  std::uint64_t bad_seen_ = 0;  // the decoder's bad frames as the last frame taken found them
  std::deque<hls::EventWord> unanswered_;  // taken, not yet labelled: numbers answered_, answered_ + 1, ...
  size_t unsent_ = 0;                      // the last of them, not yet sent (they wait to fill an events frame)
  std::uint64_t answered_ = 0;             // events labelled, or whose label was lost
  std::int64_t resent_ = 0, lost_ = 0, unbelieved_ = 0;
  int silent_ms_ = 0;
  link::Status status_, at_start_;
  link::Progress progress_;  // the latest progress frame's counts (tracks mode)
  std::uint64_t bad_at_start_ = 0;
  bool started_ = false, flushing_ = false;
  bool listening_ = false;             // listen() was called: the events enter at the board's AER pins
  bool stamped_any_ = false;           // listening to a cut core: an event came
  std::int64_t listen_limit_ = 0;      // listening: the most events to take (0: no limit)
  std::set<std::int32_t> listened_ids_;  // the track IDs whose updates came while listening
};

template <class S, class Rest, size_t LinkWindow>
std::unique_ptr<Backend> board_backend_of(const BackendOptions& o, const char* build) {
  if constexpr (LinkWindow == 0) {
    throw std::invalid_argument(std::string("the board backend runs --core ice40 (the iCEBreaker) or arty (the Arty), not ") + build);
  } else {
    return std::make_unique<BoardBackend<S, Rest, LinkWindow>>(o, build);
  }
}

}  // namespace

std::unique_ptr<Backend> make_board_backend(const BackendOptions& o) {
  const std::string build = board_build(o.core);
#define EVMS_BOARD_BACKEND_OF(name, fixed, rtl, width, height, description)                                                       \
  if (build == #name) {                                                                                                         \
    return board_backend_of<hls::rtl, std::conditional_t<board_of(#name).cut(), hls::fixed, hls::rtl>,           \
                            static_cast<size_t>(board_of(#name).link_fifo_depth)>(o, #name);                                    \
  }
  EVMS_CORE_BUILDS(EVMS_BOARD_BACKEND_OF)
#undef EVMS_BOARD_BACKEND_OF
  throw std::invalid_argument("unknown core build '" + build + "'");
}

}  // namespace evms::backend

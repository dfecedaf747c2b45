// The fixed backend: the bit-accurate C++ core (hls/) on the host, for any Shape (the
// registry's "fixed" is hls::HostShape; the word-width study instantiates others).
#pragma once

#include <memory>

#include "hls/core/core.h"
#include "host/backend/core_backend.h"

namespace evms::backend {

// The C++ core on the host with its output streams: the fixed backend's, and the rest of the
// core of a board whose core is cut (host/backend/board_backend.cpp).
template <class S>
class HostCore {
 public:
  explicit HostCore(const hls::Config& cfg) : state_(std::make_unique<State>()) { state_->core.reset(cfg); }
  void process(const hls::EventWord& w) { state_->core.process(w, state_->labels, state_->tracks, state_->packets); }
  void process_decided(const hls::EventWord& w, bool kept) {
    state_->core.process_decided(w, kept, state_->labels, state_->tracks, state_->packets);
  }
  // The core cut after its climbs (hls::Core::process_to_climbs), keeping each packet's climbs
  // for next_climbs(); and the rest of the core on a board's verdicts and climbs
  // (process_climbed, which takes climbs_needed() frames given by give_climbs()).
  void process_to_climbs(const hls::EventWord& w) { state_->core.process_to_climbs(w, state_->labels, state_->tracks, state_->packets, state_->climbs); }
  bool next_climbs(hls::ClimbsFrame<S>& f) { return state_->climbs.read(f); }
  int climbs_needed(const hls::EventWord& w, bool kept) const { return state_->core.climbs_needed(w, kept); }
  void give_climbs(const hls::ClimbsFrame<S>& f) { state_->climbs.write(f); }
  void process_climbed(const hls::EventWord& w, bool kept) {
    state_->core.process_climbed(w, kept, state_->climbs, state_->labels, state_->tracks, state_->packets);
  }
  void flush() {
    hls::EventWord w;
    w.flush = true;
    process(w);
  }
  // Hands every word the core released to the callbacks: the labels, then the track updates,
  // then the packet summaries.
  template <class OnLabel, class OnTrack, class OnPacket>
  void drain(OnLabel&& on_label, OnTrack&& on_track, OnPacket&& on_packet) {
    hls::LabelWord l;
    while (state_->labels.read(l)) on_label(l);
    hls::TrackWord t;
    while (state_->tracks.read(t)) on_track(t);
    hls::PacketWord p;
    while (state_->packets.read(p)) on_packet(p);
  }
  // The same into `out` as host records: each label word as label_of(word) makes it, the track
  // updates and summaries by `mapper`, the summaries counted in `stats`.
  template <class LabelOf>
  void drain(OutputSink& out, const CoreWordMapper<S>& mapper, CoreStats& stats, LabelOf&& label_of) {
    drain([&](const hls::LabelWord& l) { out.on_event(label_of(l)); }, [&](const hls::TrackWord& t) { out.on_track(mapper.track(t)); },
          [&](const hls::PacketWord& p) {
            stats.on_packet(p);
            out.on_packet(mapper.packet(p));
          });
  }
  // A write into a full stream (the host drains after every word, so never).
  bool overflowed() const {
    return state_->labels.overflowed() || state_->tracks.overflowed() || state_->packets.overflowed() || state_->climbs.overflowed();
  }
  void add_tracker_stats(BackendStats& s) const {
    s.tracks_started = state_->core.tracker().tracks_started();
    s.unassigned_clusters = state_->core.tracker().unassigned_clusters();
  }

 private:
  // The core's memories are large: it lives on the heap, with its output streams.
  struct State {
    hls::Core<S> core;
    typename hls::Core<S>::LabelStream labels;
    typename hls::Core<S>::TrackStream tracks;
    typename hls::Core<S>::PacketStream packets;
    typename hls::Core<S>::ClimbsStream climbs;
  };
  std::unique_ptr<State> state_;
};

template <class S>
class FixedBackend final : public Backend {
 public:
  explicit FixedBackend(const BackendOptions& o) : core_(core_config<S>(o.params, o.sensor)) {}
  void push(std::span<const Event> events, OutputSink& out) override {
    for (const Event& e : events) {
      ++stats_.s.events_in;
      core_.process(mapper_.to_word(e));
      drain(out);
    }
  }
  void finish(OutputSink& out) override {
    core_.flush();
    drain(out);
  }
  BackendStats stats() const override {
    BackendStats s = stats_.s;
    core_.add_tracker_stats(s);
    return s;
  }

 private:
  void drain(OutputSink& out) {
    core_.drain(out, mapper_, stats_, [this](const hls::LabelWord& l) { return mapper_.label(l); });
  }

  HostCore<S> core_;
  CoreWordMapper<S> mapper_;
  CoreStats stats_;
};

}  // namespace evms::backend

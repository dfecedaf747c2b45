// The fixed backend: the bit-accurate C++ core (hls/) on the host, for any Shape (the
// registry's "fixed" is hls::HostShape; the word-width study instantiates others).
#pragma once

#include <memory>

#include "hls/core/core.h"
#include "host/backend/core_backend.h"

namespace evms::backend {

template <class S>
class FixedBackend final : public Backend {
 public:
  explicit FixedBackend(const BackendOptions& o) : state_(std::make_unique<State>()) {
    state_->core.reset(core_config<S>(o.params, o.sensor));
  }
  void push(std::span<const Event> events, OutputSink& out) override {
    for (const Event& e : events) {
      ++stats_.s.events_in;
      state_->core.process(mapper_.to_word(e), state_->labels, state_->tracks, state_->packets);
      drain(out);
    }
  }
  void finish(OutputSink& out) override {
    hls::EventWord flush;
    flush.flush = true;
    state_->core.process(flush, state_->labels, state_->tracks, state_->packets);
    drain(out);
  }
  BackendStats stats() const override {
    BackendStats s = stats_.s;
    s.tracks_started = state_->core.tracker().tracks_started();
    s.unassigned_clusters = state_->core.tracker().unassigned_clusters();
    return s;
  }

 private:
  void drain(OutputSink& out) {
    hls::LabelWord l;
    while (state_->labels.read(l)) out.on_event(mapper_.label(l));
    hls::TrackWord t;
    while (state_->tracks.read(t)) out.on_track(mapper_.track(t));
    hls::PacketWord p;
    while (state_->packets.read(p)) {
      stats_.on_packet(p);
      out.on_packet(mapper_.packet(p));
    }
  }

  // The core's memories are large: it lives on the heap, with its output streams.
  struct State {
    hls::Core<S> core;
    typename hls::Core<S>::LabelStream labels;
    typename hls::Core<S>::TrackStream tracks;
    typename hls::Core<S>::PacketStream packets;
  };
  std::unique_ptr<State> state_;
  CoreWordMapper<S> mapper_;
  CoreStats stats_;
};

}  // namespace evms::backend

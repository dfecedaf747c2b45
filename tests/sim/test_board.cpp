// The board top: events over the UART link in, labels, tracks and packet summaries out,
// framed and checked; the AER receiver's four-phase handshake. Compared with the C++ core of
// the same build (hls::Ice40Shape).
#include <gtest/gtest.h>

#include "Vboard_ice40.h"
#include "hls/core/configs.h"
#include "hls/core/core.h"
#include "host/backend/core_config.h"
#include "host/eval/scene_run.h"
#include "host/link/link_protocol.h"
#include "sim/virtual_board.h"
#include "tests/support/scenes.h"

namespace evms {
namespace {

using S = hls::Ice40Shape;
constexpr int kCpb = 4;
constexpr int kWindow = 512;  // events in flight: the board's link FIFO

struct Expected {
  std::vector<hls::LabelWord> labels;
  std::vector<hls::TrackWord> tracks;
  std::vector<hls::PacketWord> packets;
};

Expected cxx_core(const std::vector<hls::EventWord>& words) {
  auto core = std::make_unique<hls::Core<S>>();
  auto labels = std::make_unique<hls::Core<S>::LabelStream>();
  hls::Core<S>::TrackStream tracks;
  hls::Core<S>::PacketStream packets;
  core->reset(backend::core_config<S>(backend::build_default_params<S>(), {128, 128}));
  Expected e;
  for (const auto& w : words) {
    core->process(w, *labels, tracks, packets);
    hls::LabelWord l;
    while (labels->read(l)) e.labels.push_back(l);
    hls::TrackWord t;
    while (tracks.read(t)) e.tracks.push_back(t);
    hls::PacketWord p;
    while (packets.read(p)) e.packets.push_back(p);
  }
  return e;
}

struct Received {
  Expected words;
  std::vector<link::Sequence> label_seqs;
  std::vector<link::Sequence> resends;  // the numbers the board asked for again
  std::vector<link::Status> status;
  std::uint64_t bad_frames = 0;
};

void collect(sim::VirtualBoard<Vboard_ice40>& board, link::FrameDecoder& decoder, Received& r) {
  std::vector<std::uint8_t> bytes(board.received.begin(), board.received.end());
  board.received.clear();
  decoder.push(bytes);
  link::Frame f;
  while (decoder.next(f)) {
    switch (f.type) {
      case link::kLabel:
        r.words.labels.push_back(link::decode_label(f));
        r.label_seqs.push_back(link::label_sequence(f));
        break;
      case link::kTrack: r.words.tracks.push_back(link::decode_track(f)); break;
      case link::kPacket: r.words.packets.push_back(link::decode_packet(f)); break;
      case link::kStatus: r.status.push_back(link::decode_status(f)); break;
      case link::kResend: r.resends.push_back(link::decode_resend(f)); break;
      default: break;
    }
  }
  r.bad_frames = decoder.bad_frames();
}

// Streams `frames` (one per event, numbered from 0, then a flush) keeping at most kWindow
// events in flight, and going back to the frame the board asks for again, as the host does.
// The first copy of frame `corrupt` (if any) has a payload bit flipped on the line.
Received run_link(const std::vector<std::vector<std::uint8_t>>& frames, size_t corrupt = SIZE_MAX) {
  sim::VirtualBoard<Vboard_ice40> board(kCpb);
  link::FrameDecoder decoder;
  Received r;
  size_t next = 0;
  size_t resends_seen = 0;
  std::uint64_t guard = 0;
  while (r.status.empty()) {
    if (next < frames.size() && !board.sending() && next < r.words.labels.size() + kWindow) {
      std::vector<std::uint8_t> frame = frames[next];
      if (next == corrupt) frame[6] ^= 0x10, corrupt = SIZE_MAX;
      board.send(frame);
      ++next;
    }
    board.run(64);
    collect(board, decoder, r);
    for (; resends_seen < r.resends.size(); ++resends_seen) next = r.resends[resends_seen];  // fewer than 2^16 frames here
    if (++guard > 5000000) {
      ADD_FAILURE() << "no status frame after the flush";
      break;
    }
  }
  return r;
}

std::vector<std::vector<std::uint8_t>> link_frames(const std::vector<hls::EventWord>& words) {
  std::vector<std::vector<std::uint8_t>> frames;
  for (const auto& w : words) {
    frames.emplace_back();
    link::append_event(frames.back(), w, static_cast<link::Sequence>(frames.size() - 1));
  }
  frames.emplace_back();
  link::append_flush(frames.back(), static_cast<link::Sequence>(words.size()));
  return frames;
}

void expect_same(const Expected& got, const Expected& want) {
  ASSERT_EQ(got.labels.size(), want.labels.size());
  for (size_t i = 0; i < want.labels.size(); ++i) {
    ASSERT_EQ(got.labels[i].t, want.labels[i].t) << i;
    ASSERT_EQ(got.labels[i].x, want.labels[i].x) << i;
    ASSERT_EQ(got.labels[i].y, want.labels[i].y) << i;
    ASSERT_EQ(got.labels[i].label, want.labels[i].label) << i;
  }
  ASSERT_EQ(got.tracks.size(), want.tracks.size());
  for (size_t i = 0; i < want.tracks.size(); ++i) {
    ASSERT_EQ(got.tracks[i].id, want.tracks[i].id) << i;
    ASSERT_EQ(got.tracks[i].x, want.tracks[i].x) << i;
    ASSERT_EQ(got.tracks[i].vy, want.tracks[i].vy) << i;
  }
  ASSERT_EQ(got.packets.size(), want.packets.size());
  for (size_t i = 0; i < want.packets.size(); ++i) ASSERT_EQ(got.packets[i].clusters, want.packets[i].clusters) << i;
}

std::vector<hls::EventWord> scene_words(double duration_s) {
  gen::SceneConfig c;
  c.motion = gen::Motion::kRotation;
  c.duration_s = duration_s;
  c.width = c.height = 128;
  const auto events = eval::generate_scene(c).events;
  std::vector<hls::EventWord> w;
  for (const Event& e : events) w.push_back({static_cast<std::uint32_t>(e.t + 1), e.x, e.y, e.p, false});
  return w;
}

TEST(BoardLink, EventsInLabelsOutEqualToTheCppCore) {
  auto words = scene_words(0.04);
  const Received r = run_link(link_frames(words));
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  expect_same(r.words, cxx_core(words));
  ASSERT_EQ(r.status.size(), 1u);
  EXPECT_EQ(r.status[0].events_received, words.size() - 1);
  EXPECT_EQ(r.status[0].crc_errors, 0u);
  EXPECT_EQ(r.status[0].framing_errors, 0u);
  EXPECT_EQ(r.status[0].overruns, 0u);
  EXPECT_EQ(r.bad_frames, 0u);
  EXPECT_TRUE(r.resends.empty());
  // Label frames are numbered in order from the reset.
  for (size_t i = 0; i < r.label_seqs.size(); ++i) ASSERT_EQ(r.label_seqs[i], static_cast<link::Sequence>(i)) << i;
}

// A frame the line corrupts is counted and dropped, the frames after it are refused until the
// board has asked for it once, and the core sees the whole stream in order.
TEST(BoardLink, ACorruptEventFrameIsAskedForAgainAndNothingIsLost) {
  auto words = scene_words(0.015);
  const size_t corrupt = words.size() / 2;
  const Received r = run_link(link_frames(words), corrupt);
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  expect_same(r.words, cxx_core(words));
  ASSERT_EQ(r.status.size(), 1u);
  EXPECT_EQ(r.status[0].crc_errors, 1u);
  EXPECT_EQ(r.status[0].events_received, words.size() - 1);
  ASSERT_EQ(r.resends.size(), 1u);
  EXPECT_EQ(r.resends[0], corrupt);
}

// A flush whose number is ahead of the board's count (its last events were lost) is answered
// by a resend request, not a status.
TEST(BoardLink, AFlushAfterLostEventsAsksForThem) {
  auto words = scene_words(0.004);
  auto frames = link_frames(words);
  const size_t last = words.size() - 1;
  frames[last][6] ^= 0x01;  // every copy of the last event is corrupt: the board never has it
  sim::VirtualBoard<Vboard_ice40> board(kCpb);
  link::FrameDecoder decoder;
  Received r;
  for (const auto& f : frames) board.send(f);
  for (int guard = 0; r.resends.empty() && guard < 200000; ++guard) {
    board.run(64);
    collect(board, decoder, r);
  }
  ASSERT_EQ(r.resends.size(), 1u);
  EXPECT_EQ(r.resends[0], last);
  EXPECT_TRUE(r.status.empty());
  // The good copy and the flush again: now the status comes.
  std::vector<std::uint8_t> event, flush;
  link::append_event(event, words[last], static_cast<link::Sequence>(last));
  link::append_flush(flush, static_cast<link::Sequence>(words.size()));
  board.send(event), board.send(flush);
  for (int guard = 0; r.status.empty() && guard < 2000000; ++guard) {
    board.run(64);
    collect(board, decoder, r);
  }
  ASSERT_EQ(r.status.size(), 1u);
  EXPECT_EQ(r.status[0].events_received, words.size());
  EXPECT_EQ(r.words.labels.size(), words.size());
}

// The sensor side of the four-phase handshake, with random waits; then a flush over the
// link. The acknowledge must follow the request both ways, and every event must come back
// with its address, stamped with the board's microsecond clock.
TEST(BoardAer, FourPhaseHandshake) {
  sim::VirtualBoard<Vboard_ice40> board(kCpb);
  gen::Random rng(77);
  auto& pins = board.pins();
  struct Sent {
    int x, y, p;
    std::uint64_t cycle;
  };
  std::vector<Sent> sent;
  int external = 0;
  for (int i = 0; i < 300; ++i) {
    board.run(1 + rng.below(200));
    const bool ext = i % 50 == 49;
    const int x = static_cast<int>(rng.below(128)), y = static_cast<int>(rng.below(128)), p = static_cast<int>(rng.below(2));
    pins.aer_addr = static_cast<std::uint16_t>((ext ? 0x8000 : 0) | (y << 8) | (x << 1) | p);
    board.run(1 + rng.below(3));
    ASSERT_EQ(pins.aer_ack_n, 1) << "acknowledge before the request";
    pins.aer_req_n = 0;
    const std::uint64_t requested = board.cycles();
    int waited = 0;
    while (pins.aer_ack_n) {
      board.tick();
      ASSERT_LT(++waited, 100000) << "no acknowledge";
    }
    if (ext) {
      ++external;
    } else {
      sent.push_back({x, y, p, requested});
    }
    board.run(rng.below(5));
    pins.aer_req_n = 1;
    waited = 0;
    while (!pins.aer_ack_n) {
      board.tick();
      ASSERT_LT(++waited, 1000) << "acknowledge not released";
    }
  }
  std::vector<std::uint8_t> flush;
  link::append_flush(flush, 0);  // no events came over the link
  board.send(flush);
  link::FrameDecoder decoder;
  Received r;
  for (int guard = 0; r.status.empty() && guard < 200000; ++guard) {
    board.run(64);
    collect(board, decoder, r);
  }
  ASSERT_EQ(r.status.size(), 1u);
  EXPECT_EQ(r.status[0].external_events, static_cast<std::uint32_t>(external));
  ASSERT_EQ(r.words.labels.size(), sent.size());
  for (size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(r.words.labels[i].x, sent[i].x) << i;
    EXPECT_EQ(r.words.labels[i].y, sent[i].y) << i;
    EXPECT_EQ(r.words.labels[i].p, sent[i].p) << i;
    // Stamped within a few microseconds of the request (12 clocks a microsecond, two
    // synchronizer flops).
    EXPECT_NEAR(static_cast<double>(r.words.labels[i].t), static_cast<double>(sent[i].cycle) / 12.0, 3.0) << i;
  }
}

}  // namespace
}  // namespace evms

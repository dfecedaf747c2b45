// The board top: events over the UART link in, labels, tracks and packet summaries out,
// framed and checked; the AER receiver's four-phase handshake; tracks mode at a sensor's rate.
// Compared with the C++ core of the same build: the iCEBreaker's board stops after the climbs
// (its verdicts are hls::FilterCore<Ice40Shape>'s, its climbs frames
// hls::Core<Ice40ClimbsShape>::process_to_climbs's, completed by process_climbed); the Arty's
// holds the whole core (hls::Core<ArtyShape>).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "Vboard_arty.h"
#include "Vboard_ice40.h"
#include "hls/cluster/climbs_words.h"
#include "hls/core/configs.h"
#include "hls/core/core.h"
#include "host/backend/core_config.h"
#include "host/eval/scene_run.h"
#include "host/link/link_protocol.h"
#include "sim/virtual_board.h"
#include "tests/support/core_words.h"
#include "tests/support/scenes.h"

namespace evms {
namespace {

using S = hls::Ice40Shape;
// The boards the virtual boards are generated for (EVMS_BOARD_BUILDS).
constexpr backend::BoardOfBuild kIce40 = backend::board_of("ice40"), kArty = backend::board_of("arty");
constexpr int kCpb = static_cast<int>(kIce40.clocks_per_bit);
constexpr int kWindow = static_cast<int>(kIce40.link_fifo_depth);  // events in flight: the board's link FIFO

using Expected = test::CoreWords;

// The C++ core of build B with its board's registers; `batch_ends` gets, for each packet, the
// number of track updates before its summary.
template <class B = S>
Expected cxx_core(const std::vector<hls::EventWord>& words, std::vector<size_t>* batch_ends = nullptr) {
  test::CoreDriver<B> core(backend::core_config<B>(backend::build_default_params<B>(), {B::kMaxWidth, B::kMaxHeight}));
  for (const auto& w : words) {
    core.process(w);
    if (batch_ends) batch_ends->resize(core.out().packets.size(), core.out().tracks.size());
  }
  return core.out();
}

// The iCEBreaker board's verdicts: the C++ core of its build cut at the filter (its climbs come after).
hls::Config board_config() {
  static_assert(kIce40.cut(), "the iCEBreaker's board returns its filter's verdicts");
  return backend::core_config<S>(backend::build_default_params<S>(), {S::kMaxWidth, S::kMaxHeight});
}
Expected cxx_filter_core(const std::vector<hls::EventWord>& words) {
  Expected e;
  e.labels = test::filter_core_verdicts<S>(words, board_config());
  return e;
}

struct Received {
  Expected words;
  std::vector<link::Sequence> label_seqs;
  size_t verdict_frames = 0;  // verdict frames received
  size_t verdicts = 0;        // of the labels, those that came in verdict frames
  std::uint32_t widest_gap_in_a_frame = 0;  // us between consecutive verdicts of one frame
  std::vector<link::Sequence> resends;  // the numbers the board asked for again
  std::vector<link::Status> status;
  std::vector<link::Progress> progress;
  std::vector<hls::ClimbsWord> climbs;  // a core cut after its climbs: its climbs frames' words
  size_t climbs_events_frames = 0;      // ... of which the events' come in these frames
  std::vector<size_t> batch_ends;  // for each packet summary, the track updates received before it
  std::uint64_t bad_frames = 0;
  size_t corrupted_from = SIZE_MAX;  // run_link: the first event of the frame it corrupted
};

template <class V>
void collect(sim::VirtualBoard<V>& board, link::FrameDecoder& decoder, Received& r) {
  std::vector<std::uint8_t> bytes(board.received.begin(), board.received.end());
  board.received.clear();
  decoder.push(bytes);
  link::Frame f;
  while (decoder.next(f)) {
    switch (f.type) {
      case link::kLabel:
      case link::kVerdict: {
        const std::vector<link::NumberedLabel> labels = link::decode_labels(f);
        for (size_t k = 0; k < labels.size(); ++k) {
          if (f.type == link::kVerdict && k > 0) r.widest_gap_in_a_frame = std::max(r.widest_gap_in_a_frame, labels[k].label.t - labels[k - 1].label.t);
          r.words.labels.push_back(labels[k].label);
          r.label_seqs.push_back(labels[k].seq);
          r.verdicts += f.type == link::kVerdict;
        }
        r.verdict_frames += f.type == link::kVerdict;
        break;
      }
      case link::kTrack: r.words.tracks.push_back(link::decode_track(f)); break;
      case link::kPacket:
        r.words.packets.push_back(link::decode_packet(f));
        r.batch_ends.push_back(r.words.tracks.size());
        break;
      case link::kStatus: r.status.push_back(link::decode_status(f)); break;
      case link::kResend: r.resends.push_back(link::decode_resend(f)); break;
      case link::kProgress: r.progress.push_back(link::decode_progress(f)); break;
      case link::kClimbsHead:
      case link::kClimbsMode:
      case link::kClimbsEvents: {
        const std::vector<hls::ClimbsWord> words = link::decode_climbs(f);
        r.climbs.insert(r.climbs.end(), words.begin(), words.end());
        r.climbs_events_frames += f.type == link::kClimbsEvents;
        break;
      }
      default: break;
    }
  }
  r.bad_frames = decoder.bad_frames();
}

// Runs a board from its power-up until its first status frame (it is ready), as the host
// waits for it before it sends; `r` is then cleared.
template <class V>
void await_ready(sim::VirtualBoard<V>& board, link::FrameDecoder& decoder, Received& r) {
  for (int guard = 0; r.status.empty() && guard < 100000; ++guard) {
    board.run(64);
    collect(board, decoder, r);
  }
  ASSERT_EQ(r.status.size(), 1u) << "no status after the power-up";
  r = Received{};
}

// Events from[0] .. from[count - 1], numbered from `from`, in events frames of up to
// kBatchEntries, as the host sends them.
std::vector<std::uint8_t> events_frames(const std::vector<hls::EventWord>& words, size_t from, size_t count) {
  std::vector<std::uint8_t> bytes;
  link::append_events(bytes, std::span(words).subspan(from, count), static_cast<link::Sequence>(from));
  return bytes;
}

// Streams `words` (numbered from 0, then a flush) in events frames of up to kBatchEntries,
// keeping at most kWindow events in flight, and going back to the event the board asks for
// again, as the host does. The first frame sent from event `corrupt` on (if any) has a payload
// bit flipped on the line; r.corrupted_from is its first event. The first frames of the first
// `corrupt_resends` resends are flipped too. A board that says nothing for the host's silence
// timer (500 ms) while events are unanswered fails the run: the host would have had to wait.
template <class V = Vboard_ice40>
Received run_link(const std::vector<hls::EventWord>& words, size_t corrupt = SIZE_MAX, size_t corrupt_resends = 0) {
  sim::VirtualBoard<V> board(kCpb);
  link::FrameDecoder decoder;
  Received r;
  await_ready(board, decoder, r);
  size_t next = 0;
  bool flush_sent = false;
  size_t resends_seen = 0;
  bool corrupt_next = false;  // the next frame is a resend's first
  std::uint64_t guard = 0, quiet_clocks = 0;
  const auto silence_clocks = static_cast<std::uint64_t>(kIce40.clock_hz / 2);
  while (r.status.empty()) {
    if (!board.sending() && next < words.size() && next < r.words.labels.size() + kWindow) {
      const size_t count = std::min({static_cast<size_t>(link::kBatchEntries), words.size() - next, r.words.labels.size() + kWindow - next});
      std::vector<std::uint8_t> frames = events_frames(words, next, count);
      if (next >= corrupt || corrupt_next) {
        frames[6] ^= 0x10;
        if (next >= corrupt) r.corrupted_from = next, corrupt = SIZE_MAX;
        corrupt_next = false;
      }
      board.send(frames);
      next += count;
    } else if (!board.sending() && next == words.size() && !flush_sent) {
      std::vector<std::uint8_t> flush;
      link::append_flush(flush, static_cast<link::Sequence>(words.size()));
      board.send(flush);
      flush_sent = true;
    }
    const auto heard = [&r] { return r.words.labels.size() + r.resends.size() + r.progress.size(); };
    const size_t heard_before = heard();
    board.run(64);
    collect(board, decoder, r);
    for (; resends_seen < r.resends.size(); ++resends_seen) {
      next = r.resends[resends_seen], flush_sent = false;  // fewer than 2^16 events here
      if (corrupt_resends > 0) --corrupt_resends, corrupt_next = true;
    }
    quiet_clocks = heard() == heard_before && !board.sending() ? quiet_clocks + 64 : 0;
    if (quiet_clocks > silence_clocks) {
      ADD_FAILURE() << "the board said nothing for 500 ms with " << next - r.words.labels.size() << " events unanswered";
      break;
    }
    if (++guard > 5000000) {
      ADD_FAILURE() << "no status frame after the flush";
      break;
    }
  }
  return r;
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

// After a run_link whose line corrupted `corrupted` frames: every event reached the core once,
// in order, and came back as the C++ core's verdict.
void expect_whole_stream(std::vector<hls::EventWord> words, const Received& r, std::uint32_t corrupted) {
  const size_t events = words.size();
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  expect_same(r.words, cxx_filter_core(words));
  ASSERT_EQ(r.status.size(), 1u);
  EXPECT_EQ(r.status[0].crc_errors, corrupted);
  EXPECT_EQ(r.status[0].events_received, events);
  EXPECT_EQ(r.status[0].overruns, 0u);
}

TEST(BoardLink, EventsInLabelsOutEqualToTheCppCore) {
  auto words = scene_words(0.04);
  const Received r = run_link(words);
  ASSERT_NO_FATAL_FAILURE(expect_whole_stream(words, r, 0));
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  size_t passed = 0;
  for (const auto& l : r.words.labels) passed += l.label == hls::kLabelPassedFilter;
  EXPECT_GT(passed, r.words.labels.size() / 5) << "a scene's events pass the filter";
  EXPECT_LT(passed, r.words.labels.size()) << "some are noise";
  // The rest of the core on the host, given the board's verdicts, gives the whole core's words.
  const test::CoreWords completed = test::completed_on_the_host<S>(r.words.labels, board_config());
  expect_same(completed, cxx_core(words));
  EXPECT_EQ(r.status[0].framing_errors, 0u);
  EXPECT_EQ(r.bad_frames, 0u);
  EXPECT_TRUE(r.resends.empty());
  // The verdicts come in verdict frames, numbered in order from the reset, several to a frame
  // while the line is busy: the host's events come 32 to a frame as fast as the line takes them.
  EXPECT_EQ(r.verdicts, r.words.labels.size());
  EXPECT_LT(r.verdict_frames * 4, r.verdicts) << "more than four verdicts a frame on average";
  for (size_t i = 0; i < r.label_seqs.size(); ++i) ASSERT_EQ(r.label_seqs[i], static_cast<link::Sequence>(i)) << i;
}

// The iCEBreaker's board cuts its core after the climbs (CoreCut 1): its registers are the cut
// shape's (CutCfg*, hls::Ice40ClimbsShape, whose method has no warm seeds, as the board's
// climbs have none).
using Cut = hls::Ice40ClimbsShape;
hls::Config cut_config() {
  static_assert(kIce40.core_cut == hls::CoreCut::kClimbs, "the iCEBreaker's board stops after the climbs");
  return backend::core_config<Cut>(backend::build_default_params<Cut>(), {Cut::kMaxWidth, Cut::kMaxHeight});
}

// The climbs frames that `r`'s climbs words make; none may be broken or left open.
std::vector<hls::ClimbsFrame<Cut>> assembled_frames(const Received& r) {
  hls::ClimbsFrameAssembler<Cut> assembler;
  std::vector<hls::ClimbsFrame<Cut>> frames;
  for (const hls::ClimbsWord& w : r.climbs) {
    if (assembler.take(w)) frames.push_back(assembler.frame());
  }
  EXPECT_EQ(assembler.broken(), 0) << "climbs frames broken on a clean line";
  EXPECT_FALSE(assembler.open()) << "a climbs frame left open after the flush's status";
  return frames;
}

void expect_same_frames(const std::vector<hls::ClimbsFrame<Cut>>& got, const std::vector<hls::ClimbsFrame<Cut>>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) {
    const auto &g = got[k], &w = want[k];
    ASSERT_EQ(g.n, w.n) << "frame " << k;
    ASSERT_EQ(g.mode_count, w.mode_count) << "frame " << k;
    ASSERT_EQ(g.trace.steps, w.trace.steps) << "frame " << k;
    ASSERT_EQ(g.trace.climbs, w.trace.climbs) << "frame " << k;
    ASSERT_EQ(g.trace.modes_lost, w.trace.modes_lost) << "frame " << k;
    for (int c = 0; c < w.mode_count; ++c) {
      ASSERT_EQ(g.x[c], w.x[c]) << "frame " << k << " mode " << c;
      ASSERT_EQ(g.y[c], w.y[c]) << "frame " << k << " mode " << c;
      ASSERT_EQ(g.support[c], w.support[c]) << "frame " << k << " mode " << c;
    }
    for (int j = 0; j < w.n; ++j) ASSERT_EQ(g.first_mode[j], w.first_mode[j]) << "frame " << k << " event " << j;
  }
}

// Over the link, every verdict and every packet's climbs frame equal the C++ core cut at the
// same place, on a clean line and on one that destroys an events frame (the board asks for it
// again); and the rest of the core on the host, given them, gives the whole core's words.
TEST(BoardLinkClimbs, VerdictsAndClimbsFramesEqualTheCppCoreCutAtTheClimbs) {
  std::vector<hls::EventWord> words = scene_words(0.3);
  const hls::Config cfg = cut_config();
  for (const size_t corrupt : {SIZE_MAX, words.size() / 3}) {
    SCOPED_TRACE(corrupt == SIZE_MAX ? "a clean line" : "an events frame destroyed");
    const Received r = run_link(words, corrupt);
    std::vector<hls::EventWord> stream = words;
    hls::EventWord flush;
    flush.flush = true;
    stream.push_back(flush);
    Expected verdicts;
    verdicts.labels = test::filter_core_verdicts<Cut>(stream, cfg);
    ASSERT_NO_FATAL_FAILURE(expect_same(r.words, verdicts));
    const std::vector<hls::ClimbsFrame<Cut>> frames = assembled_frames(r);
    const std::vector<hls::ClimbsFrame<Cut>> want = test::climbs_core_frames<Cut>(stream, cfg);
    ASSERT_GE(want.size(), 8u) << "the scene closes several packets";
    ASSERT_NO_FATAL_FAILURE(expect_same_frames(frames, want));
    // The events' modes stream into frames of kBatchEntries, as the core gives a word a few
    // clocks after the last and the UART takes a byte in 30: only each packet's last is part full.
    size_t climbed_events = 0;
    for (const auto& frame : want) climbed_events += static_cast<size_t>(frame.n);
    EXPECT_LE(r.climbs_events_frames, climbed_events / link::kBatchEntries + want.size()) << climbed_events << " events' modes in " << want.size() << " packets";
    test::CoreDriver<Cut> whole(cfg);
    for (const hls::EventWord& w : stream) whole.process(w);
    ASSERT_NO_FATAL_FAILURE(expect_same(test::completed_from_climbs<Cut>(stream, r.words.labels, frames, cfg), whole.out()));
    ASSERT_EQ(r.status.size(), 1u);
    EXPECT_EQ(r.status[0].crc_errors, corrupt == SIZE_MAX ? 0u : 1u);
    EXPECT_EQ(r.status[0].events_received, words.size());
    EXPECT_EQ(r.bad_frames, 0u);
  }
}

// A quiet DVS128: noise at 300 events a second, too few for the scrub of two entries an event to
// sweep the filter's 16-bit times within half their 8.4 s wrap, with silences of 3 s (the whole
// RAM cleared) and 9 s (longer than the wrap). The time scrubber (rtl/filter/evms_ba_filter.sv)
// visits the entries owed before each event's reads, and the board's verdicts equal the C++
// filter's, which equal golden's on such streams (BaFilterAgreesWithGolden.AQuietSensors...).
TEST(BoardLink, AQuietSensorsVerdictsEqualTheCppFilterAcrossLongSilences) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<hls::EventWord> words;
  std::uint32_t t = 1000;
  for (int k = 0; k < 4000; ++k) {
    t += static_cast<std::uint32_t>(-std::log(1 - unit(rng)) / 300 * 1e6) + 1;
    if (k == 1500) t += 3'000'000;
    if (k == 2500) t += 9'000'000;
    words.push_back({t, static_cast<std::uint16_t>(rng() % 128), static_cast<std::uint16_t>(rng() % 128), static_cast<std::uint8_t>(k & 1), false});
  }
  const Received r = run_link(words);
  ASSERT_NO_FATAL_FAILURE(expect_whole_stream(words, r, 0));
  size_t passed = 0;
  for (const auto& l : r.words.labels) passed += l.label == hls::kLabelPassedFilter;
  EXPECT_GT(passed, 20u) << "the filter keeps some of the noise, so that stale times would show";
}

// An events frame and a verdict frame hold events at most kBatchGapMax us apart: a quiet
// stretch longer than that starts the next frame either way, and nothing is lost or mistimed
// across it.
TEST(BoardLink, AQuietStretchStartsTheNextFrameBothWays) {
  auto words = scene_words(0.02);
  const size_t half = words.size() / 2;
  for (size_t i = half; i < words.size(); ++i) words[i].t += 3 * link::kBatchGapMax;
  const Received r = run_link(words);
  hls::EventWord flush;
  flush.flush = true;
  words.push_back(flush);
  expect_same(r.words, cxx_filter_core(words));
  EXPECT_EQ(r.verdicts, words.size() - 1);
  EXPECT_GT(r.widest_gap_in_a_frame, 0u);
  EXPECT_LE(r.widest_gap_in_a_frame, link::kBatchGapMax);
  for (size_t i = 0; i < r.label_seqs.size(); ++i) ASSERT_EQ(r.label_seqs[i], static_cast<link::Sequence>(i)) << i;
}

// The host believes a verdict frame only in its layout: present entries first, the first at the
// frame's own time, absent entries all zeros.
TEST(BoardLink, AVerdictFrameOutOfItsLayoutIsNotBelieved) {
  const auto frame_of = [](const std::vector<std::uint32_t>& entries) {
    link::Frame f{link::kVerdict, std::vector<std::uint8_t>(static_cast<size_t>(link::kBatchHeaderBytes + link::kBatchEntries * link::kBatchEntryBytes), 0)};
    const std::uint32_t t = 1000;
    const link::Sequence seq = 65535;
    for (int b = 0; b < 4; ++b) f.payload[static_cast<size_t>(b)] = static_cast<std::uint8_t>(t >> (8 * b));
    for (int b = 0; b < 2; ++b) f.payload[static_cast<size_t>(4 + b)] = static_cast<std::uint8_t>(seq >> (8 * b));
    for (size_t k = 0; k < entries.size(); ++k) {
      for (int b = 0; b < 4; ++b) f.payload[static_cast<size_t>(link::kBatchHeaderBytes) + 4 * k + static_cast<size_t>(b)] = static_cast<std::uint8_t>(entries[k] >> (8 * b));
    }
    return f;
  };
  const auto entry = [](std::uint8_t x, std::uint8_t y, bool p, bool passed, std::uint32_t gap) {
    return link::pack_entry({x, y, static_cast<std::uint8_t>(p), passed, true, gap});
  };
  const auto two = link::decode_labels(frame_of({entry(3, 4, true, false, 0), entry(127, 126, false, true, link::kBatchGapMax)}));
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].seq, 65535);
  EXPECT_EQ(two[1].seq, 0) << "numbers wrap modulo 2^16";
  EXPECT_EQ(two[0].label.t, 1000u);
  EXPECT_EQ(two[1].label.t, 1000u + link::kBatchGapMax);
  EXPECT_EQ(two[0].label.x, 3);
  EXPECT_EQ(two[0].label.y, 4);
  EXPECT_EQ(two[0].label.p, 1);
  EXPECT_EQ(two[0].label.label, -1);
  EXPECT_EQ(two[1].label.x, 127);
  EXPECT_EQ(two[1].label.label, hls::kLabelPassedFilter);
  EXPECT_TRUE(link::decode_labels(frame_of({})).empty()) << "no verdict present";
  EXPECT_TRUE(link::decode_labels(frame_of({0, entry(1, 1, false, true, 0)})).empty()) << "a present entry after an absent one";
  EXPECT_TRUE(link::decode_labels(frame_of({entry(1, 1, false, true, 5)})).empty()) << "the first entry away from the frame's time";
  EXPECT_TRUE(link::decode_labels(frame_of({entry(1, 1, false, true, 0), 7})).empty()) << "an absent entry that is not zeros";
}

// The host believes a climbs events frame only in its layout: present entries first, absent
// entries all zeros; a present entry's 7 bits are its mode in two's complement.
TEST(BoardLink, AClimbsEventsFrameOutOfItsLayoutIsNotBelieved) {
  const auto frame_of = [](const std::vector<std::uint8_t>& entries) {
    link::Frame f{link::kClimbsEvents, std::vector<std::uint8_t>(static_cast<size_t>(link::kBatchEntries), 0)};
    std::copy(entries.begin(), entries.end(), f.payload.begin());
    return f;
  };
  const std::uint8_t present = link::kClimbsEntryPresent;
  const auto modes = link::decode_climbs(frame_of({present | 0x7F, present | 0, present | 63, present | 0x40}));
  ASSERT_EQ(modes.size(), 4u);
  const int want[] = {-1, 0, 63, -64};
  for (size_t k = 0; k < modes.size(); ++k) {
    EXPECT_EQ(modes[k].kind, hls::ClimbsWordKind::kEvent);
    EXPECT_EQ(static_cast<std::int16_t>(modes[k].top), want[k]) << k;
    EXPECT_EQ(modes[k].low, 0u);
  }
  std::vector<std::uint8_t> full(static_cast<size_t>(link::kBatchEntries), present | 5);
  EXPECT_EQ(link::decode_climbs(frame_of(full)).size(), static_cast<size_t>(link::kBatchEntries));
  EXPECT_TRUE(link::decode_climbs(frame_of({})).empty()) << "no event present";
  EXPECT_TRUE(link::decode_climbs(frame_of({0, present | 1})).empty()) << "a present entry after an absent one";
  EXPECT_TRUE(link::decode_climbs(frame_of({present | 1, 0x05})).empty()) << "an absent entry that is not zeros";
}

// A frame the line corrupts is counted and dropped, the frames after it are refused until the
// board has asked for it once, and the core sees the whole stream in order.
TEST(BoardLink, ACorruptEventFrameIsAskedForAgainAndNothingIsLost) {
  const auto words = scene_words(0.05);
  const Received r = run_link(words, words.size() / 2);
  expect_whole_stream(words, r, 1);
  ASSERT_EQ(r.resends.size(), 1u) << "frames in flight behind the corrupt one do not ask again";
  EXPECT_EQ(r.resends[0], r.corrupted_from) << "the board asks again from the corrupt frame's first event, whose entries it forgot";
}

// When the line also destroys the first frame of the resend the board asked for, the frames
// after it are ahead again, but numbered from before those the board last saw: the host has
// started over, so the board asks again at once instead of leaving the host to its silence
// timer.
TEST(BoardLink, AResendWhoseFirstFrameIsLostIsAskedForAgainAtOnce) {
  const auto words = scene_words(0.3);
  ASSERT_GT(words.size(), 64u + 2 * kWindow) << "the window fills before the flush: only the board can ask";
  const Received r = run_link(words, 64, 2);
  expect_whole_stream(words, r, 3);
  ASSERT_EQ(r.resends.size(), 3u) << "one request for the corrupt frame and one for each resend that lost its first frame";
  for (const link::Sequence seq : r.resends) EXPECT_EQ(seq, r.corrupted_from);
}

// A flush whose number is ahead of the board's count (its last events were lost) is answered
// by a resend request, not a status.
TEST(BoardLink, AFlushAfterLostEventsAsksForThem) {
  auto words = scene_words(0.004);
  const size_t last = words.size() - 5;  // the last frame: five events
  sim::VirtualBoard<Vboard_ice40> board(kCpb);
  link::FrameDecoder decoder;
  Received r;
  await_ready(board, decoder, r);
  for (size_t from = 0; from < last; from += link::kBatchEntries) board.send(events_frames(words, from, std::min<size_t>(link::kBatchEntries, last - from)));
  std::vector<std::uint8_t> lost = events_frames(words, last, 5), flush;
  lost[6] ^= 0x01;  // the line corrupts the last frame: the board never has its events
  link::append_flush(flush, static_cast<link::Sequence>(words.size()));
  board.send(lost), board.send(flush);
  for (int guard = 0; r.resends.empty() && guard < 200000; ++guard) {
    board.run(64);
    collect(board, decoder, r);
  }
  ASSERT_EQ(r.resends.size(), 1u);
  EXPECT_EQ(r.resends[0], last);
  EXPECT_TRUE(r.status.empty());
  // The good copy and the flush again: now the status comes.
  board.send(events_frames(words, last, 5)), board.send(flush);
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
  link::FrameDecoder decoder;
  Received r;
  await_ready(board, decoder, r);
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
    // Stamped within a few microseconds of the request (two synchronizer flops).
    EXPECT_NEAR(static_cast<double>(r.words.labels[i].t), static_cast<double>(sent[i].cycle) / (static_cast<double>(kIce40.clock_hz) / 1e6), 3.0) << i;
  }
}

}  // namespace
}  // namespace evms

namespace evms {
namespace {

// Tracks mode at a sensor's rate: the Arty's board (100 MHz, 2 Mbaud) takes a generated
// DVS128 scene on its AER pins at 300 k events/s of its own time. The reset frame asks it to
// keep the labels. The sensor is never kept waiting, the board labels every event, and what
// reaches the host is whole packets, each equal to the C++ core's on the events as the board
// stamped them; the packets it skipped while the line was busy are counted.
TEST(BoardTracksMode, AerAtThreeHundredThousandEventsASecondKeepsUp) {
  using A = hls::ArtyShape;
  static_assert(!kArty.cut(), "the Arty's board holds the whole core");
  constexpr int kArtyCpb = static_cast<int>(kArty.clocks_per_bit), kTicksPerUs = static_cast<int>(kArty.clock_hz / 1000000);
  constexpr double kRate = 300e3;  // events/s
  gen::SceneConfig c;
  c.motion = gen::Motion::kRotation;
  c.duration_s = 0.5;
  c.width = c.height = 128;
  const std::vector<Event> scene = eval::generate_scene(c).events;
  ASSERT_GT(scene.size(), 1000u);
  sim::VirtualBoard<Vboard_arty> board(kArtyCpb);
  link::FrameDecoder decoder;
  Received r;
  // Power-up's status, then the reset's: the board is ready and in tracks mode.
  for (int round = 0; round < 2; ++round) {
    if (round == 1) {
      std::vector<std::uint8_t> reset;
      link::append_reset(reset, link::LinkMode::kTracks);
      board.send(reset);
    }
    for (int guard = 0; r.status.size() <= static_cast<size_t>(round) && guard < 100000; ++guard) {
      board.run(64);
      collect(board, decoder, r);
    }
  }
  ASSERT_EQ(r.status.size(), 2u) << "no status after the power-up and the reset";
  r = Received{};

  // The scene's events, at kRate: its time compressed, starting 100 us from now.
  const double scale = static_cast<double>(scene.size()) / (static_cast<double>(scene.back().t - scene.front().t) * 1e-6) / kRate;
  const auto now_us = static_cast<std::uint32_t>(board.cycles() / kTicksPerUs);
  std::vector<sim::AerSender::Event> due;
  for (const Event& e : scene) {
    due.push_back({now_us + 100 + static_cast<std::uint32_t>(static_cast<double>(e.t - scene.front().t) * scale), e.x, e.y,
                   static_cast<std::uint8_t>(e.p)});
  }
  sim::AerSender sensor(due, kTicksPerUs);
  while (!sensor.done()) {
    sensor.drive(board.pins(), board.cycles());
    board.tick();
    if (board.received.size() > 256) collect(board, decoder, r);
  }
  std::vector<std::uint8_t> flush;
  link::append_flush(flush, 0);  // no events came over the link
  board.send(flush);
  for (int guard = 0; r.status.empty() && guard < 200000; ++guard) {
    board.run(64);
    collect(board, decoder, r);
  }
  ASSERT_EQ(r.status.size(), 1u) << "no status after the flush";
  const link::Status& status = r.status[0];

  const double span_s = static_cast<double>(sensor.stamp(due.size() - 1) - sensor.stamp(0)) * 1e-6;
  const double rate = static_cast<double>(due.size()) / span_s;
  std::printf("AER: %zu events over %.4f s of the board's time (%.0f events/s), the longest wait %llu us; %zu packets sent, "
              "%u skipped; %zu progress frames\n",
              due.size(), span_s, rate, static_cast<unsigned long long>(sensor.max_lag_us()), r.words.packets.size(), status.packets_skipped,
              r.progress.size());
  EXPECT_GE(rate, 100e3);
  // The board never held the sensor back: every event was requested within a few microseconds
  // of its due time (one a microsecond, so a burst waits its turn).
  EXPECT_LE(sensor.max_lag_us(), 10u);
  EXPECT_EQ(status.overruns, 0u);
  EXPECT_EQ(status.crc_errors, 0u);
  EXPECT_EQ(r.bad_frames, 0u);
  EXPECT_TRUE(r.words.labels.empty()) << "a label frame in tracks mode";
  EXPECT_EQ(static_cast<size_t>(status.labelled) + status.noise, due.size());

  std::vector<hls::EventWord> words;
  for (size_t i = 0; i < due.size(); ++i) words.push_back({sensor.stamp(i), due[i].x, due[i].y, due[i].p, false});
  hls::EventWord end;
  end.flush = true;
  words.push_back(end);
  std::vector<size_t> want_ends;
  const Expected want = cxx_core<A>(words, &want_ends);
  size_t noise = 0;
  for (const auto& l : want.labels) noise += l.label < 0;
  EXPECT_EQ(status.noise, noise);
  EXPECT_EQ(r.words.packets.size() + status.packets_skipped, want.packets.size());
  EXPECT_GT(r.words.packets.size(), want.packets.size() / 4) << "the line carried few packets";
  EXPECT_GT(status.packets_skipped, 0u) << "at this rate the line cannot carry every packet";
  // Each packet received is whole: its summary and its track updates, equal to the core's.
  size_t at = 0;
  for (size_t k = 0; k < r.words.packets.size(); ++k) {
    const hls::PacketWord& got = r.words.packets[k];
    while (at < want.packets.size() && want.packets[at].t_first != got.t_first) ++at;
    ASSERT_LT(at, want.packets.size()) << "packet " << k << " is not one of the core's, or out of order";
    EXPECT_EQ(got.t_last, want.packets[at].t_last);
    EXPECT_EQ(got.events, want.packets[at].events);
    EXPECT_EQ(got.clusters, want.packets[at].clusters);
    const size_t got_first = k == 0 ? 0 : r.batch_ends[k - 1], want_first = at == 0 ? 0 : want_ends[at - 1];
    ASSERT_EQ(r.batch_ends[k] - got_first, want_ends[at] - want_first) << "packet " << k << ": its track updates";
    for (size_t i = 0; i < r.batch_ends[k] - got_first; ++i) {
      const hls::TrackWord &g = r.words.tracks[got_first + i], &w = want.tracks[want_first + i];
      EXPECT_EQ(std::tie(g.t, g.id, g.x, g.y, g.vx, g.vy, g.zx, g.zy, g.confirmed), std::tie(w.t, w.id, w.x, w.y, w.vx, w.vy, w.zx, w.zy, w.confirmed))
          << "packet " << k << ", update " << i;
    }
  }
  // Progress frames count forward, and the last one before the flush's status is complete.
  ASSERT_FALSE(r.progress.empty());
  for (size_t i = 1; i < r.progress.size(); ++i) EXPECT_GE(r.progress[i].labelled + r.progress[i].noise, r.progress[i - 1].labelled + r.progress[i - 1].noise);
  EXPECT_EQ(r.progress.back().taken, 0u) << "no event came over the link";
}

}  // namespace
}  // namespace evms

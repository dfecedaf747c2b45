// Live sources: the USB camera decoders on byte streams built from the protocol, the bounded
// live buffer, real-time replay, and jAER AEUnicast over UDP on loopback.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "host/read/live/live_source.h"
#include "host/read/live/usb_decoders.h"
#include "tests/support/encoders.h"

namespace evms::read {
namespace {

struct Collected : DecodedSink {
  std::vector<Event> events;
  std::vector<std::string> skipped;
  void event(TimeUs t, std::uint16_t x, std::uint16_t y, std::uint8_t p) override { events.push_back({t, x, y, p}); }
  void skip(const char* kind) override { skipped.emplace_back(kind); }
};

using test::Bytes;
using test::davis_word;
using test::dvs128_event;
using test::dvs128_flag;

TEST(Dvs128Decoder, DecodesEventsWrapsResetsAndSpecialEvents) {
  Bytes b;
  dvs128_event(b, 3, 5, 1, 100);
  dvs128_flag(b, 0x80);  // wrap: +0x4000
  dvs128_event(b, 127, 0, 0, 7);
  b.insert(b.end(), {0x00, 0x80, 0x10, 0x00});  // address bit 15: a synchronisation event
  dvs128_flag(b, 0x40);  // timestamp reset: the camera's clock restarts at 0
  dvs128_event(b, 0, 127, 1, 3);
  Collected c;
  Dvs128Decoder d(c);
  d.feed(b);
  ASSERT_EQ(c.events.size(), 3u);
  EXPECT_EQ(c.events[0], (Event{100, 3, 5, 1}));
  EXPECT_EQ(c.events[1], (Event{0x4000 + 7, 127, 0, 0}));
  // Time keeps increasing across the reset: it continues from the last event.
  EXPECT_EQ(c.events[2], (Event{0x4000 + 16 + 3, 0, 127, 1}));
  EXPECT_EQ(d.resets(), 1);
  ASSERT_EQ(c.skipped.size(), 1u);
}

TEST(Dvs128Decoder, WordsSplitAcrossTransfersAreCompleted) {
  Bytes b;
  for (int i = 0; i < 50; ++i) dvs128_event(b, i, 2 * i, i & 1, 10 * i);
  Collected whole, split;
  Dvs128Decoder(whole).feed(b);
  Dvs128Decoder d(split);
  // Transfers of 1, 2, 3, ... bytes: every split position within a word occurs.
  size_t at = 0;
  for (size_t len = 1; at < b.size(); ++len) {
    const size_t n = std::min(len, b.size() - at);
    d.feed(std::span(b).subspan(at, n));
    at += n;
  }
  EXPECT_EQ(split.events, whole.events);
  EXPECT_EQ(whole.events.size(), 50u);
}

TEST(DavisDecoder, DecodesRowsColumnsWrapsResetsAndSkipsApsAndImu) {
  Bytes b;
  davis_word(b, 0x8000 | 50);        // timestamp 50
  davis_word(b, 0x1000 | 17);        // row 17
  davis_word(b, 0x3000 | 200);       // column 200, ON
  davis_word(b, 0x2000 | 201);       // column 201, OFF (same row)
  davis_word(b, 0x4000 | 0x123);     // APS sample
  davis_word(b, 0x5000 | 1);         // IMU / misc
  davis_word(b, 0x7000 | 2);         // wrap: base += 2 * 0x8000
  davis_word(b, 0x8000 | 5);         // timestamp 0x10000 + 5
  davis_word(b, 0x1000 | 179);
  davis_word(b, 0x3000 | 0);
  davis_word(b, 0x0000 | 1);         // timestamp reset
  davis_word(b, 0x8000 | 2);         // the camera's clock restarts at 2
  davis_word(b, 0x2000 | 239);
  davis_word(b, 0x0000 | 5);         // another special event
  Collected c;
  DavisDecoder d(c);
  // Fed one byte at a time: every word is split across two transfers.
  for (std::uint8_t byte : b) d.feed(std::span(&byte, 1));
  ASSERT_EQ(c.events.size(), 4u);
  EXPECT_EQ(c.events[0], (Event{50, 200, 17, 1}));
  EXPECT_EQ(c.events[1], (Event{50, 201, 17, 0}));
  EXPECT_EQ(c.events[2], (Event{0x10005, 0, 179, 1}));
  EXPECT_EQ(c.events[3], (Event{0x10005 + 2, 239, 179, 0}));
  EXPECT_EQ(d.resets(), 1);
  EXPECT_EQ(c.skipped, (std::vector<std::string>{"APS samples", "IMU and miscellaneous words", "special events"}));
}

TEST(DavisDecoder, AColumnBeforeAnyRowIsCountedNotEmitted) {
  Bytes b;
  davis_word(b, 0x3000 | 4);
  Collected c;
  DavisDecoder(c).feed(b);
  EXPECT_TRUE(c.events.empty());
  EXPECT_EQ(c.skipped.size(), 1u);
}

TEST(LiveBuffer, DropsAndCountsWhatDoesNotFitAndDeliversTheRest) {
  LiveBuffer buffer(5);
  std::vector<Event> in(8);
  for (size_t i = 0; i < in.size(); ++i) in[i].t = static_cast<TimeUs>(i);
  buffer.push(in, 42);
  buffer.close();
  std::vector<Event> out(16);
  std::vector<std::int64_t> arrival(16);
  ASSERT_EQ(buffer.pop(out, arrival), 5u);
  EXPECT_EQ(out[4].t, 4);
  EXPECT_EQ(arrival[0], 42);
  EXPECT_EQ(buffer.dropped(), 3);
  EXPECT_EQ(buffer.pop(out, arrival), 0u);
}

TEST(LiveBuffer, ReadyWithinWaitsForAnEventOrTheEndAndNoLonger) {
  LiveBuffer buffer(4);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(buffer.ready_within(20));
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(20));
  std::vector<Event> in(1);
  buffer.push(in, 1);
  EXPECT_TRUE(buffer.ready_within(0));
  std::vector<Event> out(4);
  std::vector<std::int64_t> arrival(4);
  ASSERT_EQ(buffer.pop(out, arrival), 1u);
  EXPECT_FALSE(buffer.ready_within(0));
  // A producer on another thread wakes the wait before its time is up.
  std::jthread producer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    buffer.close();
  });
  EXPECT_TRUE(buffer.ready_within(60000));
  EXPECT_EQ(buffer.pop(out, arrival), 0u);
}

TEST(LiveBuffer, AProducerFailureIsReportedAfterTheEventsBeforeIt) {
  LiveBuffer buffer(4);
  std::vector<Event> in(2);
  buffer.push(in, 1);
  buffer.fail("usb://dvs128: the DVS128 was unplugged while streaming");
  std::vector<Event> out(4);
  std::vector<std::int64_t> arrival(4);
  EXPECT_EQ(buffer.pop(out, arrival), 2u);
  EXPECT_THROW(
      {
        try {
          buffer.pop(out, arrival);
        } catch (const InputError& e) {
          EXPECT_STREQ(e.what(), "usb://dvs128: the DVS128 was unplugged while streaming");
          throw;
        }
      },
      InputError);
}

// Reads a source to its end; a live source stamps every event with its arrival time.
size_t drain(EventSource& s, std::vector<Event>* all = nullptr, bool live = true) {
  std::vector<Event> batch(1024);
  size_t total = 0;
  while (size_t n = s.read(batch)) {
    total += n;
    if (all) all->insert(all->end(), batch.begin(), batch.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_EQ(s.arrivals().size(), live ? n : 0);
  }
  return total;
}

TEST(RealtimeReplay, KeepsThePaceOfTheTimestampsTimesTheSpeed) {
  SourceOptions o;
  o.realtime = true;
  o.speed = 4;
  // 0.4 s of scene time at 4x: about 0.1 s of wall time.
  auto source = open_source("gen://translation?duration-s=0.4&seed=3", o);
  SourceOptions plain;
  auto reference = open_source("gen://translation?duration-s=0.4&seed=3", plain);
  const auto start = std::chrono::steady_clock::now();
  std::vector<Event> paced, direct;
  drain(*source, &paced);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  drain(*reference, &direct, false);
  EXPECT_EQ(paced, direct);
  EXPECT_EQ(source->dropped(), 0);
  EXPECT_GE(wall, 0.09) << "the replay ran ahead of the timestamps";
}

TEST(RealtimeReplay, StartsItsPaceWhenItsReaderFirstAsksNotWhenOpened) {
  SourceOptions o;
  o.realtime = true;
  o.live_buffer_events = 4096;
  // 0.2 s of scene time at 1x, far more events than the buffer holds: a replay that ran while
  // its reader was still being built would have dropped most of them by the first read.
  auto source = open_source("gen://translation?duration-s=0.2&seed=3", o);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a backend being built
  EXPECT_EQ(source->dropped(), 0);
  const auto start = std::chrono::steady_clock::now();
  const size_t got = drain(*source);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  SourceOptions plain;
  auto reference = open_source("gen://translation?duration-s=0.2&seed=3", plain);
  const size_t all = drain(*reference, nullptr, false);
  ASSERT_GT(all, 4 * o.live_buffer_events);
  EXPECT_EQ(got + static_cast<size_t>(source->dropped()), all);
  EXPECT_GE(wall, 0.19) << "the replay's pace did not start at the first read";
}

TEST(RealtimeReplay, ABackendThatFallsBehindLosesCountedEvents) {
  SourceOptions o;
  o.realtime = true;
  o.speed = 1000;
  o.live_buffer_events = 64;
  auto source = open_source("gen://rotation?duration-s=0.5&seed=4", o);
  std::vector<Event> first(1);
  size_t got = source->read(first);  // the replay starts
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a backend stalled while the replay ran
  got += drain(*source);
  SourceOptions plain;
  auto reference = open_source("gen://rotation?duration-s=0.5&seed=4", plain);
  const size_t all = drain(*reference, nullptr, false);
  EXPECT_GT(source->dropped(), 0);
  EXPECT_EQ(got + static_cast<size_t>(source->dropped()), all);
}

// jAER AEUnicast datagrams: BE int32 sequence number, then BE {address, timestamp} records.
Bytes aeunicast(std::uint32_t seq, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& records) {
  Bytes b;
  auto be = [&](std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
  };
  be(seq);
  for (auto [a, t] : records) be(a), be(t);
  return b;
}

int free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

TEST(UdpSource, ReceivesAeUnicastOverLoopbackAndCountsLostDatagrams) {
  const int port = free_udp_port();
  auto source = open_source("udp://127.0.0.1:" + std::to_string(port) + "?camera=dvs128&idle-s=0.5", {});
  EXPECT_EQ(source->info().sensor.width, 128);
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  auto send = [&](const Bytes& d) { ::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to); };
  // DVS128 jAER addresses: y << 8 | x << 1 | polarity.
  send(aeunicast(7, {{(5u << 8) | (3u << 1) | 1u, 100}, {(6u << 8) | (4u << 1), 110}}));
  send(aeunicast(8, {{(1u << 15), 115}}));  // an external event
  send(aeunicast(11, {{(127u << 8) | (127u << 1), 200}}));  // sequence numbers 9 and 10 were lost
  send(Bytes{1, 2, 3});                                     // not a datagram of records
  ::close(fd);
  std::vector<Event> got;
  drain(*source, &got);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], (Event{100, 3, 5, 1}));
  EXPECT_EQ(got[1], (Event{110, 4, 6, 0}));
  EXPECT_EQ(got[2], (Event{200, 127, 127, 0}));
  std::map<std::string, std::int64_t> skipped;
  for (const auto& [k, n] : source->skipped()) skipped[k] = n;
  EXPECT_EQ(skipped["lost datagrams (sequence gaps)"], 2);
  EXPECT_EQ(skipped["external events"], 1);
  EXPECT_EQ(skipped["malformed datagrams (length not 4 + 8k bytes)"], 1);
}

TEST(UdpSource, BadUrisAreOneLineErrors) {
  const std::string local = "udp://127.0.0.1:" + std::to_string(free_udp_port());
  EXPECT_THROW(open_source(local + "?camera=atis", {}), InputError);
  EXPECT_THROW(open_source(local + "?colour=red", {}), InputError);
  // An idle time that is not a finite number of seconds, or whose milliseconds overflow an int.
  for (const char* idle : {"inf", "nan", "0", "-1", "1e12", "soon"}) {
    try {
      open_source(local + "?idle-s=" + idle, {});
      ADD_FAILURE() << idle << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), local + "?idle-s=" + idle + ": 'idle-s' needs a number of seconds above 0 and at most 1000000, got '" +
                                           idle + "'");
    }
  }
  EXPECT_THROW(open_source("udp://no-such-host.invalid:8991", {}), InputError);
  // A port no sender can reach is refused, never a listener on a random port.
  for (const char* port : {":99999", ":70000", ":0", ":", ":http", ":-5"}) {
    const std::string uri = std::string("udp://0.0.0.0") + port;
    try {
      open_source(uri, {});
      ADD_FAILURE() << uri << " was accepted";
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(uri + ": port '", 0), 0u) << m;
      EXPECT_NE(m.find("is not a number from 1 to 65535"), std::string::npos) << m;
    }
  }
}

TEST(UdpSource, SaysWhereItListens) {
  const int port = free_udp_port();
  testing::internal::CaptureStderr();
  {
    auto source = open_source("udp://127.0.0.1:" + std::to_string(port) + "?idle-s=0.1", {});
  }
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("listening on 127.0.0.1:" + std::to_string(port) + " (UDP)"), std::string::npos) << said;
}

TEST(UsbCamera, NoCameraIsAClearErrorNamingTheSource) {
  try {
    auto s = open_source("usb://dvs128", {});
    GTEST_SKIP() << "a DVS128 is plugged into this machine";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("usb://dvs128: ", 0), 0u) << m;
    EXPECT_TRUE(m.find("no DVS128 camera found") != std::string::npos || m.find("libusb could not start") != std::string::npos ||
                m.find("no permission") != std::string::npos)
        << m;
  }
  EXPECT_THROW(open_source("usb://atis", {}), InputError);
}

}  // namespace
}  // namespace evms::read

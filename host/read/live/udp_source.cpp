// udp://HOST:PORT?camera=dvs128|davis[&idle-s=S]: a jAER AEUnicast stream.
//
// evms binds HOST:PORT (default port 8991) and receives datagrams of a big-endian int32
// sequence number followed by 8-byte {int32 address, int32 timestamp_us} records, the layout
// jAER's AEUnicastOutput sends by default. The addresses are jAER's (jaer_address.h) for the
// named camera; the sensor is 128x128 for dvs128 and --width/--height (default 240x180, the
// DAVIS240) for davis. A gap in the sequence numbers counts the datagrams lost in between.
// The stream ends after S seconds without a datagram when idle-s is given, else on Ctrl-C.
// The datagrams' layout is decoded by jaer_datagram.h.
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <optional>

#include "host/read/formats/jaer_address.h"
#include "host/read/live/jaer_datagram.h"
#include "host/read/live/live_source.h"
#include "host/read/uri.h"

namespace evms::read {
namespace {

constexpr size_t kDatagramMax = 65536;  // jAER sends up to 63,000 bytes

class UdpSource final : public LiveSource {
 public:
  UdpSource(const std::string& uri, const SourceOptions& o) : LiveSource(o.live_buffer_events), uri_(uri) {
    info_.name = uri;
    const SourceUri parts = split_source_uri(uri);
    std::string camera = "dvs128";
    for (const auto& [key, value] : parts.query) {
      if (key == "camera") {
        camera = value;
      } else if (key == "idle-s") {
        char* end = nullptr;
        const double s = std::strtod(value.c_str(), &end);
        // At most a million seconds: the milliseconds it becomes must fit an int.
        if (value.empty() || *end != '\0' || !(s > 0 && s <= 1e6)) {
          throw InputError(uri + ": 'idle-s' needs a number of seconds above 0 and at most 1000000, got '" + value + "'");
        }
        idle_ms_ = static_cast<int>(s * 1000);
      } else {
        throw InputError(uri + ": unknown option '" + key + "' (known: camera, idle-s)");
      }
    }
    if (camera == "dvs128") {
      layout_ = JaerLayout::kDvs128;
      info_.sensor = {128, 128};
      info_.sensor_origin = "DVS128";
    } else if (camera == "davis") {
      layout_ = JaerLayout::kDavis;
      const bool given = o.width > 0 && o.height > 0;
      info_.sensor = given ? SensorSize{o.width, o.height} : SensorSize{240, 180};
      info_.sensor_origin = given ? "--width/--height" : "DAVIS240 default";
    } else {
      throw InputError(uri + ": unknown camera '" + camera + "' (expected camera=dvs128 or camera=davis)");
    }
    info_.format = "jAER AEUnicast over UDP (" + camera + " addresses)";
    decoder_.emplace(layout_, info_.sensor);
    bind_to(parts.target);
    start();
  }

  ~UdpSource() override {
    stop();
    if (fd_ >= 0) ::close(fd_);
  }

  std::vector<std::pair<std::string, std::int64_t>> skipped() const override {
    auto s = LiveSource::skipped();
    if (lost_ > 0) s.emplace_back("lost datagrams (sequence gaps)", lost_);
    return s;
  }

 private:
  void bind_to(const std::string& authority) {
    const size_t colon = authority.rfind(':');
    const std::string host = colon == std::string::npos ? authority : authority.substr(0, colon);
    const std::string port = colon == std::string::npos ? "8991" : authority.substr(colon + 1);
    // getaddrinfo takes "99999" and "0" (any free port) without a word: a listener that no
    // sender can find.
    int number = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), number);
    if (port.empty() || ec != std::errc() || end != port.data() + port.size() || number < 1 || number > 65535) {
      throw InputError(uri_ + ": port '" + printable(port) + "' is not a number from 1 to 65535");
    }
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    hints.ai_flags = AI_PASSIVE;
    addrinfo* res = nullptr;
    if (int rc = getaddrinfo(host.empty() ? nullptr : host.c_str(), port.c_str(), &hints, &res); rc != 0) {
      throw InputError(uri_ + ": cannot resolve '" + authority + "' (" + gai_strerror(rc) + ")");
    }
    std::string why = "no address";
    for (addrinfo* a = res; a && fd_ < 0; a = a->ai_next) {
      fd_ = ::socket(a->ai_family, a->ai_socktype, a->ai_protocol);
      if (fd_ < 0) continue;
      int big = 4 << 20;
      setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &big, sizeof big);
      if (::bind(fd_, a->ai_addr, a->ai_addrlen) == 0) break;
      why = std::strerror(errno);
      ::close(fd_);
      fd_ = -1;
    }
    freeaddrinfo(res);
    if (fd_ < 0) throw InputError(uri_ + ": cannot listen on " + authority + " (" + why + ")");
    std::fprintf(stderr, "listening on %s:%s (UDP)\n", host.empty() ? "0.0.0.0" : host.c_str(), port.c_str());
  }

  void produce(std::stop_token stop) override {
    std::vector<unsigned char> datagram(kDatagramMax);
    std::vector<Event> events;
    int idle = 0;
    while (!stop.stop_requested()) {
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, 100);
      if (ready < 0 && errno != EINTR) throw InputError(uri_ + ": poll failed (" + std::strerror(errno) + ")");
      if (ready <= 0) {
        idle += 100;
        if (idle_ms_ > 0 && idle >= idle_ms_) return;
        continue;
      }
      idle = 0;
      const ssize_t n = ::recv(fd_, datagram.data(), datagram.size(), 0);
      if (n < 0) throw InputError(uri_ + ": receive failed (" + std::strerror(errno) + ")");
      const std::int64_t arrival = steady_now_ns();
      events.clear();
      decoder_->decode(std::span(datagram.data(), static_cast<size_t>(n)), events, [this](const char* kind) { count_skipped(kind); });
      lost_ = decoder_->lost();
      buffer_.push(events, arrival);
    }
  }

  std::string uri_;
  JaerLayout layout_ = JaerLayout::kDvs128;
  std::optional<JaerDatagramDecoder> decoder_;
  int fd_ = -1, idle_ms_ = 0;
  std::atomic<std::int64_t> lost_{0};
};

}  // namespace

std::unique_ptr<EventSource> open_udp_stream(const std::string& uri, const SourceOptions& o) {
  return std::make_unique<UdpSource>(uri, o);
}

}  // namespace evms::read

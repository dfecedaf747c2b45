#include "host/read/source_window.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <stdexcept>

namespace evms::read {
namespace {

class WindowedSource final : public EventSource {
 public:
  WindowedSource(std::unique_ptr<EventSource> inner, const SourceWindow& w, std::vector<std::pair<int, int>> hot)
      : inner_(std::move(inner)), window_(w), info_(inner_->info()) {
    if (w.roi) {
      const Roi& r = *w.roi;
      if (r.x + r.width > info_.sensor.width || r.y + r.height > info_.sensor.height) {
        throw std::invalid_argument("--roi " + std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.width) + "," +
                                    std::to_string(r.height) + " reaches outside the " + std::to_string(info_.sensor.width) + "x" +
                                    std::to_string(info_.sensor.height) + " sensor");
      }
      info_.sensor = {r.width, r.height};
      info_.sensor_origin += ", cropped by --roi";
    }
    const SensorSize full = inner_->info().sensor;
    full_width_ = static_cast<size_t>(full.width);
    if (!hot.empty()) masked_.assign(static_cast<size_t>(full.width) * static_cast<size_t>(full.height), false);
    for (const auto& [x, y] : hot) {
      if (x < 0 || y < 0 || x >= full.width || y >= full.height) {
        throw std::invalid_argument("--hot-pixels: pixel (" + std::to_string(x) + "," + std::to_string(y) + ") is outside the " +
                                    std::to_string(full.width) + "x" + std::to_string(full.height) + " sensor");
      }
      masked_[static_cast<size_t>(y) * static_cast<size_t>(full.width) + static_cast<size_t>(x)] = true;
    }
    hot_kind_ = "events of " + std::to_string(hot.size()) + " hot pixel" + (hot.size() == 1 ? "" : "s") + " masked";
    for (size_t i = 0; i < hot.size() && i < 8; ++i) {
      hot_kind_ += (i ? ", (" : ": (") + std::to_string(hot[i].first) + "," + std::to_string(hot[i].second) + ")";
    }
    if (hot.size() > 8) hot_kind_ += ", ...";
  }

  const SourceInfo& info() const override { return info_; }
  double progress() const override { return inner_->progress(); }
  std::int64_t reordered() const override { return inner_->reordered(); }
  std::int64_t dropped() const override { return inner_->dropped(); }
  bool ready_within(int wait_ms) override { return inner_->ready_within(wait_ms); }
  std::span<const std::int64_t> arrivals() const override { return arrivals_; }
  std::vector<std::pair<std::string, std::int64_t>> skipped() const override {
    auto s = inner_->skipped();
    if (hot_masked_) s.emplace_back(hot_kind_, hot_masked_);
    if (outside_roi_) s.emplace_back("events outside --roi", outside_roi_);
    return s;
  }

  size_t read(std::span<Event> out) override {
    arrivals_.clear();
    size_t n = 0;
    while (n == 0 && !done_) {
      buffer_.resize(out.size());
      const size_t got = inner_->read(buffer_);
      if (got == 0) {
        done_ = true;
        break;
      }
      const auto arrived = inner_->arrivals();
      for (size_t i = 0; i < got && !done_; ++i) {
        const Event& e = buffer_[i];
        if (!started_) start_ = e.t + window_.start_us, started_ = true;
        if (e.t < start_) continue;
        if (window_.duration_us > 0 && e.t >= start_ + window_.duration_us) {
          done_ = true;
          break;
        }
        if (!masked_.empty() && masked_[static_cast<size_t>(e.y) * full_width_ + e.x]) {
          ++hot_masked_;
          continue;
        }
        Event kept = e;
        if (window_.roi) {
          const Roi& r = *window_.roi;
          if (e.x < r.x || e.y < r.y || e.x >= r.x + r.width || e.y >= r.y + r.height) {
            ++outside_roi_;
            continue;
          }
          kept.x = static_cast<std::uint16_t>(e.x - r.x);
          kept.y = static_cast<std::uint16_t>(e.y - r.y);
        }
        out[n++] = kept;
        if (!arrived.empty()) arrivals_.push_back(arrived[i]);
        if (window_.limit > 0 && ++taken_ >= window_.limit) done_ = true;
      }
    }
    return n;
  }

 private:
  std::unique_ptr<EventSource> inner_;
  SourceWindow window_;
  SourceInfo info_;
  std::vector<bool> masked_;  // per pixel of the inner source's sensor
  size_t full_width_ = 0;
  std::string hot_kind_;
  std::vector<Event> buffer_;
  std::vector<std::int64_t> arrivals_;
  bool started_ = false, done_ = false;
  TimeUs start_ = 0;
  std::int64_t taken_ = 0, hot_masked_ = 0, outside_roi_ = 0;
};

std::vector<std::pair<int, int>> read_pixel_list(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, {}, "cannot open the hot-pixel list");
  std::vector<std::pair<int, int>> pixels;
  std::string line;
  for (std::uint64_t number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    int x = 0, y = 0;
    const char* end = line.data() + line.size();
    auto [p, ec] = std::from_chars(line.data(), end, x);
    if (ec == std::errc() && p != end && (*p == ',' || *p == ' ')) {
      auto [q, ec2] = std::from_chars(p + 1, end, y);
      if (ec2 == std::errc() && q == end) {
        pixels.emplace_back(x, y);
        continue;
      }
    }
    fail(path, InputPosition::line(number), "expected 'x,y', got '" + printable(line) + "'");
  }
  return pixels;
}

}  // namespace

Roi parse_roi(const std::string& text) {
  Roi r;
  int* fields[] = {&r.x, &r.y, &r.width, &r.height};
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    auto [next, ec] = std::from_chars(p, end, *fields[i]);
    if (ec != std::errc() || (i < 3 ? (next == end || *next != ',') : next != end)) {
      throw std::invalid_argument("--roi '" + printable(text) + "': expected X,Y,W,H (four whole numbers)");
    }
    p = next + 1;
  }
  if (r.x < 0 || r.y < 0 || r.width < 1 || r.height < 1) throw std::invalid_argument("--roi '" + printable(text) + "': X,Y >= 0 and W,H >= 1");
  return r;
}

std::vector<std::pair<int, int>> find_hot_pixels(EventSource& source, double factor) {
  const SensorSize s = source.info().sensor;
  std::vector<std::int64_t> count(static_cast<size_t>(s.width) * static_cast<size_t>(s.height), 0);
  std::vector<Event> batch(1 << 16);
  while (size_t n = source.read(batch)) {
    for (size_t i = 0; i < n; ++i) ++count[static_cast<size_t>(batch[i].y) * static_cast<size_t>(s.width) + batch[i].x];
  }
  std::vector<std::int64_t> active;
  for (std::int64_t c : count) {
    if (c > 0) active.push_back(c);
  }
  if (active.empty()) return {};
  std::nth_element(active.begin(), active.begin() + static_cast<long>(active.size() / 2), active.end());
  const double median = static_cast<double>(active[active.size() / 2]);
  std::vector<std::pair<std::int64_t, std::pair<int, int>>> hot;
  for (size_t i = 0; i < count.size(); ++i) {
    const int x = static_cast<int>(i % static_cast<size_t>(s.width)), y = static_cast<int>(i / static_cast<size_t>(s.width));
    // A pixel on a busy edge has busy neighbours; a hot pixel fires alone.
    double around = 0;
    int neighbours = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx || dy) && s.contains(x + dx, y + dy)) {
          around += static_cast<double>(count[static_cast<size_t>(y + dy) * static_cast<size_t>(s.width) + static_cast<size_t>(x + dx)]);
          ++neighbours;
        }
      }
    }
    if (static_cast<double>(count[i]) > factor * std::max(median, around / neighbours)) {
      hot.push_back({count[i], {static_cast<int>(i % static_cast<size_t>(s.width)), static_cast<int>(i / static_cast<size_t>(s.width))}});
    }
  }
  std::sort(hot.begin(), hot.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  std::vector<std::pair<int, int>> out;
  for (const auto& h : hot) out.push_back(h.second);
  return out;
}

std::unique_ptr<EventSource> window_source(std::unique_ptr<EventSource> source, const SourceWindow& window,
                                           const std::function<std::unique_ptr<EventSource>()>& reopen) {
  if (!window.active()) return source;
  std::vector<std::pair<int, int>> hot;
  if (window.hot_pixels == "auto") {
    if (!reopen) throw std::invalid_argument("--hot-pixels auto needs a recorded source (it reads it twice); give a list instead");
    auto first_pass = reopen();
    hot = find_hot_pixels(*first_pass, window.hot_factor);
  } else if (!window.hot_pixels.empty()) {
    hot = read_pixel_list(window.hot_pixels);
  }
  return std::make_unique<WindowedSource>(std::move(source), window, std::move(hot));
}

}  // namespace evms::read

#include "golden/cluster/mode_links.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace evms::golden {

ModeLinks::ModeLinks(SensorSize sensor) : sensor_(sensor), map_(static_cast<size_t>(sensor.width) * sensor.height, 0) {}

int ModeLinks::find(int c) {
  while (root_[static_cast<size_t>(c)] != c) c = root_[static_cast<size_t>(c)] = root_[static_cast<size_t>(root_[static_cast<size_t>(c)])];
  return c;
}

void ModeLinks::unite(int a, int b) {
  const int ra = find(a), rb = find(b);
  if (ra != rb) root_[static_cast<size_t>(std::max(ra, rb))] = std::min(ra, rb);
}

void ModeLinks::join(std::span<const Event> events, double link_px, int modes, std::vector<int>& mode_of) {
  if (modes > 0xFFFF) throw std::length_error("ModeLinks: more than 65535 modes in a packet");
  root_.resize(static_cast<size_t>(modes));
  for (int c = 0; c < modes; ++c) root_[static_cast<size_t>(c)] = c;
  if (link_px != reach_for_) {
    // Row dy of the disc spans dx with dx^2 + dy^2 <= link_px^2.
    half_width_.clear();
    for (int dy = 0; dy * dy <= link_px * link_px; ++dy) {
      int dx = 0;
      while ((dx + 1) * (dx + 1) + dy * dy <= link_px * link_px) ++dx;
      half_width_.push_back(dx);
    }
    reach_for_ = link_px;
  }
  if (++packet_ > 0xFFFF) {  // the stamps wrapped: start from a clear map
    std::fill(map_.begin(), map_.end(), 0);
    packet_ = 1;
  }
  const std::uint32_t stamp = packet_ << 16;
  const int w = sensor_.width, h = sensor_.height;
  written_.clear();
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    const auto pixel = static_cast<std::uint32_t>(events[i].y) * static_cast<std::uint32_t>(w) + events[i].x;
    std::uint32_t& p = map_[pixel];
    if ((p & 0xFFFF0000u) == stamp) unite(mode_of[i], static_cast<int>(p & 0xFFFFu));
    else written_.push_back(pixel);
    p = stamp | static_cast<std::uint32_t>(mode_of[i]);
  }
  for (const std::uint32_t pixel : written_) {
    const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(w)), y = static_cast<int>(pixel / static_cast<std::uint32_t>(w));
    const std::uint32_t own = map_[pixel];
    for (int dy = 0; dy < static_cast<int>(half_width_.size()) && y + dy < h; ++dy) {
      const int a = half_width_[static_cast<size_t>(dy)];
      const int x0 = dy == 0 ? x + 1 : std::max(0, x - a), x1 = std::min(w - 1, x + a);
      const std::uint32_t* row = &map_[static_cast<size_t>(y + dy) * static_cast<size_t>(w)];
      for (int nx = x0; nx <= x1; ++nx) {
        if ((row[nx] & 0xFFFF0000u) == stamp && row[nx] != own) unite(static_cast<int>(own & 0xFFFFu), static_cast<int>(row[nx] & 0xFFFFu));
      }
    }
  }
  for (int& c : mode_of) {
    if (c >= 0) c = find(c);
  }
}

}  // namespace evms::golden

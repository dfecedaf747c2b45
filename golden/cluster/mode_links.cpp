#include "golden/cluster/mode_links.h"

#include <algorithm>
#include <cmath>

namespace evms::golden {

ModeLinks::ModeLinks(SensorSize sensor) : sensor_(sensor), map_(static_cast<size_t>(sensor.width) * sensor.height) {}

int ModeLinks::find(int c) {
  while (root_[static_cast<size_t>(c)] != c) c = root_[static_cast<size_t>(c)] = root_[static_cast<size_t>(root_[static_cast<size_t>(c)])];
  return c;
}

void ModeLinks::unite(int a, int b) {
  const int ra = find(a), rb = find(b);
  if (ra != rb) root_[static_cast<size_t>(std::max(ra, rb))] = std::min(ra, rb);
}

void ModeLinks::join(std::span<const Event> events, double link_px, int modes, std::vector<int>& mode_of) {
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
  if (++packet_ == 0) {  // the stamps wrapped: start from a clear map
    std::fill(map_.begin(), map_.end(), Pixel{});
    packet_ = 1;
  }
  const int w = sensor_.width, h = sensor_.height;
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    Pixel& p = map_[static_cast<size_t>(events[i].y) * static_cast<size_t>(w) + events[i].x];
    if (p.written == packet_) unite(mode_of[i], p.mode);
    p.written = packet_;
    p.mode = mode_of[i];
  }
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    const int x = events[i].x, y = events[i].y;
    Pixel& own = map_[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)];
    if (own.looked == packet_) continue;  // the pixel's events are one set already
    own.looked = packet_;
    const int mode = own.mode;
    for (int dy = 0; dy < static_cast<int>(half_width_.size()) && y + dy < h; ++dy) {
      const int a = half_width_[static_cast<size_t>(dy)];
      const int x0 = dy == 0 ? x + 1 : std::max(0, x - a), x1 = std::min(w - 1, x + a);
      const Pixel* row = &map_[static_cast<size_t>(y + dy) * static_cast<size_t>(w)];
      for (int nx = x0; nx <= x1; ++nx) {
        if (row[nx].written == packet_ && row[nx].mode != mode) unite(mode, row[nx].mode);
      }
    }
  }
  for (int& c : mode_of) {
    if (c >= 0) c = find(c);
  }
}

}  // namespace evms::golden

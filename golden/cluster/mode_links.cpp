#include "golden/cluster/mode_links.h"

#include <algorithm>
#include <cmath>

namespace evms::golden {

ModeLinks::ModeLinks(SensorSize sensor)
    : sensor_(sensor), stamp_(static_cast<size_t>(sensor.width) * sensor.height, 0), read_(stamp_.size(), 0), mode_(stamp_.size(), -1) {}

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
  if (link_px != offsets_for_) {
    offsets_.clear();
    const int r = static_cast<int>(std::floor(link_px));
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        // Half the disc: of two events within reach, the one the other lies ahead of looks.
        const bool ahead = dy > 0 || (dy == 0 && dx > 0);
        if (ahead && dx * dx + dy * dy <= link_px * link_px) offsets_.emplace_back(dx, dy);
      }
    }
    offsets_for_ = link_px;
  }
  if (++packet_ == 0) {  // the stamps wrapped: start from a clear map
    std::fill(stamp_.begin(), stamp_.end(), 0);
    std::fill(read_.begin(), read_.end(), 0);
    packet_ = 1;
  }
  const int w = sensor_.width, h = sensor_.height;
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    const size_t pixel = static_cast<size_t>(events[i].y) * static_cast<size_t>(w) + events[i].x;
    if (stamp_[pixel] == packet_) unite(mode_of[i], mode_[pixel]);
    stamp_[pixel] = packet_;
    mode_[pixel] = mode_of[i];
  }
  // Every pair of events within reach meets here: two on one pixel met above (a later event
  // overwrote the pixel after joining the earlier), any others now, once a pixel.
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    const int x = events[i].x, y = events[i].y;
    const size_t own = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
    if (read_[own] == packet_) continue;
    read_[own] = packet_;
    for (const auto& [dx, dy] : offsets_) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const size_t pixel = static_cast<size_t>(ny) * static_cast<size_t>(w) + static_cast<size_t>(nx);
      if (stamp_[pixel] == packet_ && mode_[pixel] != mode_of[i]) unite(mode_of[i], mode_[pixel]);
    }
  }
  for (int& c : mode_of) {
    if (c >= 0) c = find(c);
  }
}

}  // namespace evms::golden

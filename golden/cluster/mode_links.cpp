#include "golden/cluster/mode_links.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace evms::golden {

ModeLinks::ModeLinks(SensorSize sensor)
    : sensor_(sensor),
      words_per_row_((sensor.width + 63) / 64 + 2),
      marked_(static_cast<size_t>(words_per_row_) * sensor.height, 0),
      mode_(static_cast<size_t>(sensor.width) * sensor.height, -1) {}

int ModeLinks::find(int c) {
  while (root_[static_cast<size_t>(c)] != c) c = root_[static_cast<size_t>(c)] = root_[static_cast<size_t>(root_[static_cast<size_t>(c)])];
  return c;
}

void ModeLinks::unite(int a, int b) {
  const int ra = find(a), rb = find(b);
  if (ra != rb) root_[static_cast<size_t>(std::max(ra, rb))] = std::min(ra, rb);
}

void ModeLinks::join_row(int mode, int y, int x0, int x1) {
  x0 = std::max(x0, 0), x1 = std::min(x1, sensor_.width - 1);
  const std::uint64_t* row = &marked_[static_cast<size_t>(y) * static_cast<size_t>(words_per_row_)];
  const int* modes = &mode_[static_cast<size_t>(y) * static_cast<size_t>(sensor_.width)];
  // 64 pixels at a time: bit k of `marked` is pixel x + k (bit b of word w is pixel 64 (w - 1) + b).
  for (int x = x0; x <= x1; x += 64) {
    const int len = std::min(64, x1 - x + 1), w = x / 64 + 1, off = x % 64;
    std::uint64_t marked = row[w] >> off;
    if (off > 0) marked |= row[w + 1] << (64 - off);
    if (len < 64) marked &= (std::uint64_t{1} << len) - 1;
    if (marked == 0) continue;
    // The marked pixels of another mode: most near a pixel share its mode.
    std::uint64_t other = 0;
    for (int k = 0; k < len; ++k) other |= static_cast<std::uint64_t>(modes[x + k] != mode) << k;
    for (std::uint64_t bits = marked & other; bits != 0; bits &= bits - 1) unite(mode, modes[x + std::countr_zero(bits)]);
  }
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
  const int w = sensor_.width, h = sensor_.height;
  const auto bit = [&](int x, int y) -> std::uint64_t& { return marked_[static_cast<size_t>(y) * static_cast<size_t>(words_per_row_) + static_cast<size_t>(x / 64 + 1)]; };
  written_.clear();
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    const int x = events[i].x, y = events[i].y;
    const std::uint64_t mask = std::uint64_t{1} << (x % 64);
    int& mode = mode_[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)];
    if (bit(x, y) & mask) {
      unite(mode_of[i], mode);
    } else {
      bit(x, y) |= mask;
      written_.push_back(static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(w) + static_cast<std::uint32_t>(x));
    }
    mode = mode_of[i];
  }
  for (const std::uint32_t pixel : written_) {
    const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(w)), y = static_cast<int>(pixel / static_cast<std::uint32_t>(w));
    const int mode = mode_[pixel];
    join_row(mode, y, x + 1, x + half_width_[0]);
    for (int dy = 1; dy < static_cast<int>(half_width_.size()) && y + dy < h; ++dy) {
      join_row(mode, y + dy, x - half_width_[static_cast<size_t>(dy)], x + half_width_[static_cast<size_t>(dy)]);
    }
  }
  for (const std::uint32_t pixel : written_) {
    const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(w)), y = static_cast<int>(pixel / static_cast<std::uint32_t>(w));
    bit(x, y) &= ~(std::uint64_t{1} << (x % 64));
  }
  for (int& c : mode_of) {
    if (c >= 0) c = find(c);
  }
}

}  // namespace evms::golden

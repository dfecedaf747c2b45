#include "golden/cluster/mode_links.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace evms::golden {

ModeLinks::ModeLinks(SensorSize sensor)
    : sensor_(sensor),
      words_per_row_((sensor.width + 63) / 64),
      marked_(static_cast<size_t>(words_per_row_) * sensor.height, 0),
      mode_(static_cast<size_t>(sensor.width) * sensor.height, -1),
      row_marked_(static_cast<size_t>(sensor.height), 0),
      row_words_(2 * static_cast<size_t>(sensor.height), 0) {}

void ModeLinks::collect_runs(int y) {
  const std::uint64_t* row = &marked_[static_cast<size_t>(y) * static_cast<size_t>(words_per_row_)];
  const int* modes = &mode_[static_cast<size_t>(y) * static_cast<size_t>(sensor_.width)];
  for (int w = row_words_[2 * static_cast<size_t>(y)]; w < row_words_[2 * static_cast<size_t>(y) + 1]; ++w) {
    for (std::uint64_t bits = row[w]; bits != 0; bits &= bits - 1) {
      const int x = 64 * w + std::countr_zero(bits), mode = modes[x];
      if (!runs_.empty() && runs_.back().x1 == x - 1 && runs_.back().mode == mode) {
        runs_.back().x1 = x;
      } else {
        runs_.push_back({x, x, mode});
      }
    }
  }
}

void ModeLinks::join_row(int mode, int y, int x0, int x1) {
  x0 = std::max(x0, 0), x1 = std::min(x1, sensor_.width - 1);
  const std::uint64_t* row = &marked_[static_cast<size_t>(y) * static_cast<size_t>(words_per_row_)];
  const int* modes = &mode_[static_cast<size_t>(y) * static_cast<size_t>(sensor_.width)];
  // 64 pixels at a time: bit k of `marked` is pixel x + k.
  for (int x = x0; x <= x1; x += 64) {
    const int len = std::min(64, x1 - x + 1), w = x / 64, off = x % 64;
    std::uint64_t marked = row[w] >> off;
    if (off > 0 && w + 1 < words_per_row_) marked |= row[w + 1] << (64 - off);
    if (len < 64) marked &= (std::uint64_t{1} << len) - 1;
    if (marked == 0) continue;
    // The marked pixels of another mode: most near a run share its mode.
    std::uint64_t other = 0;
    for (int k = 0; k < len; ++k) other |= static_cast<std::uint64_t>(modes[x + k] != mode) << k;
    for (std::uint64_t bits = marked & other; bits != 0; bits &= bits - 1) sets_.unite(mode, modes[x + std::countr_zero(bits)]);
  }
}

void ModeLinks::join(std::span<const Event> events, double link_px, int modes, std::vector<int>& mode_of) {
  sets_.reset(modes);
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
  const int w = sensor_.width;
  const auto word = [&](int x, int y) -> std::uint64_t& { return marked_[static_cast<size_t>(y) * static_cast<size_t>(words_per_row_) + static_cast<size_t>(x / 64)]; };
  written_.clear();
  rows_.clear();
  for (size_t i = 0; i < events.size(); ++i) {
    if (mode_of[i] < 0) continue;
    const int x = events[i].x, y = events[i].y;
    const std::uint64_t bit = std::uint64_t{1} << (x % 64);
    int& mode = mode_[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)];
    if (word(x, y) & bit) {
      sets_.unite(mode_of[i], mode);
    } else {
      word(x, y) |= bit;
      written_.push_back(static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(w) + static_cast<std::uint32_t>(x));
      int* words = &row_words_[2 * static_cast<size_t>(y)];
      if (!row_marked_[static_cast<size_t>(y)]) {
        row_marked_[static_cast<size_t>(y)] = 1, rows_.push_back(y);
        words[0] = x / 64, words[1] = x / 64 + 1;
      }
      words[0] = std::min(words[0], x / 64), words[1] = std::max(words[1], x / 64 + 1);
    }
    mode = mode_of[i];
  }
  const int h = sensor_.height;
  for (const int y : rows_) {
    runs_.clear();
    collect_runs(y);
    for (size_t k = 0; k < runs_.size(); ++k) {
      const Run& run = runs_[k];
      if (k + 1 < runs_.size() && runs_[k + 1].x0 - run.x1 <= half_width_[0] && runs_[k + 1].mode != run.mode) sets_.unite(run.mode, runs_[k + 1].mode);
      for (int dy = 1; dy < static_cast<int>(half_width_.size()) && y + dy < h; ++dy) {
        if (!row_marked_[static_cast<size_t>(y + dy)]) continue;
        const int a = half_width_[static_cast<size_t>(dy)];
        join_row(run.mode, y + dy, run.x0 - a, run.x1 + a);
      }
    }
  }
  for (const std::uint32_t pixel : written_) {
    const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(w)), y = static_cast<int>(pixel / static_cast<std::uint32_t>(w));
    word(x, y) &= ~(std::uint64_t{1} << (x % 64));
  }
  for (const int y : rows_) row_marked_[static_cast<size_t>(y)] = 0;
  for (int& c : mode_of) {
    if (c >= 0) c = sets_.find(c);
  }
}

}  // namespace evms::golden

// Clusters that touch become one (golden/cluster/clustering.cpp, link): two modes join when an
// event of one lies within the link distance (dx^2 + dy^2 <= link2, in whole pixels) of an
// event of the other. The joined set's representative is its oldest mode (union-find with the
// smaller index as the root), so the result does not depend on the order of the unions.
//
// In hardware form this is a pixel map like the filter's timestamp memory: each event writes
// its mode into its pixel, stamped with the packet's number; a pixel that already holds a mode
// of this packet joins the two. Then each pixel written reads the pixels within the link
// distance ahead of it (the rows below, and to its right in its own row) and joins its mode with
// every mode stamped there. Every pair of events within reach meets: two events on one pixel at
// the write, any others at the read, where of two pixels within reach one lies ahead of the
// other (a pixel's later events overwrote its earlier ones, but those were joined at the write;
// a pixel reads once, stamped as read).
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/core/config.h"

namespace evms::hls {

template <class S>
class ModeLinks {
 public:
  void reset() {
    for (int i = 0; i < S::kMaxWidth * S::kMaxHeight; ++i) stamp_[i] = 0, read_[i] = 0;
    packet_ = 0;
  }

  // Replaces each event's mode (first_mode, -1 for none) by the oldest mode of its set.
  void run(const PacketEvents<S>& ev, int n, int modes, const Config& cfg, std::int16_t first_mode[S::kPacketMax]) {
  roots:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= modes) break;
      parent_[c] = static_cast<std::int16_t>(c);
    }
    if (cfg.link2 != 0) {
      next_packet();
    write:
      for (int j = 0; j < S::kPacketMax; ++j) {
        if (j >= n) break;
        if (first_mode[j] < 0) continue;
        const int pixel = ev.y[j] * S::kMaxWidth + ev.x[j];
        if (stamp_[pixel] == packet_) join(first_mode[j], mode_[pixel]);
        stamp_[pixel] = packet_;
        mode_[pixel] = first_mode[j];
      }
      // The reach along row dy: the largest dx with dx^2 + dy^2 <= link2 (-1: none).
      int half_width[S::kLinkMax + 1];
    widths:
      for (int dy = 0; dy <= S::kLinkMax; ++dy) {
        half_width[dy] = -1;
        for (int dx = 0; dx <= S::kLinkMax; ++dx) {
          if (static_cast<std::uint32_t>(dx * dx + dy * dy) <= cfg.link2) half_width[dy] = dx;
        }
      }
    read:
      for (int j = 0; j < S::kPacketMax; ++j) {
        if (j >= n) break;
        if (first_mode[j] < 0) continue;
        const int own = ev.y[j] * S::kMaxWidth + ev.x[j];
        if (read_[own] == packet_) continue;
        read_[own] = packet_;
        const int mode = mode_[own];
      window:
        for (int dy = 0; dy <= S::kLinkMax; ++dy) {
          for (int dx = -S::kLinkMax; dx <= S::kLinkMax; ++dx) {
#pragma HLS PIPELINE II = 1
            if (dx > half_width[dy] || -dx > half_width[dy] || (dy == 0 && dx <= 0)) continue;
            const int x = ev.x[j] + dx, y = ev.y[j] + dy;
            if (x < 0 || x >= cfg.sensor_width || y >= cfg.sensor_height) continue;
            const int pixel = y * S::kMaxWidth + x;
            if (stamp_[pixel] == packet_ && mode_[pixel] != mode) join(mode, mode_[pixel]);
          }
        }
      }
    }
  resolve:
    for (int j = 0; j < S::kPacketMax; ++j) {
      if (j >= n) break;
      if (first_mode[j] >= 0) first_mode[j] = find(first_mode[j]);
    }
  }

 private:
  int find(int c) const {
  walk:
    for (int k = 0; k < S::kModesMax; ++k) {
      if (parent_[c] == c) break;
      c = parent_[c];
    }
    return c;
  }

  void join(int a, int b) {
    const int ra = find(a), rb = find(b);
    if (ra < rb) parent_[rb] = static_cast<std::int16_t>(ra);
    else if (rb < ra) parent_[ra] = static_cast<std::int16_t>(rb);
  }

  // A new packet number; at the wrap the stamps restart from a cleared map.
  void next_packet() {
    if (++packet_ == 0) {
      reset();
      packet_ = 1;
    }
  }

  std::uint32_t stamp_[S::kMaxWidth * S::kMaxHeight] = {};
  std::uint32_t read_[S::kMaxWidth * S::kMaxHeight] = {};   // the packet that last read around the pixel
  std::int16_t mode_[S::kMaxWidth * S::kMaxHeight] = {};
  std::int16_t parent_[S::kModesMax] = {};
  std::uint32_t packet_ = 0;
};

}  // namespace evms::hls

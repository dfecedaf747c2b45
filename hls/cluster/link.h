// Clusters that touch become one (golden/cluster/mode_links.h): two modes join when an event of
// one lies within the link distance (dx^2 + dy^2 <= link2, in whole pixels) of an event of the
// other. The joined set's representative is its oldest mode (union-find with the smaller index
// as the root), so the result does not depend on the order of the unions.
//
// In hardware form this is a one-bit-a-pixel map of the pixels the packet's events fall on, and
// beside it the mode each of those pixels holds. Each event marks its pixel and writes its mode
// there (a pixel already marked joins the two) and the pixel goes on a list. Then each listed
// pixel reads the marked pixels within the link distance ahead of it (the rows below, and to its
// right in its own row) and joins its mode with theirs: of two pixels within reach one lies
// ahead of the other, and a pixel's later events overwrote its earlier ones only after joining
// them. Last, the listed pixels are unmarked, so the map is clear for the next packet without a
// pass over the sensor.
//
// The write pass also says which events are the first of the packet on their pixel (among the
// events with a mode): each pixel once, for the pixel centre (hls/cluster/centroid.h). All the
// events with a mode on one pixel end in one set, so the pixel counts for that set's cluster.
#pragma once

#include <cstdint>

#include "hls/cluster/features.h"
#include "hls/cluster/union_find.h"
#include "hls/core/config.h"

namespace evms::hls {

template <class S>
class ModeLinks {
 public:
  void reset() {
    for (int i = 0; i < S::kMaxHeight * kWordsPerRow; ++i) marked_[i] = 0;
  }

  // Replaces each event's mode (first_mode, -1 for none) by the oldest mode of its set, and sets
  // first_on_pixel[j] when event j has a mode and no earlier event with a mode fell on its pixel
  // (with link2 == 0 there is no map: every event with a mode is first).
  void run(const PacketEvents<S>& ev, int n, int modes, const Config& cfg, std::int16_t first_mode[S::kPacketMax],
           bool first_on_pixel[S::kPacketMax]) {
  roots:
    for (int c = 0; c < S::kModesMax; ++c) {
      if (c >= modes) break;
      sets_.make_set(c);
    }
  firsts:
    for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
      if (j >= n) break;
      first_on_pixel[j] = first_mode[j] >= 0;
    }
    if (cfg.link2 != 0) {
      int listed = 0;
    write:
      for (int j = 0; j < S::kPacketMax; ++j) {
#pragma HLS PIPELINE II = 1
        if (j >= n) break;
        if (first_mode[j] < 0) continue;
        const int pixel = ev.y[j] * S::kMaxWidth + ev.x[j];
        if (is_marked(ev.x[j], ev.y[j])) {
          sets_.unite(first_mode[j], mode_[pixel]);
          first_on_pixel[j] = false;
        } else {
          mark(ev.x[j], ev.y[j], true);
          listed_[listed++] = pixel;
        }
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
      for (int k = 0; k < S::kPacketMax; ++k) {
        if (k >= listed) break;
        const int x0 = listed_[k] % S::kMaxWidth, y0 = listed_[k] / S::kMaxWidth;
        const int mode = mode_[listed_[k]];
      // Only the disc's own pixels: a build whose kLinkMax exceeds the registered distance
      // (the host build holds 8 px for wide sensors and links 4 px below 320 px) does not pay
      // for the largest window on every sensor. The rows shrink as dy grows, so the first row
      // without reach ends the window.
      window:
        for (int dy = 0; dy <= S::kLinkMax; ++dy) {
          if (half_width[dy] < 0) break;
          const int first_dx = dy == 0 ? 1 : -half_width[dy];
        row:
          for (int i = 0; i <= 2 * S::kLinkMax; ++i) {
#pragma HLS PIPELINE II = 1
            const int dx = first_dx + i;
            if (dx > half_width[dy]) break;
            const int x = x0 + dx, y = y0 + dy;
            if (x < 0 || x >= cfg.sensor_width || y >= cfg.sensor_height || !is_marked(x, y)) continue;
            const int other = mode_[y * S::kMaxWidth + x];
            if (other != mode) sets_.unite(mode, other);
          }
        }
      }
    unmark:
      for (int k = 0; k < S::kPacketMax; ++k) {
#pragma HLS PIPELINE II = 1
        if (k >= listed) break;
        mark(listed_[k] % S::kMaxWidth, listed_[k] / S::kMaxWidth, false);
      }
    }
  resolve:
    for (int j = 0; j < S::kPacketMax; ++j) {
      if (j >= n) break;
      if (first_mode[j] >= 0) first_mode[j] = static_cast<std::int16_t>(sets_.find(first_mode[j]));
    }
  }

  // After run: the oldest mode of mode c's set.
  int root(int c) { return sets_.find(c); }

 private:
  static constexpr int kWordsPerRow = (S::kMaxWidth + 63) / 64;

  bool is_marked(int x, int y) const { return (marked_[y * kWordsPerRow + x / 64] >> (x % 64)) & 1; }
  void mark(int x, int y, bool on) {
    std::uint64_t& word = marked_[y * kWordsPerRow + x / 64];
    const std::uint64_t bit = std::uint64_t{1} << (x % 64);
    word = on ? word | bit : word & ~bit;
  }

  std::uint64_t marked_[S::kMaxHeight * kWordsPerRow] = {};  // one bit a pixel: written by this packet
  std::int16_t mode_[S::kMaxWidth * S::kMaxHeight] = {};     // the mode last written there (where marked)
  std::int32_t listed_[S::kPacketMax] = {};                 // the pixels this packet marked
  UnionFind<S::kModesMax> sets_;                          // the modes' sets
};

}  // namespace evms::hls

// Clusters that touch become one: two modes join when an event of one lies within link_px of an
// event of the other (dx^2 + dy^2 <= link_px^2 in pixels). A joined set is named by its oldest
// mode (union-find with the smaller index as the root), so the result does not depend on the
// order of the joins.
//
// A packet's events are found through a bitmap of the sensor's pixels with the mode written at
// each: an event marks its pixel and writes its mode there (joining the mode already there in
// this packet); then each pixel marked looks, row by row, at the marked pixels within reach ahead
// of it (the rows below, and the pixels to its right in its own row; of two events within reach,
// one lies ahead of the other), a machine word of the bitmap at a time. The marks are cleared
// after the packet, pixel by pixel, so no packet touches more of the map than its own events.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "types/event.h"

namespace evms::golden {

class ModeLinks {
 public:
  explicit ModeLinks(SensorSize sensor);

  // Replaces each event's mode (-1 for none) by the oldest mode of its joined set.
  void join(std::span<const Event> events, double link_px, int modes, std::vector<int>& mode_of);

 private:
  int find(int c);
  void unite(int a, int b);
  // Joins `mode` with the modes of the marked pixels x0 .. x1 of row y.
  void join_row(int mode, int y, int x0, int x1);

  SensorSize sensor_;
  int words_per_row_;                 // a word of margin each side, so that no window leaves the row
  std::vector<std::uint64_t> marked_; // per pixel, one bit: written by this packet
  std::vector<int> mode_;             // per pixel: the mode written (meaningful where marked)
  std::vector<std::uint32_t> written_;  // the pixels this packet marked
  std::vector<int> root_;             // per mode
  std::vector<int> half_width_;       // per row offset dy = 0 .. r: the reach along the row
  double reach_for_ = -1;
};

}  // namespace evms::golden

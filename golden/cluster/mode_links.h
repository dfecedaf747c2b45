// Clusters that touch become one: two modes join when an event of one lies within link_px of an
// event of the other (dx^2 + dy^2 <= link_px^2 in pixels). A joined set is named by its oldest
// mode (union-find with the smaller index as the root), so the result does not depend on the
// order of the joins.
//
// The events of a packet are found through a pixel map of the sensor, each pixel stamped with
// the packet that last wrote it: an event writes its mode into its pixel (joining the mode
// already there in this packet), then each pixel written looks at the pixels within reach ahead
// of it (the rows below, and the pixels to its right in its own row): of two events within
// reach, one lies ahead of the other. The map lives across packets, so no packet clears it
// (but the one at which the 16-bit stamps wrap); a pixel is one 32-bit word, so that a row of
// the reach is one cache line.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "golden/event.h"

namespace evms::golden {

class ModeLinks {
 public:
  explicit ModeLinks(SensorSize sensor);

  // Replaces each event's mode (-1 for none) by the oldest mode of its joined set.
  void join(std::span<const Event> events, double link_px, int modes, std::vector<int>& mode_of);

 private:
  int find(int c);
  void unite(int a, int b);

  SensorSize sensor_;
  std::vector<std::uint32_t> map_;    // per pixel: the packet that last wrote it (high 16 bits), its mode (low 16)
  std::vector<std::uint32_t> written_;  // the pixels this packet wrote
  std::vector<int> root_;             // per mode
  std::vector<int> half_width_;       // per row offset dy = 0 .. r: the reach along the row
  double reach_for_ = -1;
  std::uint32_t packet_ = 0;          // 1 .. 65535
};

}  // namespace evms::golden

// Clusters that touch become one: two modes join when an event of one lies within link_px of an
// event of the other (dx^2 + dy^2 <= link_px^2 in pixels). A joined set is named by its oldest
// mode (union-find with the smaller index as the root), so the result does not depend on the
// order of the joins.
//
// The events of a packet are found through a pixel map of the sensor, each pixel stamped with
// the packet that last wrote it: an event writes its mode into its pixel (joining the mode
// already there in this packet) and reads the pixels within reach. The map lives across
// packets, so no packet clears it.
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
  std::vector<std::uint32_t> stamp_;   // per pixel: the packet that wrote it
  std::vector<std::uint32_t> read_;    // per pixel: the packet that looked around it
  std::vector<int> mode_;              // per pixel: the mode written
  std::vector<int> root_;              // per mode
  std::vector<std::pair<int, int>> offsets_;  // the pixels within reach ahead of an event
  double offsets_for_ = -1;
  std::uint32_t packet_ = 0;
};

}  // namespace evms::golden

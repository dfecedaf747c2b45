// Clusters that touch become one: two modes join when an event of one lies within link_px of an
// event of the other (dx^2 + dy^2 <= link_px^2 in pixels). A joined set is named by its oldest
// mode (union-find with the smaller index as the root), so the result does not depend on the
// order of the joins.
//
// A packet's events are drawn into a bitmap of the sensor's pixels with the mode written at each
// (two events on one pixel join there). Each row's marked pixels then form runs: consecutive
// marked pixels of one mode. Along a row, each run joins the next when the gap between them is
// within reach (a run between two others lies within reach of both). Below it, a run x0 .. x1
// reaches, in the row dy further down, the pixels x0 - a .. x1 + a (a the disc's half-width at
// dy): that window is read from the bitmap 64 pixels at a time and its marked pixels of another
// mode joined. A dense object is a few long runs a row, each read once a row below, not a disc
// around every pixel. The marks are cleared after the packet, pixel by pixel, so no packet
// touches more of the map than its own pixels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "golden/cluster/union_find.h"
#include "types/event.h"

namespace evms::golden {

class ModeLinks {
 public:
  explicit ModeLinks(SensorSize sensor);

  // Replaces each event's mode (-1 for none) by the oldest mode of its joined set.
  void join(std::span<const Event> events, double link_px, int modes, std::vector<int>& mode_of);

 private:
  struct Run {
    int x0, x1, mode;  // pixels x0 .. x1 of the row, all marked, all of this mode
  };
  // Row y's runs, appended to runs_.
  void collect_runs(int y);
  // Joins `mode` with the marked pixels of another mode among x0 .. x1 of row y.
  void join_row(int mode, int y, int x0, int x1);

  SensorSize sensor_;
  int words_per_row_;
  std::vector<std::uint64_t> marked_;   // per pixel, one bit: written by this packet
  std::vector<int> mode_;               // per pixel: the mode written (meaningful where marked)
  std::vector<std::uint32_t> written_;  // the pixels this packet marked
  std::vector<int> rows_;               // the rows this packet marked
  std::vector<std::uint8_t> row_marked_;  // per row: in rows_
  std::vector<int> row_words_;          // per row: the first and one past the last word marked (2 entries)
  std::vector<Run> runs_;               // the runs of one row
  UnionFind sets_;                      // over the modes
  std::vector<int> half_width_;         // per row offset dy = 0 .. r: the reach along the row
  double reach_for_ = -1;
};

}  // namespace evms::golden

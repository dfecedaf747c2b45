// A packet's events binned into a grid of square cells on the (x, y) features, stored cell by
// cell (compressed rows: the members of cell c are positions start[c] .. start[c + 1]) as
// structure-of-arrays. Cells are numbered row by row, so the members of a run of neighbouring
// cells in one row are one contiguous range: a kernel of reach r at m visits 2r + 1 ranges.
// Members keep packet order within their cell.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "golden/cluster/features.h"

namespace evms::golden {

class PacketGrid {
 public:
  // Bins `f` (and the events' pixel coordinates) into cells of side `cell` feature units.
  // `finite` false makes one cell that holds every event (a kernel without reach).
  void build(const FeatureMatrix& f, std::span<const Event> events, double cell, bool finite);

  int size() const { return static_cast<int>(event_.size()); }
  // The cell of a feature coordinate (negative ones in cell 0; beyond the grid, beyond it).
  long column(double fx) const { return cell(fx); }
  long row(double fy) const { return cell(fy); }

  // Calls run(begin, end) for the members of the cells within `reach` cells of (fx, fy), one
  // call a row of cells.
  template <class Run>
  void rows_near(double fx, double fy, long reach, Run&& run) const {
    const long cx = column(fx), cy = row(fy);
    const long x0 = cx - reach < 0 ? 0 : cx - reach, x1 = cx + reach >= nx_ ? nx_ - 1 : cx + reach;
    const long y0 = cy - reach < 0 ? 0 : cy - reach, y1 = cy + reach >= ny_ ? ny_ - 1 : cy + reach;
    if (x0 > x1) return;
    for (long y = y0; y <= y1; ++y) run(start_[static_cast<size_t>(y * nx_ + x0)], start_[static_cast<size_t>(y * nx_ + x1 + 1)]);
  }

  // The occupied cells, most populated first (ties: the lower cell number), each as the range
  // of its members.
  std::vector<std::pair<int, int>> cells_by_population() const;

  // Member k (a position in cell order): its event's index in the packet, its features, its pixel.
  int event(int k) const { return event_[static_cast<size_t>(k)]; }
  // The position of the packet's event i.
  int position(int i) const { return position_[static_cast<size_t>(i)]; }

  std::vector<double> fx, fy, fp, ft;        // features, in cell order
  std::vector<std::int32_t> px, py;          // pixel coordinates, in cell order

 private:
  long cell(double v) const;

  double cell_ = 1;
  long nx_ = 1, ny_ = 1;
  std::vector<int> start_;      // nx * ny + 1 entries
  std::vector<int> event_;      // cell order -> packet order
  std::vector<int> position_;   // packet order -> cell order
  std::vector<long> cell_of_;   // per packet event, while building
};

}  // namespace evms::golden

// A packet's events binned into a grid of square cells on the (x, y) features, stored cell by
// cell (compressed rows: the members of cell c are positions start[c] .. start[c + 1]) as
// structure-of-arrays. Cells are numbered row by row, so the members of a run of neighbouring
// cells in one row are one contiguous range: a kernel of reach r at m visits 2r + 1 ranges.
// Members keep packet order within their cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "golden/cluster/features.h"

namespace evms::golden {

class PacketGrid {
 public:
  // Bins `f` (and the events' pixel coordinates) into cells of side `cell` feature units.
  // `finite` false makes one cell that holds every event (a kernel without reach: rows_near
  // gives them all).
  void build(const FeatureMatrix& f, std::span<const Event> events, double cell, bool finite);

  int size() const { return static_cast<int>(event_.size()); }

  // Calls run(begin, end) for the members of the cells that the disc of radius r around
  // (fx, fy) touches, one call a row of cells: in each row, the cells between the disc's left and
  // right edges within that row's band. Every point within r is among them.
  template <class Run>
  void rows_near(double fx, double fy, double r, Run&& run) const {
    if (!finite_) {
      run(0, size());
      return;
    }
    const long y0 = std::max(0L, cell(fy - r)), y1 = std::min(ny_ - 1, cell(fy + r));
    for (long y = y0; y <= y1; ++y) {
      // The band's nearest point to fy, and the disc's half-width there (a hair wider, so
      // that rounding cannot shut out a point on the rim).
      const double band0 = static_cast<double>(y) * cell_, band1 = band0 + cell_;
      const double dy = fy < band0 ? band0 - fy : (fy > band1 ? fy - band1 : 0.0);
      const double half = std::sqrt(std::max(0.0, r * r - dy * dy)) * (1 + 1e-12) + 1e-15;
      const long x0 = std::max(0L, cell(fx - half)), x1 = std::min(nx_ - 1, cell(fx + half));
      if (x0 > x1) continue;
      run(start_[static_cast<size_t>(y * nx_ + x0)], start_[static_cast<size_t>(y * nx_ + x1 + 1)]);
    }
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

  double cell_ = 1, per_cell_ = 1;
  bool finite_ = true;
  long nx_ = 1, ny_ = 1;
  std::vector<int> start_;      // nx * ny + 1 entries
  std::vector<int> event_;      // cell order -> packet order
  std::vector<int> position_;   // packet order -> cell order
  std::vector<long> cell_of_;   // per packet event, while building
};

}  // namespace evms::golden

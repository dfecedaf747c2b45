#include "golden/cluster/packet_grid.h"

#include <algorithm>
#include <cmath>

namespace evms::golden {

long PacketGrid::cell(double v) const { return static_cast<long>(std::floor(v * per_cell_)); }

void PacketGrid::build(const FeatureMatrix& f, std::span<const Event> events, double cell, bool finite) {
  const int n = static_cast<int>(f.cols());
  cell_ = finite ? cell : 1e300;
  per_cell_ = 1 / cell_;  // cells by multiplication: monotonic in the feature, which is all rows_near needs
  finite_ = finite;
  // Features are not negative (pixels from 0), so the cells start at 0.
  double most_x = 0, most_y = 0;
  for (int i = 0; i < n; ++i) most_x = std::max(most_x, f(0, i)), most_y = std::max(most_y, f(1, i));
  nx_ = this->cell(most_x) + 1, ny_ = this->cell(most_y) + 1;
  // Counting sort by cell, stable: members keep packet order within a cell.
  start_.assign(static_cast<size_t>(nx_ * ny_ + 1), 0);
  cell_of_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    cell_of_[static_cast<size_t>(i)] = this->cell(f(1, i)) * nx_ + this->cell(f(0, i));
    ++start_[static_cast<size_t>(cell_of_[static_cast<size_t>(i)] + 1)];
  }
  for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  event_.resize(static_cast<size_t>(n));
  position_.resize(static_cast<size_t>(n));
  for (auto* v : {&fx, &fy, &fp, &ft}) v->resize(static_cast<size_t>(n));
  px.resize(static_cast<size_t>(n));
  py.resize(static_cast<size_t>(n));
  std::vector<int>& fill = event_;  // borrowed as the cells' fill counters until placed
  std::vector<int> next(start_.begin(), start_.end() - 1);
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(next[static_cast<size_t>(cell_of_[static_cast<size_t>(i)])]++);
    position_[static_cast<size_t>(i)] = static_cast<int>(k);
  }
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(position_[static_cast<size_t>(i)]);
    fill[k] = i;
    fx[k] = f(0, i), fy[k] = f(1, i), fp[k] = f(2, i), ft[k] = f(3, i);
    px[k] = events[static_cast<size_t>(i)].x, py[k] = events[static_cast<size_t>(i)].y;
  }
}

std::vector<std::pair<int, int>> PacketGrid::cells_by_population() const {
  std::vector<std::pair<int, int>> cells;
  for (size_t c = 0; c + 1 < start_.size(); ++c) {
    if (start_[c + 1] > start_[c]) cells.emplace_back(start_[c], start_[c + 1]);
  }
  std::stable_sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.second - a.first > b.second - b.first; });
  return cells;
}

}  // namespace evms::golden

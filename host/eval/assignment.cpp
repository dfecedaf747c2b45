#include "host/eval/assignment.h"

#include <cstddef>
#include <limits>

namespace evms::eval {

using std::size_t;

namespace {

// The method itself, for rows <= columns.
std::vector<int> assign_rows(const std::vector<std::vector<double>>& weight) {
  const int n = static_cast<int>(weight.size());
  const int m = n ? static_cast<int>(weight[0].size()) : 0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> u(static_cast<size_t>(n + 1)), v(static_cast<size_t>(m + 1));
  std::vector<int> p(static_cast<size_t>(m + 1), 0), way(static_cast<size_t>(m + 1), 0);
  auto cost = [&](int i, int j) { return -weight[static_cast<size_t>(i - 1)][static_cast<size_t>(j - 1)]; };
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<size_t>(m + 1), kInf);
    std::vector<bool> used(static_cast<size_t>(m + 1), false);
    do {
      used[static_cast<size_t>(j0)] = true;
      const int i0 = p[static_cast<size_t>(j0)];
      double delta = kInf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[static_cast<size_t>(j)]) continue;
        const double cur = cost(i0, j) - u[static_cast<size_t>(i0)] - v[static_cast<size_t>(j)];
        if (cur < minv[static_cast<size_t>(j)]) minv[static_cast<size_t>(j)] = cur, way[static_cast<size_t>(j)] = j0;
        if (minv[static_cast<size_t>(j)] < delta) delta = minv[static_cast<size_t>(j)], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[static_cast<size_t>(j)]) {
          u[static_cast<size_t>(p[static_cast<size_t>(j)])] += delta;
          v[static_cast<size_t>(j)] -= delta;
        } else {
          minv[static_cast<size_t>(j)] -= delta;
        }
      }
      j0 = j1;
    } while (p[static_cast<size_t>(j0)] != 0);
    do {
      const int j1 = way[static_cast<size_t>(j0)];
      p[static_cast<size_t>(j0)] = p[static_cast<size_t>(j1)];
      j0 = j1;
    } while (j0);
  }
  std::vector<int> column(static_cast<size_t>(n), -1);
  for (int j = 1; j <= m; ++j) {
    if (p[static_cast<size_t>(j)] > 0) column[static_cast<size_t>(p[static_cast<size_t>(j)] - 1)] = j - 1;
  }
  return column;
}

}  // namespace

std::vector<int> max_weight_assignment(const std::vector<std::vector<double>>& weight) {
  const size_t rows = weight.size(), columns = rows ? weight[0].size() : 0;
  if (rows <= columns) return assign_rows(weight);
  // More rows than columns: match every column to a row, on the transpose.
  std::vector<std::vector<double>> transposed(columns, std::vector<double>(rows));
  for (size_t r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns; ++c) transposed[c][r] = weight[r][c];
  }
  const std::vector<int> row_of_column = assign_rows(transposed);
  std::vector<int> column(rows, -1);
  for (size_t c = 0; c < columns; ++c) column[static_cast<size_t>(row_of_column[c])] = static_cast<int>(c);
  return column;
}

}  // namespace evms::eval

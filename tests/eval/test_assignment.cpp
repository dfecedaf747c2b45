// The one-to-one matching the metrics share (host/eval/assignment.h), against every assignment.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "host/eval/assignment.h"

namespace evms::eval {
namespace {

// The best total over every injective map of rows to columns, by trying each permutation of
// the columns and reading the first `rows` of it.
double best_total(const std::vector<std::vector<double>>& w) {
  std::vector<int> cols(w.empty() ? 0 : w[0].size());
  std::iota(cols.begin(), cols.end(), 0);
  double best = -1e300;
  do {
    double total = 0;
    for (size_t r = 0; r < w.size(); ++r) total += w[r][static_cast<size_t>(cols[r])];
    best = std::max(best, total);
  } while (std::next_permutation(cols.begin(), cols.end()));
  return best;
}

TEST(Assignment, MaxWeightAssignmentIsOptimalOnEveryRandomMatrixUpTo5x6) {
  std::mt19937 rng(20261125);
  std::uniform_int_distribution<int> weight(-20, 20);
  int checked = 0;
  for (int rows = 1; rows <= 5; ++rows) {
    for (int cols = rows; cols <= 6; ++cols) {
      for (int trial = 0; trial < 40; ++trial) {
        std::vector<std::vector<double>> w(static_cast<size_t>(rows), std::vector<double>(static_cast<size_t>(cols)));
        for (auto& row : w) for (double& x : row) x = weight(rng);  // integers: ties are common
        const std::vector<int> col = max_weight_assignment(w);
        ASSERT_EQ(col.size(), w.size());
        std::vector<bool> used(static_cast<size_t>(cols), false);
        double total = 0;
        for (size_t r = 0; r < w.size(); ++r) {
          ASSERT_GE(col[r], 0);
          ASSERT_LT(col[r], cols);
          ASSERT_FALSE(used[static_cast<size_t>(col[r])]) << "column " << col[r] << " assigned twice";
          used[static_cast<size_t>(col[r])] = true;
          total += w[r][static_cast<size_t>(col[r])];
        }
        ASSERT_DOUBLE_EQ(total, best_total(w)) << rows << "x" << cols << " trial " << trial;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 40 * (6 + 5 + 4 + 3 + 2));
}

// More rows than columns: every column is matched to a distinct row, the rest get -1, and the
// total is the best over the transposed problem's assignments.
TEST(Assignment, MoreRowsThanColumnsMatchEveryColumn) {
  std::mt19937 rng(20261126);
  std::uniform_int_distribution<int> weight(-20, 20);
  for (int columns = 1; columns <= 4; ++columns) {
    for (int rows = columns + 1; rows <= 6; ++rows) {
      for (int trial = 0; trial < 20; ++trial) {
        std::vector<std::vector<double>> w(static_cast<size_t>(rows), std::vector<double>(static_cast<size_t>(columns)));
        for (auto& row : w) for (double& x : row) x = weight(rng);
        std::vector<std::vector<double>> t(static_cast<size_t>(columns), std::vector<double>(static_cast<size_t>(rows)));
        for (int r = 0; r < rows; ++r) for (int c = 0; c < columns; ++c) t[static_cast<size_t>(c)][static_cast<size_t>(r)] = w[static_cast<size_t>(r)][static_cast<size_t>(c)];
        const std::vector<int> col = max_weight_assignment(w);
        ASSERT_EQ(col.size(), w.size());
        std::vector<bool> used(static_cast<size_t>(columns), false);
        double total = 0;
        int matched = 0;
        for (size_t r = 0; r < w.size(); ++r) {
          if (col[r] < 0) continue;
          ASSERT_LT(col[r], columns);
          ASSERT_FALSE(used[static_cast<size_t>(col[r])]) << "column " << col[r] << " assigned twice";
          used[static_cast<size_t>(col[r])] = true;
          total += w[r][static_cast<size_t>(col[r])];
          ++matched;
        }
        ASSERT_EQ(matched, columns);
        ASSERT_DOUBLE_EQ(total, best_total(t)) << rows << "x" << columns << " trial " << trial;
      }
    }
  }
}

TEST(Assignment, NoRowsGiveNoAssignment) { EXPECT_TRUE(max_weight_assignment({}).empty()); }

}  // namespace
}  // namespace evms::eval

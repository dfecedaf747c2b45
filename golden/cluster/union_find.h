// Disjoint sets over 0 .. n - 1 whose representative is the set's smallest member, so that the
// sets and their names do not depend on the order of the unions. The links (mode_links.h) join
// modes with it, the polarity split (polarity_split.h) a cluster's events.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace evms::golden {

class UnionFind {
 public:
  // Room for members 0 .. n - 1, each to be made a set of its own by make_set before use.
  void resize(int n) { root_.resize(static_cast<size_t>(n)); }
  // Every member 0 .. n - 1 a set of its own.
  void reset(int n) {
    resize(n);
    for (int i = 0; i < n; ++i) make_set(i);
  }
  void make_set(int i) { root_[static_cast<size_t>(i)] = i; }

  int find(int a) {
    while (root_[static_cast<size_t>(a)] != a) a = root_[static_cast<size_t>(a)] = root_[static_cast<size_t>(root_[static_cast<size_t>(a)])];
    return a;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) root_[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }

 private:
  std::vector<int> root_;
};

}  // namespace evms::golden

// Disjoint sets over 0 .. N - 1 whose representative is the set's smallest member, so that the
// sets and their names do not depend on the order of the unions (golden/cluster/union_find.h).
// The links (link.h) join modes with it, the polarity split (polarity_split.h) a cluster's events.
#pragma once

#include <cstdint>

namespace evms::hls {

template <int N>
class UnionFind {
  static_assert(N <= 32767, "members are 16-bit");

 public:
  void make_set(int i) { root_[i] = static_cast<std::int16_t>(i); }

  int find(int i) {
  walk:
    for (int k = 0; k < N; ++k) {
      if (root_[i] == i) break;
      root_[i] = root_[root_[i]];  // path halving: the sets stay the same
      i = root_[i];
    }
    return i;
  }

  void unite(int a, int b) {
    const int ra = find(a), rb = find(b);
    if (ra < rb) root_[rb] = static_cast<std::int16_t>(ra);
    else if (rb < ra) root_[ra] = static_cast<std::int16_t>(rb);
  }

 private:
  std::int16_t root_[N] = {};
};

}  // namespace evms::hls

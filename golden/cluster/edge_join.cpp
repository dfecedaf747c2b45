#include "golden/cluster/edge_join.h"

#include <cstdint>

namespace evms::golden {
namespace {

struct Cluster {
  int events = 0, on = 0;
  std::int64_t x = 0, y = 0;  // sums of the events' pixel coordinates
  int lean = 0;               // +1 mostly ON, -1 mostly OFF, 0 neither or too small
};

}  // namespace

void join_edges(std::span<const Event> events, const EdgeRule& rule, int clusters, std::vector<int>& cluster_of) {
  if (rule.radius2 == 0) return;
  std::vector<Cluster> cl(static_cast<size_t>(clusters));
  for (size_t j = 0; j < cluster_of.size(); ++j) {
    if (cluster_of[j] < 0) continue;
    Cluster& c = cl[static_cast<size_t>(cluster_of[j])];
    ++c.events, c.on += events[j].p, c.x += events[j].x, c.y += events[j].y;
  }
  for (Cluster& c : cl) {
    if (c.events < static_cast<int>(rule.min_events)) continue;
    const std::int64_t surplus = std::int64_t{2} * c.on - c.events;  // ON - OFF
    const std::int64_t needed = std::int64_t{rule.balance} * c.events;
    const std::int64_t scaled = surplus * (1 << kSplitFractionFrac);
    c.lean = scaled >= needed ? 1 : (-scaled >= needed ? -1 : 0);
  }
  // Each leaning cluster's nearest partner: the other lean, within the radius and the size ratio.
  std::vector<int> nearest(cl.size(), -1);
  for (size_t a = 0; a < cl.size(); ++a) {
    if (cl[a].lean == 0) continue;
    std::uint64_t best = 0;
    for (size_t b = 0; b < cl.size(); ++b) {
      if (cl[b].lean != -cl[a].lean) continue;
      if (cl[a].events > kEdgeSizeRatio * cl[b].events || cl[b].events > kEdgeSizeRatio * cl[a].events) continue;
      const std::int64_t dx = mean_sixteenths(cl[a].x, cl[a].events) - mean_sixteenths(cl[b].x, cl[b].events);
      const std::int64_t dy = mean_sixteenths(cl[a].y, cl[a].events) - mean_sixteenths(cl[b].y, cl[b].events);
      const auto d2 = static_cast<std::uint64_t>(dx * dx + dy * dy);
      if (d2 <= rule.radius2 && (nearest[a] < 0 || d2 < best)) nearest[a] = static_cast<int>(b), best = d2;
    }
  }
  std::vector<int> into(cl.size());
  for (size_t c = 0; c < cl.size(); ++c) {
    const int b = nearest[c];
    into[c] = b >= 0 && nearest[static_cast<size_t>(b)] == static_cast<int>(c) && b < static_cast<int>(c) ? b : static_cast<int>(c);
  }
  for (int& c : cluster_of) {
    if (c >= 0) c = into[static_cast<size_t>(c)];
  }
}

}  // namespace evms::golden

#include "host/eval/touching_objects.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace evms::eval {

std::vector<std::int32_t> merge_touching_objects(std::span<const Event> events, std::span<const std::int32_t> truth,
                                                 double reach_px) {
  if (events.size() != truth.size()) throw std::invalid_argument("merge_touching_objects: events and labels differ in length");
  if (!(reach_px >= 0)) throw std::invalid_argument("merge_touching_objects: the reach must be at least 0 px");
  // Dense object indices, so the union-find is a vector.
  std::unordered_map<std::int32_t, std::int32_t> index;
  std::vector<std::int32_t> label_of;
  for (std::int32_t l : truth) {
    if (l >= 0 && index.emplace(l, static_cast<std::int32_t>(label_of.size())).second) label_of.push_back(l);
  }
  std::vector<std::int32_t> parent(label_of.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  // Each pixel's objects: one event of an object per pixel is enough.
  auto key = [](std::int64_t x, std::int64_t y) { return (x << 32) | y; };
  std::unordered_map<std::int64_t, std::vector<std::int32_t>> at_pixel;
  for (size_t i = 0; i < events.size(); ++i) {
    if (truth[i] < 0) continue;
    auto& here = at_pixel[key(events[i].x, events[i].y)];
    const std::int32_t o = index[truth[i]];
    if (std::find(here.begin(), here.end(), o) == here.end()) here.push_back(o);
  }
  const auto r = static_cast<std::int64_t>(std::floor(reach_px));
  for (const auto& [k, objects] : at_pixel) {
    const std::int64_t x = k >> 32, y = k & 0xffffffff;
    for (size_t j = 1; j < objects.size(); ++j) parent[find(objects[j])] = find(objects[0]);
    for (std::int64_t dy = -r; dy <= r; ++dy) {
      for (std::int64_t dx = -r; dx <= r; ++dx) {
        if ((dx == 0 && dy == 0) || x + dx < 0 || y + dy < 0 || static_cast<double>(dx * dx + dy * dy) > reach_px * reach_px) continue;
        const auto near = at_pixel.find(key(x + dx, y + dy));
        if (near == at_pixel.end()) continue;
        for (std::int32_t o : near->second) parent[find(o)] = find(objects[0]);
      }
    }
  }
  // Each group's smallest label.
  std::vector<std::int32_t> group_label(label_of.size(), -1);
  for (size_t o = 0; o < label_of.size(); ++o) {
    std::int32_t& g = group_label[find(static_cast<std::int32_t>(o))];
    g = g < 0 ? label_of[o] : std::min(g, label_of[o]);
  }
  std::vector<std::int32_t> merged(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) merged[i] = truth[i] < 0 ? truth[i] : group_label[find(index[truth[i]])];
  return merged;
}

std::vector<std::int32_t> merge_touching_objects(std::span<const Event> events, std::span<const std::int32_t> truth,
                                                 Chunking chunking, double reach_px) {
  if (events.size() != truth.size()) throw std::invalid_argument("merge_touching_objects: events and labels differ in length");
  std::vector<std::int32_t> merged(truth.begin(), truth.end());
  for (const auto& [first, last] : chunk_ranges(events, chunking)) {
    const auto chunk = merge_touching_objects(events.subspan(first, last - first), truth.subspan(first, last - first), reach_px);
    std::copy(chunk.begin(), chunk.end(), merged.begin() + static_cast<std::ptrdiff_t>(first));
  }
  return merged;
}

}  // namespace evms::eval

#include "golden/cluster/clustering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <tuple>

#include "golden/cluster/kernel.h"
#include "golden/cluster/mean_shift.h"

namespace evms::golden {
namespace {

using Point = Eigen::Vector4d;

// The events of a packet binned into an h x h grid on (x, y). A finite kernel at m only sees
// events in m's cell and the eight around it; a Gaussian one sees every event.
class PointGrid {
 public:
  PointGrid(const FeatureMatrix& f, double h, bool finite) : f_(f), h_(h), finite_(finite) {
    const Eigen::Index n = f.cols();
    if (!finite_ || n == 0) return;
    nx_ = cell(f.row(0).maxCoeff()) + 1;
    ny_ = cell(f.row(1).maxCoeff()) + 1;
    start_.assign(static_cast<size_t>(nx_ * ny_ + 1), 0);
    for (Eigen::Index i = 0; i < n; ++i) ++start_[static_cast<size_t>(index(f(0, i), f(1, i)) + 1)];
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    members_.resize(static_cast<size_t>(n));
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (Eigen::Index i = 0; i < n; ++i) members_[static_cast<size_t>(fill[static_cast<size_t>(index(f(0, i), f(1, i)))]++)] = static_cast<int>(i);
  }

  // Calls visit(j) for every event that may lie within `reach` (at least h) of m.
  template <class Visit>
  void near(const Point& m, double reach, Visit&& visit) const {
    if (!finite_) {
      for (Eigen::Index j = 0; j < f_.cols(); ++j) visit(static_cast<int>(j));
      return;
    }
    const long cx = cell(m.x()), cy = cell(m.y()), r = static_cast<long>(std::ceil(reach / h_ - 1e-12));
    for (long y = std::max(0L, cy - r); y <= std::min(ny_ - 1, cy + r); ++y) {
      for (long x = std::max(0L, cx - r); x <= std::min(nx_ - 1, cx + r); ++x) {
        const size_t c = static_cast<size_t>(y * nx_ + x);
        for (int k = start_[c]; k < start_[c + 1]; ++k) visit(members_[static_cast<size_t>(k)]);
      }
    }
  }

  // The occupied cells, most populated first (ties: lower cell index), as lists of events.
  std::vector<std::vector<int>> cells_by_population() const {
    std::vector<std::vector<int>> cells;
    for (size_t c = 0; c + 1 < start_.size(); ++c) {
      if (start_[c + 1] > start_[c]) cells.emplace_back(members_.begin() + start_[c], members_.begin() + start_[c + 1]);
    }
    std::stable_sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
    return cells;
  }

 private:
  long cell(double v) const { return std::max(0L, static_cast<long>(std::floor(v / h_))); }
  long index(double x, double y) const { return cell(y) * nx_ + cell(x); }

  const FeatureMatrix& f_;
  double h_;
  bool finite_;
  long nx_ = 0, ny_ = 0;
  std::vector<int> start_;    // CSR: events of cell c are members_[start_[c] .. start_[c + 1])
  std::vector<int> members_;
};

struct Vote {
  int event;
  int mode;
  int count;
};

class SeededClimbs {
 public:
  SeededClimbs(const FeatureMatrix& f, std::span<const Event> events, const Params& p, double sensor_area)
      : f_(f), events_(events), p_(p), sensor_area_(sensor_area), grid_(f, p.bandwidth, kernel_is_finite(p.kernel)), reached_(static_cast<size_t>(f.cols()), false),
        first_(static_cast<size_t>(f.cols()), -1),
        steps_inside_(static_cast<size_t>(f.cols()), 0) {}

  // Climbs from `seed` to a mode with the kernel's bandwidth h (the packet's, or a warm seed's
  // own) and records the climb's votes under it.
  void climb(Point m, double h) {
    const double inv_h2 = 1.0 / (h * h);
    touched_.clear();
    int inside = 0;  // events in the ball at the climb's last step
    for (int step = 0; step < p_.max_iterations; ++step) {
      double sum_w = 0;
      inside = 0;
      Point sum = Point::Zero();
      grid_.near(m, h, [&](int j) {
        ++result_.kernel_evaluations;
        const double u = (f_.col(j) - m).squaredNorm() * inv_h2;
        if (u < 1.0) {
          ++inside;
          if (steps_inside_[static_cast<size_t>(j)]++ == 0) touched_.push_back(j);
          reached_[static_cast<size_t>(j)] = true;
        }
        const double w = kernel_profile(p_.kernel, u);
        sum_w += w;
        sum += w * f_.col(j);
      });
      ++result_.iterations;
      if (sum_w <= 0) break;  // nothing in reach: the climb stays where it is
      const Point next = sum / sum_w;
      const double move = (next - m).cwiseAbs().maxCoeff();
      m = next;
      if (move <= p_.tolerance) break;
    }
    const int mode = join_or_open(m, inside);
    for (int j : touched_) {
      if (first_[static_cast<size_t>(j)] < 0) first_[static_cast<size_t>(j)] = mode;
      votes_.push_back({j, mode, steps_inside_[static_cast<size_t>(j)]});
      steps_inside_[static_cast<size_t>(j)] = 0;
    }
  }

  void seed_from_events() {
    for (Eigen::Index i = 0; i < f_.cols(); ++i) {
      if (!reached_[static_cast<size_t>(i)]) climb(f_.col(i), p_.bandwidth);
    }
  }

  void seed_from_grid() {
    for (const std::vector<int>& cell : grid_cells()) {
      if (std::all_of(cell.begin(), cell.end(), [&](int j) { return reached_[static_cast<size_t>(j)]; })) continue;
      Point centroid = Point::Zero();
      for (int j : cell) centroid += f_.col(j);
      climb(centroid / static_cast<double>(cell.size()), p_.bandwidth);
    }
  }

  PacketClusters finish() {
    const auto n = static_cast<size_t>(f_.cols());
    std::vector<int> raw(n, -1);
    // A mode no denser than a uniform spread of the packet, times min_density, is noise.
    const double uniform = static_cast<double>(n) * M_PI * p_.bandwidth * p_.bandwidth / sensor_area_;
    if (p_.labelling == Labelling::kFirst) {
      raw = first_;
    } else if (p_.labelling == Labelling::kVotes) {
      std::sort(votes_.begin(), votes_.end(), [](const Vote& a, const Vote& b) { return std::tie(a.event, a.mode) < std::tie(b.event, b.mode); });
      std::vector<int> best(n, 0);
      for (size_t k = 0; k < votes_.size();) {
        const Vote& v = votes_[k];
        int total = 0;
        size_t e = k;
        for (; e < votes_.size() && votes_[e].event == v.event && votes_[e].mode == v.mode; ++e) total += votes_[e].count;
        const auto j = static_cast<size_t>(v.event);
        if (total > best[j]) best[j] = total, raw[j] = v.mode;  // modes ascend: ties keep the older
        k = e;
      }
    } else {
      const double reach = p_.label_reach * p_.bandwidth;
      for (size_t j = 0; j < n; ++j) {
        double best = reach * reach;
        for (size_t c = 0; c < modes_.size(); ++c) {
          const double d2 = (f_.col(static_cast<Eigen::Index>(j)) - modes_[c]).squaredNorm();
          if (d2 < best) best = d2, raw[j] = static_cast<int>(c);
        }
      }
    }
    for (int& c : raw) {
      if (c >= 0 && support_[static_cast<size_t>(c)] < p_.min_density * uniform) c = -1;
    }
    if (p_.link_px > 0) link(raw);
    if (p_.join_boxes) join_overlapping_boxes(raw);
    std::vector<int> size(modes_.size(), 0);
    for (int c : raw) {
      if (c >= 0) ++size[static_cast<size_t>(c)];
    }
    std::vector<int> renumber(modes_.size(), -1);
    for (size_t c = 0; c < modes_.size(); ++c) {
      if (size[c] >= p_.min_cluster_size && result_.count < p_.max_clusters) {
        renumber[c] = result_.count++;
        result_.modes.push_back(modes_[c]);
      }
    }
    result_.cluster_of.resize(n);
    for (size_t j = 0; j < n; ++j) result_.cluster_of[j] = raw[j] < 0 ? -1 : renumber[static_cast<size_t>(raw[j])];
    // Each cluster's spread: the RMS distance of its events from their mean, in feature units.
    std::vector<Point> mean(static_cast<size_t>(result_.count), Point::Zero());
    std::vector<double> sq(static_cast<size_t>(result_.count), 0.0), count(static_cast<size_t>(result_.count), 0.0);
    for (size_t j = 0; j < n; ++j) {
      const int c = result_.cluster_of[j];
      if (c < 0) continue;
      mean[static_cast<size_t>(c)] += f_.col(static_cast<Eigen::Index>(j));
      sq[static_cast<size_t>(c)] += f_.col(static_cast<Eigen::Index>(j)).squaredNorm();
      count[static_cast<size_t>(c)] += 1;
    }
    for (size_t c = 0; c < mean.size(); ++c) {
      const Point m = mean[c] / count[c];
      result_.spreads.push_back(std::sqrt(std::max(0.0, sq[c] / count[c] - m.squaredNorm())));
    }
    return std::move(result_);
  }

 private:
  std::vector<std::vector<int>> grid_cells() const {
    if (kernel_is_finite(p_.kernel)) return grid_.cells_by_population();
    return PointGrid(f_, p_.bandwidth, true).cells_by_population();
  }

  int join_or_open(const Point& m, int inside) {
    const double r2 = p_.merge_radius * p_.merge_radius;
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (size_t c = 0; c < modes_.size(); ++c) {
      const double d2 = (m - modes_[c]).squaredNorm();
      if (d2 <= r2 && d2 < best_d2) best = static_cast<int>(c), best_d2 = d2;
    }
    if (best >= 0) {
      support_[static_cast<size_t>(best)] = std::max(support_[static_cast<size_t>(best)], inside);
      return best;
    }
    modes_.push_back(m);
    support_.push_back(inside);
    return static_cast<int>(modes_.size()) - 1;
  }

  // Clusters with events within link_px of each other become one (union-find, the older
  // mode is the root).
  void link(std::vector<int>& raw) const {
    std::vector<int> root(modes_.size());
    for (size_t c = 0; c < root.size(); ++c) root[c] = static_cast<int>(c);
    auto find = [&](int c) {
      while (root[static_cast<size_t>(c)] != c) c = root[static_cast<size_t>(c)] = root[static_cast<size_t>(root[static_cast<size_t>(c)])];
      return c;
    };
    // Events binned into cells of link_px: a link only reaches the neighbouring cells.
    const double cell = std::max(p_.link_px, 1e-9);
    std::map<std::pair<long, long>, std::vector<int>> cells;
    for (size_t j = 0; j < raw.size(); ++j) {
      if (raw[j] >= 0) cells[{static_cast<long>(events_[j].x / cell), static_cast<long>(events_[j].y / cell)}].push_back(static_cast<int>(j));
    }
    const double r2 = p_.link_px * p_.link_px;
    for (const auto& [key, members] : cells) {
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dx = -1; dx <= 1; ++dx) {
          auto it = cells.find({key.first + dx, key.second + dy});
          if (it == cells.end()) continue;
          for (int a : members) {
            for (int b : it->second) {
              const int ca = find(raw[static_cast<size_t>(a)]), cb = find(raw[static_cast<size_t>(b)]);
              if (ca == cb) continue;
              const double ex = events_[static_cast<size_t>(a)].x - events_[static_cast<size_t>(b)].x;
              const double ey = events_[static_cast<size_t>(a)].y - events_[static_cast<size_t>(b)].y;
              if (ex * ex + ey * ey <= r2) root[static_cast<size_t>(std::max(ca, cb))] = std::min(ca, cb);
            }
          }
        }
      }
    }
    for (int& c : raw) {
      if (c >= 0) c = find(c);
    }
  }

  // Clusters whose bounding boxes overlap become one, until no two overlap.
  void join_overlapping_boxes(std::vector<int>& raw) const {
    struct Box {
      int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
      bool empty() const { return x1 < 0; }
    };
    std::vector<Box> box(modes_.size());
    for (size_t j = 0; j < raw.size(); ++j) {
      if (raw[j] < 0) continue;
      Box& b = box[static_cast<size_t>(raw[j])];
      b.x0 = std::min<int>(b.x0, events_[j].x), b.x1 = std::max<int>(b.x1, events_[j].x);
      b.y0 = std::min<int>(b.y0, events_[j].y), b.y1 = std::max<int>(b.y1, events_[j].y);
    }
    std::vector<int> into(modes_.size());
    for (size_t c = 0; c < into.size(); ++c) into[c] = static_cast<int>(c);
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t a = 0; a < box.size(); ++a) {
        for (size_t b = a + 1; b < box.size(); ++b) {
          if (box[a].empty() || box[b].empty()) continue;
          if (box[a].x0 > box[b].x1 || box[b].x0 > box[a].x1 || box[a].y0 > box[b].y1 || box[b].y0 > box[a].y1) continue;
          box[a] = {std::min(box[a].x0, box[b].x0), std::min(box[a].y0, box[b].y0), std::max(box[a].x1, box[b].x1), std::max(box[a].y1, box[b].y1)};
          box[b] = {};
          for (int& c : into) c = c == static_cast<int>(b) ? static_cast<int>(a) : c;
          changed = true;
        }
      }
    }
    for (int& c : raw) {
      if (c >= 0) c = into[static_cast<size_t>(c)];
    }
  }

  const FeatureMatrix& f_;
  std::span<const Event> events_;
  const Params& p_;
  double sensor_area_;             // of the sensor in (x, y) feature units
  PointGrid grid_;
  std::vector<bool> reached_;
  std::vector<int> first_;         // per event: the mode of the first climb that reached it
  std::vector<int> steps_inside_;  // of the current climb, per event
  std::vector<int> touched_;       // events the current climb reached
  std::vector<Vote> votes_;
  std::vector<Point> modes_;
  std::vector<int> support_;       // per mode: the most events a climb's last ball there held
  PacketClusters result_;
};

PacketClusters every_event(const FeatureMatrix& features, const Params& params) {
  const MeanShiftResult shifted = hybrid_mean_shift(features, params);
  const ModeClusters merged = merge_modes(shifted.modes, params);
  PacketClusters out;
  out.cluster_of = merged.cluster_of;
  out.count = merged.count;
  out.iterations = shifted.iterations;
  out.kernel_evaluations = shifted.kernel_evaluations;
  // A cluster's mode: the mode of its seed, the first event that opened it.
  out.modes.assign(static_cast<size_t>(merged.count), Point::Zero());
  std::vector<bool> set(static_cast<size_t>(merged.count), false);
  for (size_t i = 0; i < merged.cluster_of.size(); ++i) {
    const int c = merged.cluster_of[i];
    if (c >= 0 && !set[static_cast<size_t>(c)]) set[static_cast<size_t>(c)] = true, out.modes[static_cast<size_t>(c)] = shifted.modes.col(static_cast<Eigen::Index>(i));
  }
  return out;
}

}  // namespace

PacketClusters cluster_packet(std::span<const Event> events, const FeatureMatrix& features, const Params& params,
                              const std::vector<Eigen::Vector4d>& warm_modes, const std::vector<double>& warm_spreads,
                              double sensor_area) {
  if (params.seeding == Seeding::kEvery) return every_event(features, params);
  SeededClimbs climbs(features, events, params, sensor_area);
  if (params.warm_start) {
    for (size_t k = 0; k < warm_modes.size(); ++k) {
      const double own = k < warm_spreads.size() ? params.warm_scale * warm_spreads[k] : 0.0;
      climbs.climb(warm_modes[k], std::clamp(own, params.bandwidth, std::max(params.bandwidth, params.warm_max_bandwidth)));
    }
  }
  if (params.seeding == Seeding::kGrid) climbs.seed_from_grid();
  climbs.seed_from_events();  // after grid seeds: only events no climb reached, if any
  return climbs.finish();
}

}  // namespace evms::golden

#include "golden/cluster/seeded_climbs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "golden/cluster/kernel.h"

namespace evms::golden {

void SeededClimbs::start(const PacketGrid& grid, const Params& params, SensorSize sensor) {
  grid_ = &grid;
  p_ = &params;
  const Eigen::Vector2d px = feature_pixels(sensor, params);
  scale_x_ = px.x(), scale_y_ = px.y();
  flat2d_ = params.kernel == Kernel::kFlat && params.scale_p == 0 && params.scale_t == 0;
  const auto n = static_cast<size_t>(grid.size());
  first_climb_.assign(n, -1);
  inside_.assign(n, 0);
  climb_mode_.clear();
  votes_.clear();
  touched_.clear();
  if (params.labelling == Labelling::kVotes) steps_inside_.assign(n, 0);
  modes_.clear();
  support_.clear();
  iterations_ = 0;
  kernel_evaluations_ = 0;
}

// One step of a climb at m: the sums over the members in the ball; those within its reach (u below
// reach2_per_h2) are marked reached by this climb (and, for votes, counted).
template <bool kFlat2d, bool kCountSteps>
void SeededClimbs::step(const Eigen::Vector4d& m, double h, double reach2_per_h2, int climb, Sums& s) {
  const PacketGrid& g = *grid_;
  const Kernel kernel = p_->kernel;
  const double inv_h2 = 1.0 / (h * h);
  g.rows_near(m.x(), m.y(), h, [&](int begin, int end) {
    kernel_evaluations_ += end - begin;
    if constexpr (kFlat2d) {
      // The ball test and the exact sums first, in a loop the compiler vectorizes (the
      // pointers are restrict: the flags written do not alias the features read).
      const double* __restrict fx = g.fx.data();
      const double* __restrict fy = g.fy.data();
      const std::int32_t* __restrict px = g.px.data();
      const std::int32_t* __restrict py = g.py.data();
      std::uint8_t* __restrict inside = inside_.data();
      const double mx = m.x(), my = m.y();
      std::int64_t count = 0, sx = 0, sy = 0;
      for (int k = begin; k < end; ++k) {
        const double dx = fx[k] - mx, dy = fy[k] - my;
        const double u = (dx * dx + dy * dy) * inv_h2;
        const bool in = u < 1.0;
        inside[k] = u < reach2_per_h2;
        count += in;
        sx += in ? px[k] : 0;
        sy += in ? py[k] : 0;
      }
      s.count += count, s.x += sx, s.y += sy;
    } else {
      for (int k = begin; k < end; ++k) {
        const auto j = static_cast<size_t>(k);
        const Eigen::Vector4d f(g.fx[j], g.fy[j], g.fp[j], g.ft[j]);
        const double u = (f - m).squaredNorm() * inv_h2;
        const bool in = u < 1.0;
        inside_[j] = u < reach2_per_h2;
        const double w = kernel_profile(kernel, u);
        s.w += w;
        s.f += w * f;
        if (in) ++s.count, s.x += g.px[j], s.y += g.py[j];
      }
    }
    if constexpr (kCountSteps) {
      for (int k = begin; k < end; ++k) {
        const auto j = static_cast<size_t>(k);
        if (!inside_[j]) continue;
        if (first_climb_[j] < 0) first_climb_[j] = climb;
        if (steps_inside_[j]++ == 0) touched_.push_back(k);
      }
    } else {
      const std::uint8_t* __restrict inside = inside_.data();
      int* __restrict first = first_climb_.data();
      for (int k = begin; k < end; ++k) first[k] = inside[k] && first[k] < 0 ? climb : first[k];
    }
  });
}

Eigen::Vector4d SeededClimbs::mean_of(const Sums& s) const {
  if (p_->kernel != Kernel::kFlat) return s.f / s.w;
  // The mean pixel, as a feature the way features.cpp makes one from a pixel.
  const double n = static_cast<double>(s.count);
  return {p_->scale_xy * (static_cast<double>(s.x) / n) / scale_x_, p_->scale_xy * (static_cast<double>(s.y) / n) / scale_y_,
          s.f(2) / n, s.f(3) / n};
}

void SeededClimbs::climb(const Eigen::Vector4d& seed, double h, double reach) {
  const int id = static_cast<int>(climb_mode_.size());
  const double reach2_per_h2 = reach > 0 && reach < h ? (reach / h) * (reach / h) : 1.0;
  const bool votes = p_->labelling == Labelling::kVotes;
  Eigen::Vector4d m = seed;
  int inside = 0;  // events in the ball at the climb's last step
  for (int k = 0; k < p_->max_iterations; ++k) {
    Sums s;
    if (flat2d_ && !votes) step<true, false>(m, h, reach2_per_h2, id, s);
    else if (flat2d_) step<true, true>(m, h, reach2_per_h2, id, s);
    else if (!votes) step<false, false>(m, h, reach2_per_h2, id, s);
    else step<false, true>(m, h, reach2_per_h2, id, s);
    if (p_->kernel == Kernel::kFlat) {
      // Only the exact sums were kept on the fast path; the flat kernel's weight is the count.
      s.w = static_cast<double>(s.count);
      if (flat2d_) s.f = Eigen::Vector4d::Zero();
    }
    inside = static_cast<int>(s.count);
    ++iterations_;
    if (s.w <= 0) break;  // nothing in reach: the climb stays where it is
    const Eigen::Vector4d next = mean_of(s);
    const double move = (next - m).cwiseAbs().maxCoeff();
    m = next;
    if (move <= p_->tolerance) break;
  }
  const int mode = join_or_open(m, inside);
  climb_mode_.push_back(mode);
  if (votes) {
    for (int k : touched_) {
      votes_.push_back({k, mode, steps_inside_[static_cast<size_t>(k)]});
      steps_inside_[static_cast<size_t>(k)] = 0;
    }
    touched_.clear();
  }
}

void SeededClimbs::seed_from_events() {
  const PacketGrid& g = *grid_;
  for (int i = 0; i < g.size(); ++i) {
    const auto k = static_cast<size_t>(g.position(i));
    if (first_climb_[k] < 0) climb({g.fx[k], g.fy[k], g.fp[k], g.ft[k]}, p_->bandwidth);
  }
}

void SeededClimbs::seed_from_grid(const PacketGrid& cells) {
  for (const auto& [begin, end] : cells.cells_by_population()) {
    bool all_reached = true;
    for (int k = begin; k < end && all_reached; ++k) all_reached = first_climb_[static_cast<size_t>(grid_->position(cells.event(k)))] >= 0;
    if (all_reached) continue;
    Eigen::Vector4d centroid = Eigen::Vector4d::Zero();
    for (int k = begin; k < end; ++k) {
      const auto j = static_cast<size_t>(k);
      centroid += Eigen::Vector4d(cells.fx[j], cells.fy[j], cells.fp[j], cells.ft[j]);
    }
    climb(centroid / static_cast<double>(end - begin), p_->bandwidth);
  }
}

int SeededClimbs::join_or_open(const Eigen::Vector4d& m, int inside) {
  const double r2 = p_->merge_radius * p_->merge_radius;
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

std::vector<int> SeededClimbs::labels() const {
  const PacketGrid& g = *grid_;
  const auto n = static_cast<size_t>(g.size());
  std::vector<int> mode(n, -1);  // in packet order
  switch (p_->labelling) {
    case Labelling::kFirst:
      for (size_t i = 0; i < n; ++i) {
        const int c = first_climb_[static_cast<size_t>(g.position(static_cast<int>(i)))];
        if (c >= 0) mode[i] = climb_mode_[static_cast<size_t>(c)];
      }
      break;
    case Labelling::kVotes: {
      std::vector<Vote> votes = votes_;
      std::sort(votes.begin(), votes.end(), [](const Vote& a, const Vote& b) { return std::tie(a.member, a.mode) < std::tie(b.member, b.mode); });
      std::vector<int> best(n, 0);
      for (size_t k = 0; k < votes.size();) {
        const Vote& v = votes[k];
        int total = 0;
        size_t e = k;
        for (; e < votes.size() && votes[e].member == v.member && votes[e].mode == v.mode; ++e) total += votes[e].count;
        const auto i = static_cast<size_t>(g.event(v.member));
        if (total > best[i]) best[i] = total, mode[i] = v.mode;  // modes ascend: ties keep the older
        k = e;
      }
      break;
    }
    case Labelling::kNearest: {
      const double reach = p_->label_reach * p_->bandwidth;
      for (size_t i = 0; i < n; ++i) {
        const auto k = static_cast<size_t>(g.position(static_cast<int>(i)));
        const Eigen::Vector4d f(g.fx[k], g.fy[k], g.fp[k], g.ft[k]);
        double best = reach * reach;
        for (size_t c = 0; c < modes_.size(); ++c) {
          const double d2 = (f - modes_[c]).squaredNorm();
          if (d2 < best) best = d2, mode[i] = static_cast<int>(c);
        }
      }
      break;
    }
  }
  return mode;
}

}  // namespace evms::golden

#include "golden/cluster/motion_split.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace evms::golden {
namespace {

constexpr int kLeastClusterEvents = 200;
constexpr int kBoxMarginPx = 2;
constexpr int kMeetingPoints = 2;
constexpr double kDistanceWeight = 0.5;    // per RMS radius, against a velocity's residual of at most 1
constexpr double kNoSlopeResidual = 0.5;
constexpr int kRounds = 8;
constexpr int kLeastPartEvents = 64;
constexpr double kLeastVelocityDifference = 0.3;  // times the faster part's speed

// The parts, velocities and residual of the best round so far.
struct Best {
  double two_residual = 0;
  std::vector<int> part;
  Eigen::Vector2d velocity[2];
  int sloped_in[2] = {0, 0};
};

}  // namespace

MotionSplit::MotionSplit(const Params& params, SensorSize sensor)
    : gain_(motion_split_gain(params)), width_(sensor.width), height_(sensor.height),
      slopes_(params.motion_split > 0 ? std::optional<TimeSurfaceSlopes>(sensor) : std::nullopt) {}

bool MotionSplit::parts_of(std::span<const Event> events, std::span<const int> members, std::vector<int>& part) const {
  std::vector<int> sloped;
  double mx = 0, my = 0;
  for (int i : members) {
    if (has_slope_[i]) sloped.push_back(i);
    mx += events[i].x, my += events[i].y;
  }
  if (sloped.size() * 3 < members.size()) return false;
  mx /= static_cast<double>(members.size()), my /= static_cast<double>(members.size());
  const Eigen::Vector2d one = fit_velocity(slope_, sloped);
  double one_residual = 0;
  for (int i : sloped) one_residual += capped_misfit(slope_[i], one);

  // The first cut: across the principal axis of the events' pixels, from their second moments
  // times m^2, exact in integers (cxx = m sum x^2 - (sum x)^2, ...). With d = cxx - cyy and
  // r = |(d, 2 cxy)|, the axis at half the angle of (d, 2 cxy) is along (r + d, 2 cxy), or along
  // y when that vanishes (cxy = 0, cxx < cyy).
  const auto m = static_cast<std::int64_t>(members.size());
  std::int64_t sum_x = 0, sum_y = 0, sum_xx = 0, sum_yy = 0, sum_xy = 0;
  for (int i : members) {
    const std::int64_t x = events[i].x, y = events[i].y;
    sum_x += x, sum_y += y, sum_xx += x * x, sum_yy += y * y, sum_xy += x * y;
  }
  const std::int64_t cxx = m * sum_xx - sum_x * sum_x, cyy = m * sum_yy - sum_y * sum_y, cxy = m * sum_xy - sum_x * sum_y;
  const auto d = static_cast<double>(cxx - cyy), r = std::hypot(d, 2.0 * static_cast<double>(cxy));
  const bool along_y = cxy == 0 && cxx < cyy;
  const double ax = along_y ? 0 : (r == 0 ? 1 : r + d), ay = along_y ? 1 : 2.0 * static_cast<double>(cxy);
  // The events' mean Chebyshev distance from their centre: the scale of the distance term.
  double radius = 0;
  for (int i : members) radius += std::max(std::abs(events[i].x - mx), std::abs(events[i].y - my));
  radius = radius / static_cast<double>(m) + 1e-9;
  part.resize(members.size());
  for (size_t k = 0; k < members.size(); ++k) {
    const Event& e = events[members[k]];
    part[k] = static_cast<double>(m * e.x - sum_x) * ax + static_cast<double>(m * e.y - sum_y) * ay > 0;
  }

  Eigen::Vector2d velocity[2], centre[2];
  double two_residual = 0;
  int sloped_in[2] = {0, 0};
  std::vector<int> sloped_of[2];
  // The rounds need not settle, and their residual need not fall each round: the round of the
  // least residual is kept, its parts and the velocities that gave them.
  Best best;
  for (int round = 0; round < kRounds; ++round) {
    sloped_of[0].clear(), sloped_of[1].clear();
    centre[0] = centre[1] = Eigen::Vector2d::Zero();
    int count[2] = {0, 0};
    for (size_t k = 0; k < members.size(); ++k) {
      const int i = members[k];
      centre[part[k]] += Eigen::Vector2d(events[i].x, events[i].y), ++count[part[k]];
      if (has_slope_[i]) sloped_of[part[k]].push_back(i);
    }
    if (count[0] == 0 || count[1] == 0 || sloped_of[0].size() < 3 || sloped_of[1].size() < 3) return false;
    centre[0] /= count[0], centre[1] /= count[1];
    velocity[0] = fit_velocity(slope_, sloped_of[0]), velocity[1] = fit_velocity(slope_, sloped_of[1]);
    two_residual = 0;
    sloped_in[0] = sloped_in[1] = 0;
    bool moved = false;
    for (size_t k = 0; k < members.size(); ++k) {
      const int i = members[k];
      const Eigen::Vector2d at(events[i].x, events[i].y);
      double best = 1e300;
      int best_part = 0;
      for (int q = 0; q < 2; ++q) {
        const Eigen::Vector2d away = at - centre[q];
        const double cost = (has_slope_[i] ? capped_misfit(slope_[i], velocity[q]) : kNoSlopeResidual) +
                            kDistanceWeight * std::max(std::abs(away.x()), std::abs(away.y())) / radius;
        if (cost < best) best = cost, best_part = q;
      }
      moved = moved || best_part != part[k];
      part[k] = best_part;
      if (has_slope_[i]) two_residual += capped_misfit(slope_[i], velocity[part[k]]), ++sloped_in[part[k]];
    }
    if (round == 0 || two_residual < best.two_residual) {
      best.two_residual = two_residual, best.part = part, best.velocity[0] = velocity[0], best.velocity[1] = velocity[1];
      best.sloped_in[0] = sloped_in[0], best.sloped_in[1] = sloped_in[1];
    }
    if (!moved) break;  // the next round would fit the same parts again
  }
  two_residual = best.two_residual, part = best.part, velocity[0] = best.velocity[0], velocity[1] = best.velocity[1];
  sloped_in[0] = best.sloped_in[0], sloped_in[1] = best.sloped_in[1];
  const double faster = std::max(velocity[0].norm(), velocity[1].norm());
  if (std::ldexp(two_residual, kMotionGainFrac) > gain_ * one_residual) return false;
  if (static_cast<size_t>(std::min(sloped_in[0], sloped_in[1])) * 5 < sloped.size()) return false;
  if ((velocity[0] - velocity[1]).norm() < kLeastVelocityDifference * faster) return false;
  const auto in_second = static_cast<int>(std::count(part.begin(), part.end(), 1));
  return std::min<int>(in_second, static_cast<int>(members.size()) - in_second) >= kLeastPartEvents;
}

void MotionSplit::split(std::span<const Event> events, const FeatureMatrix& features, std::span<const Eigen::Vector2d> meeting_points,
                        std::vector<Eigen::Vector4d>& modes, std::vector<int>& cluster_of) {
  if (meeting_points.size() < static_cast<size_t>(kMeetingPoints)) return;
  const size_t n = events.size();
  const size_t clusters = modes.size();
  std::vector<std::vector<int>> members(clusters);
  for (size_t i = 0; i < n; ++i) {
    if (cluster_of[i] >= 0) members[static_cast<size_t>(cluster_of[i])].push_back(static_cast<int>(i));
  }
  // The clusters where two tracks meet.
  std::vector<size_t> looked_at;
  for (size_t c = 0; c < clusters; ++c) {
    if (members[c].size() < static_cast<size_t>(kLeastClusterEvents)) continue;
    int x0 = width_, y0 = height_, x1 = -1, y1 = -1;
    for (int i : members[c]) {
      x0 = std::min<int>(x0, events[i].x), x1 = std::max<int>(x1, events[i].x);
      y0 = std::min<int>(y0, events[i].y), y1 = std::max<int>(y1, events[i].y);
    }
    const auto held = std::count_if(meeting_points.begin(), meeting_points.end(), [&](const Eigen::Vector2d& q) {
      return q.x() >= x0 - kBoxMarginPx && q.x() <= x1 + kBoxMarginPx && q.y() >= y0 - kBoxMarginPx && q.y() <= y1 + kBoxMarginPx;
    });
    if (held >= kMeetingPoints) looked_at.push_back(c);
  }
  if (looked_at.empty()) return;

  slopes_->add(events);
  slope_.resize(n);
  has_slope_.assign(n, 0);
  for (size_t c : looked_at) {
    for (int i : members[c]) {
      const std::optional<Eigen::Vector2d> slope = slopes_->at(events[i]);
      has_slope_[i] = slope.has_value();
      if (slope) slope_[i] = *slope;
    }
  }
  std::vector<int> part;
  for (size_t c : looked_at) {
    if (!parts_of(events, members[c], part)) continue;
    Eigen::Vector4d sum[2] = {Eigen::Vector4d::Zero(), Eigen::Vector4d::Zero()};
    int count[2] = {0, 0};
    const int second = static_cast<int>(modes.size());
    for (size_t k = 0; k < members[c].size(); ++k) {
      const int i = members[c][k];
      sum[part[k]] += features.col(i), ++count[part[k]];
      if (part[k] == 1) cluster_of[i] = second;
    }
    modes[c] = sum[0] / count[0];
    modes.push_back(sum[1] / count[1]);
  }
  slopes_->clear();
}

}  // namespace evms::golden

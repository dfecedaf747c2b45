#include "golden/cluster/time_surface_slopes.h"

#include <algorithm>

#include <Eigen/Dense>

namespace evms::golden {
namespace {

constexpr int kNeighbourPx = 2;      // the plane: 5x5 pixels
constexpr int kLeastNeighbours = 6;  // events on the plane, the event's own among them

}  // namespace

Eigen::Vector2d fit_velocity(std::span<const Eigen::Vector2d> slope, std::span<const int> sloped) {
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  for (int i : sloped) normal += slope[static_cast<size_t>(i)] * slope[static_cast<size_t>(i)].transpose(), rhs += slope[static_cast<size_t>(i)];
  if (std::abs(normal.determinant()) < 1e-30) {
    // Rank one, normal = s u u^T with s its trace: its pseudo-inverse is normal / s^2.
    const double trace = normal.trace();
    return trace > 0 ? Eigen::Vector2d(normal * rhs / (trace * trace)) : Eigen::Vector2d::Zero();
  }
  return normal.ldlt().solve(rhs);
}

TimeSurfaceSlopes::TimeSurfaceSlopes(SensorSize sensor) : width_(sensor.width), height_(sensor.height) {}

void TimeSurfaceSlopes::add(std::span<const Event> events) {
  if (events.empty()) return;
  first_t_ = events.front().t;
  for (const Event& e : events) {
    PixelEvents& pixel = on_pixel_[pixel_index(e.p, e.x, e.y)];
    ++pixel.count, pixel.time_sum += e.t - first_t_;
  }
}

void TimeSurfaceSlopes::clear() {
  on_pixel_.clear();
  slopes_.clear();
}

std::optional<Eigen::Vector2d> TimeSurfaceSlopes::at(const Event& e) {
  PixelEvents& pixel = on_pixel_[pixel_index(e.p, e.x, e.y)];
  if (pixel.slope == kSlopeUnknown) {
    const std::optional<Eigen::Vector2d> slope = fit(e.p, e.x, e.y);
    pixel.slope = slope ? static_cast<int>(slopes_.size()) : kNoSlope;
    if (slope) slopes_.push_back(*slope);
  }
  if (pixel.slope < 0) return std::nullopt;
  return slopes_[static_cast<size_t>(pixel.slope)];
}

std::optional<Eigen::Vector2d> TimeSurfaceSlopes::fit(std::uint8_t polarity, int x0, int y0) const {
  // Sums over the neighbours of their offsets (px) and times after the packet's first event (us),
  // exact in integers.
  std::int64_t m = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, st = 0, sxt = 0, syt = 0;
  const int dx_lo = std::max(-kNeighbourPx, -x0), dx_hi = std::min(kNeighbourPx, width_ - 1 - x0);
  const int dy_lo = std::max(-kNeighbourPx, -y0), dy_hi = std::min(kNeighbourPx, height_ - 1 - y0);
  for (int dy = dy_lo; dy <= dy_hi; ++dy) {
    for (int dx = dx_lo; dx <= dx_hi; ++dx) {
      const auto pixel = on_pixel_.find(pixel_index(polarity, x0 + dx, y0 + dy));
      if (pixel == on_pixel_.end()) continue;  // most of a window: an edge is a line through it
      const std::int64_t count = pixel->second.count, times = pixel->second.time_sum;
      m += count, sx += dx * count, sy += dy * count, sxx += dx * dx * count, syy += dy * dy * count, sxy += dx * dy * count;
      st += times, sxt += dx * times, syt += dy * times;
    }
  }
  if (m < kLeastNeighbours) return std::nullopt;
  const double n = static_cast<double>(m);
  const double cxx = static_cast<double>(sxx) - static_cast<double>(sx * sx) / n, cyy = static_cast<double>(syy) - static_cast<double>(sy * sy) / n;
  const double cxy = static_cast<double>(sxy) - static_cast<double>(sx * sy) / n;
  const double cxt = (static_cast<double>(sxt) - static_cast<double>(sx) * static_cast<double>(st) / n) * 1e-6;
  const double cyt = (static_cast<double>(syt) - static_cast<double>(sy) * static_cast<double>(st) / n) * 1e-6;
  const double det = cxx * cyy - cxy * cxy;
  // Neighbours along one line leave the slope across it unknown.
  if (det <= 0 || det < 1e-6 * (cxx + cyy) * (cxx + cyy)) return std::nullopt;
  const Eigen::Vector2d slope((cyy * cxt - cxy * cyt) / det, (cxx * cyt - cxy * cxt) / det);
  if (slope.squaredNorm() < 1e-14) return std::nullopt;
  return slope;
}

}  // namespace evms::golden

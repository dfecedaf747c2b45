// The slope of a packet's time surface under each event: how fast the edge that fired it moves.
//
// An event's slope is the gradient (s/px) of the plane fitted by least squares to the times of
// its packet's events of the same polarity on the 5x5 pixels around it (at least 6 of them, the
// fit not degenerate). An edge moving at velocity v fires so that slope · v = 1, whatever its
// orientation. The fit takes sums of each pixel's event count and summed times, exact in
// integers; the plane's gradient does not depend on where its time starts, so the events of one
// pixel and polarity share one slope, computed once a packet. The sums are kept for the packet's
// own pixels alone (a hash map), so their memory does not grow with the sensor. The split and the
// measurement by motion (motion_split.h, golden/track/motion_measure.h) and the outline split
// (golden/track/outline_split.h) read it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "types/event.h"

namespace evms::golden {

// How far velocity v (px/s) is from explaining slope g (s/px): 0 when an edge moving at v fires
// it.
inline double misfit(const Eigen::Vector2d& g, const Eigen::Vector2d& v) { return std::abs(g.dot(v) - 1.0); }

// The same, capped at 1: one event that no velocity near v explains weighs no more than that.
inline double capped_misfit(const Eigen::Vector2d& g, const Eigen::Vector2d& v) { return std::min(1.0, misfit(g, v)); }

// The velocity that explains the slopes slope[i], i in `sloped`, best: least squares on
// slope · v = 1. Slopes that all point one way (a straight edge) fix only the velocity along
// them: the least-norm solution.
Eigen::Vector2d fit_velocity(std::span<const Eigen::Vector2d> slope, std::span<const int> sloped);

class TimeSurfaceSlopes {
 public:
  explicit TimeSurfaceSlopes(SensorSize sensor);

  // Takes a packet's events; clear() before the next packet.
  void add(std::span<const Event> events);
  void clear();
  // The slope under event e (one of the packet's), when its neighbours give one.
  std::optional<Eigen::Vector2d> at(const Event& e);

 private:
  std::uint64_t pixel_index(std::uint8_t polarity, int x, int y) const {
    return (static_cast<std::uint64_t>(polarity != 0) * height_ + static_cast<std::uint64_t>(y)) * width_ + static_cast<std::uint64_t>(x);
  }
  std::optional<Eigen::Vector2d> fit(std::uint8_t polarity, int x, int y) const;

  int width_, height_;
  TimeUs first_t_ = 0;  // the packet's first event's time, from which the summed times count
  // Per polarity and pixel, the packet's events of it there: how many, their times after the
  // packet's first event summed, and their slope once known (an index into slopes_).
  static constexpr int kSlopeUnknown = -1, kNoSlope = -2;
  struct PixelEvents {
    int count = 0;
    int slope = kSlopeUnknown;
    std::int64_t time_sum = 0;
  };
  std::unordered_map<std::uint64_t, PixelEvents> on_pixel_;
  std::vector<Eigen::Vector2d> slopes_;
};

}  // namespace evms::golden

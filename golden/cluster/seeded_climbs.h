// Seeded climbs (params.seeding events or grid), as the authors' code clusters: a seed climbs
// by plain mean shift against the packet's events,
//     m <- sum_j k(|m - f_j|^2 / h^2) f_j / sum_j k(...),
// until it moves no more than the tolerance (or max_iterations). Every event inside the ball of
// radius h around the climb, at any of its steps, is "reached" (with a reach below h, every event
// within the reach). A converged climb joins the nearest earlier mode within the merge radius (its
// support raised to the climb's) or opens a new mode. Seeds, in order: the previous packet's modes
// (warm_start, each with its own ball, and its reach with warm_reach);
// then, for "grid", the centroid of each h x h cell's events, most populated cell first,
// skipping cells whose events were all reached; then the oldest event no climb has reached yet,
// until every event was reached.
//
// An event's mode is the mode of the first climb that reached it (labelling first), the mode
// whose climbs held it in their ball at most steps (labelling votes; ties to the older mode), or
// the nearest mode within label_reach bandwidths (labelling nearest; noise beyond).
//
// With the flat kernel a step's new position is the mean of the pixels in the ball, taken from
// exact integer sums of the pixel coordinates: no rounding depends on the order in which the
// events are visited.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "golden/cluster/packet_grid.h"

namespace evms::golden {

class SeededClimbs {
 public:
  // Starts a packet's climbs over `grid` (built on the packet's features).
  void start(const PacketGrid& grid, const Params& params, SensorSize sensor);

  // Climbs from `seed` with bandwidth h (at least params.bandwidth: the grid's cell). The events
  // it reaches are those within `reach` (at most h; 0: h) of it at a step.
  void climb(const Eigen::Vector4d& seed, double h, double reach = 0);
  // Climbs from the oldest event no climb has reached yet, until every event was reached.
  void seed_from_events();
  // Climbs from each cell's centroid (`cells`: the packet's grid with cell h), most populated
  // cell first, skipping cells whose events were all reached.
  void seed_from_grid(const PacketGrid& cells);

  // Per packet event: its mode (-1 for none), by params.labelling.
  std::vector<int> labels() const;

  const std::vector<Eigen::Vector4d>& modes() const { return modes_; }
  // Per mode: the most events a climb's last ball there held.
  const std::vector<int>& support() const { return support_; }
  int iterations() const { return iterations_; }
  std::int64_t kernel_evaluations() const { return kernel_evaluations_; }

 private:
  struct Sums {
    std::int64_t count = 0, x = 0, y = 0;      // flat kernel: exact
    double w = 0;                              // every kernel
    Eigen::Vector4d f = Eigen::Vector4d::Zero();
  };
  template <bool kFlat2d, bool kCountSteps>
  void step(const Eigen::Vector4d& m, double h, double reach2_per_h2, int climb, Sums& s);
  Eigen::Vector4d mean_of(const Sums& s) const;
  int join_or_open(const Eigen::Vector4d& m, int inside);

  const PacketGrid* grid_ = nullptr;
  const Params* p_ = nullptr;
  double scale_x_ = 0, scale_y_ = 0;        // feature = scale_xy * pixel / these
  bool flat2d_ = false;                      // flat kernel on (x, y) alone: the fast path
  std::vector<int> first_climb_;             // per member (cell order): the first climb that reached it, -1
  std::vector<std::uint8_t> inside_;         // per member: within the climb's reach at the current step
  std::vector<int> climb_mode_;              // per climb: the mode it joined
  // labelling votes: the current climb's steps with each member inside, and the votes cast
  std::vector<int> steps_inside_;
  std::vector<int> touched_;
  struct Vote {
    int member, mode, count;
  };
  std::vector<Vote> votes_;
  std::vector<Eigen::Vector4d> modes_;
  std::vector<int> support_;
  int iterations_ = 0;
  std::int64_t kernel_evaluations_ = 0;
};

}  // namespace evms::golden

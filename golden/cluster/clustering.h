// One packet's clustering: which cluster each event belongs to (or -1 for noise), and each
// cluster's mode. Two ways to get there (params.seeding):
//
//  every   The paper's text. Every event climbs at once (hybrid_mean_shift in mean_shift.h);
//          an event's cluster is the one its own mode joins (merge_modes).
//  events, grid
//          Seeded climbs, as the authors' code does it (seeded_climbs.h): seeds climb to modes
//          and each event takes the mode of the first climb that reached it (or by votes, or
//          the nearest mode). Clusters whose events touch are then joined (mode_links.h).
//
// With seeded climbs, a mode whose ball held fewer than min_density times the events that a
// uniform spread of the packet over the sensor would put in a ball of radius h is noise, and so
// are the events it would label: a cluster of background activity is no denser than that.
// With split_balance, a cluster that holds two objects apart from each other is then split in
// two (polarity_split.h), and with motion_split, one where two tracks meet that holds two
// motions (motion_split.h).
// Either way, clusters with fewer than min_cluster_size events become noise, and of the rest
// the first max_clusters in the order they opened are kept (the others become noise). The
// survivors are numbered 0.. in that order. There is no randomness.
#pragma once

#include <cstdint>
#include <vector>

#include "golden/cluster/features.h"
#include "golden/cluster/mode_links.h"
#include "golden/cluster/motion_split.h"
#include "golden/cluster/packet_grid.h"
#include "golden/cluster/polarity_split.h"
#include "golden/cluster/seeded_climbs.h"

namespace evms::golden {

struct PacketClusters {
  std::vector<int> cluster_of;           // per event: cluster index, or -1
  int count = 0;
  std::vector<Eigen::Vector4d> modes;    // per cluster
  std::vector<double> spreads;           // per cluster (seeded climbs): RMS distance of its events from their mean
  int iterations = 0;                    // sweeps (every) or climb steps, summed (seeded)
  std::int64_t kernel_evaluations = 0;   // point-to-point distances taken
};

// Clusters packet after packet, keeping its working memory (the grid, the climbs' marks, the
// link map) from one to the next.
class PacketClusterer {
 public:
  PacketClusterer(const Params& params, SensorSize sensor);

  // `warm_modes` and `warm_spreads`: the previous packet's modes and clusters' spreads, used
  // when params.warm_start is set; `meeting_points`: the confirmed tracks' predictions, used
  // when params.motion_split is set (motion_split.h).
  PacketClusters cluster(std::span<const Event> events, const FeatureMatrix& features, const std::vector<Eigen::Vector4d>& warm_modes,
                         const std::vector<double>& warm_spreads, std::span<const Eigen::Vector2d> meeting_points = {});

 private:
  PacketClusters finish(std::span<const Event> events, const FeatureMatrix& features, std::span<const Eigen::Vector2d> meeting_points,
                        std::vector<int> mode_of);
  void join_overlapping_boxes(std::span<const Event> events, std::vector<int>& raw) const;

  Params params_;
  SensorSize sensor_;
  double least_support_per_event_;  // least_support_per_event (types/params.h)
  PacketGrid grid_;       // cells of h / 2, for the climbs
  PacketGrid cells_;      // cells of h, the seeds of grid seeding
  SeededClimbs climbs_;
  ModeLinks links_;
  PolaritySplit split_;
  MotionSplit motion_split_;
  EdgeRule edge_;  // the edge join's (golden/cluster/edge_join.h)
};

// One packet on its own.
PacketClusters cluster_packet(std::span<const Event> events, const FeatureMatrix& features, const Params& params,
                              const std::vector<Eigen::Vector4d>& warm_modes, const std::vector<double>& warm_spreads, SensorSize sensor);

}  // namespace evms::golden

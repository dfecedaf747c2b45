// One packet's clustering: which cluster each event belongs to (or -1 for noise), and each
// cluster's mode. Two ways to get there (params.seeding):
//
//  every   The paper's text. Every event climbs at once (hybrid_mean_shift in mean_shift.h);
//          an event's cluster is the one its own mode joins (merge_modes).
//  events, grid
//          Seeded climbs, as the authors' code does it. A seed climbs by plain mean shift
//          against the packet's events,
//              m <- sum_j k(|m - f_j|^2 / h^2) f_j / sum_j k(...),
//          until it moves no more than the tolerance (or max_iterations). Every event inside the
//          ball of radius h around the climb, at any of its steps, is "reached" and gets one
//          vote for the climb. A converged climb joins the nearest earlier mode within the merge
//          radius (votes added, that mode kept) or opens a new mode. Seeds, in order: the
//          previous packet's modes (warm_start); then, for "events", the oldest event no climb
//          has reached yet, until every event was reached; for "grid", the centroid of the
//          events of each cell of an h x h grid on (x, y), most populated cell first, skipping
//          cells whose events were all reached. An event's cluster is then the mode with most
//          of its votes (labelling votes; ties to the older mode) or the nearest mode within h
//          (labelling nearest; noise beyond).
//
// With seeded climbs, a mode whose ball held fewer than min_density times the events that a
// uniform spread of the packet over the sensor would put in a ball of radius h is noise, and so
// are the events it would label: a cluster of background activity is no denser than that.
// Either way, clusters with fewer than min_cluster_size events become noise, and of the rest
// the first max_clusters in the order they opened are kept (the others become noise). The
// survivors are numbered 0.. in that order. There is no randomness.
#pragma once

#include <cstdint>
#include <vector>

#include "golden/cluster/features.h"

namespace evms::golden {

struct PacketClusters {
  std::vector<int> cluster_of;           // per event: cluster index, or -1
  int count = 0;
  std::vector<Eigen::Vector4d> modes;    // per cluster
  std::vector<double> spreads;           // per cluster (seeded climbs): RMS distance of its events from their mean
  int iterations = 0;                    // sweeps (every) or climb steps, summed (seeded)
  std::int64_t kernel_evaluations = 0;   // point-to-point distances taken
};

// `warm_modes`: the previous packet's modes, used when params.warm_start is set.
// `sensor_area`: the sensor's area in (x, y) feature units (feature_pixels' reciprocals times
// the sensor size, times scale_xy squared).
PacketClusters cluster_packet(std::span<const Event> events, const FeatureMatrix& features, const Params& params,
                              const std::vector<Eigen::Vector4d>& warm_modes, const std::vector<double>& warm_spreads,
                              double sensor_area);

}  // namespace evms::golden

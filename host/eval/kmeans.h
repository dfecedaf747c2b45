// The paper's baseline: K-means on the same features as the mean shift, given the true
// number of objects in each chunk. Initialised by k-means++ from a fixed seed, then Lloyd
// iterations until no assignment changes (at most 100). Events the background-activity
// filter rejects are noise (-1), as for the mean shift.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "types/event.h"
#include "types/params.h"
#include "host/eval/chunks.h"

namespace evms::eval {

// Cluster index (unique within its chunk) or -1 for each event.
std::vector<std::int32_t> kmeans_labels(std::span<const Event> events, std::span<const std::int32_t> truth,
                                        SensorSize sensor, const Params& params, Chunking chunking,
                                        std::uint64_t seed = 1);

// K-means on the columns of a feature matrix (4 x n), k-means++ initialisation.
std::vector<int> kmeans(const Eigen::Matrix<double, 4, Eigen::Dynamic>& points, int k, std::uint64_t seed);

}  // namespace evms::eval

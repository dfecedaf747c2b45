// One-to-one matching for the metrics: IDF1's objects to IDs (host/eval/identity_metrics.h)
// and CLEAR MOT's objects to tracks in a frame (host/eval/tracking_metrics.h).
#pragma once

#include <vector>

namespace evms::eval {

// The assignment of rows to distinct columns (rows <= columns) that maximizes the total weight:
// Hungarian method with potentials on the cost -weight. Returns the column of each row.
std::vector<int> max_weight_assignment(const std::vector<std::vector<double>>& weight);

}  // namespace evms::eval

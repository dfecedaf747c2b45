// One-to-one matching for the metrics: IDF1's objects to IDs (host/eval/identity_metrics.h)
// and CLEAR MOT's objects to tracks in a frame (host/eval/tracking_metrics.h).
#pragma once

#include <vector>

namespace evms::eval {

// The one-to-one assignment of rows and columns that matches every row or every column, whichever
// are fewer, and maximizes the total weight: Hungarian method with potentials on the cost
// -weight. Returns the column of each row, -1 for a row left over when columns are fewer.
std::vector<int> max_weight_assignment(const std::vector<std::vector<double>>& weight);

}  // namespace evms::eval

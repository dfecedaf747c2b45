// How closely one implementation follows another on the same events: label agreement (ARI
// and F of one labelling scored against the other, per chunk) and track agreement (each
// update against the reference's nearest update within 2 us: a mean timestamp may round the
// other way).
#pragma once

#include "host/eval/chunks.h"
#include "host/eval/clustering_metrics.h"
#include "host/eval/scene_run.h"

namespace evms::eval {

struct Agreement {
  ClusteringScores labels;          // `other` scored against `reference` as if it were the truth
  std::int64_t track_matched = 0;   // updates with a reference update within 2 us and 5 px
  std::int64_t track_unmatched = 0;
  double track_mean_px = 0, track_median_px = 0, track_p90_px = 0, track_p99_px = 0, track_max_px = 0;
};

Agreement agreement(std::span<const Event> events, const RunResult& reference, const RunResult& other, Chunking chunking);

}  // namespace evms::eval

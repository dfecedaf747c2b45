// One evaluation of one implementation on one labelled scene: clustering scores per chunk,
// tracking accuracy, and cost.
#pragma once

#include <span>
#include <string>

#include "host/eval/chunks.h"
#include "host/eval/clustering_metrics.h"
#include "host/eval/scene_run.h"
#include "host/eval/tracking_metrics.h"

namespace evms::eval {

struct Evaluation {
  ClusteringScores scores;         // mean over chunks
  std::int64_t chunks = 0;
  ClusteringScores scores_clear;   // mean over chunks where no two objects overlap
  std::int64_t chunks_clear = 0;
  TrackingReport tracking;
  RunResult run;
  double events_per_s_sensor = 0;  // input rate in sensor time
  double kept_per_s_sensor = 0;    // events that reach the mean shift, per second of sensor time
};

// Scores a labelling of a scene's events chunk by chunk; with `clear_only`, only chunks in
// which no two objects' outlines overlap (no occlusion) count.
ClusteringScores score_chunks(const Scene& scene, std::span<const std::int32_t> labels, Chunking chunking,
                              std::int64_t* chunks = nullptr, bool clear_only = false);

// Milliseconds of the scene (t_us / 1000) in which two objects' outlines overlap.
std::vector<bool> overlap_by_ms(const Scene& scene);

// A generated scene's tracking against both ground truths: its objects' true centres and the
// centres of their labelled events, each track owned by the object whose events it labelled
// most (`labels`, the run's; tracking_metrics.h).
TrackingReport scene_tracking(std::span<const TrackUpdate> updates, const Scene& scene, std::span<const std::int32_t> labels,
                              double tau_px = 2.5);

Evaluation evaluate(const Scene& scene, const Params& params, const std::string& backend, Chunking chunking,
                    double tau_px = 2.5);

}  // namespace evms::eval

#include "host/eval/evaluation.h"

#include <cmath>

namespace evms::eval {

std::vector<bool> overlap_by_ms(const Scene& scene) {
  std::vector<bool> overlap(scene.events.empty() ? 0 : static_cast<size_t>(scene.events.back().t / 1000 + 1), false);
  for (size_t i = 0; i < scene.centres.size();) {
    size_t j = i;
    while (j < scene.centres.size() && scene.centres[j].t == scene.centres[i].t) ++j;
    const auto ms = static_cast<size_t>(scene.centres[i].t / 1000);
    for (size_t a = i; a < j && ms < overlap.size(); ++a) {
      for (size_t b = a + 1; b < j; ++b) {
        const auto &p = scene.centres[a], &q = scene.centres[b];
        if (std::hypot(p.x - q.x, p.y - q.y) < p.radius + q.radius) overlap[ms] = true;
      }
    }
    i = j;
  }
  return overlap;
}

ClusteringScores score_chunks(const Scene& scene, std::span<const std::int32_t> labels, Chunking chunking,
                              std::int64_t* chunks, bool clear_only) {
  ScoreAverage average;
  const std::span<const std::int32_t> truth(scene.truth);
  const std::vector<bool> overlap = clear_only ? overlap_by_ms(scene) : std::vector<bool>{};
  for (const auto& [begin, end] : chunk_ranges(scene.events, chunking)) {
    if (end - begin < 2) continue;
    if (clear_only) {
      const auto first = static_cast<size_t>(scene.events[begin].t / 1000), last = static_cast<size_t>(scene.events[end - 1].t / 1000);
      bool occluded = false;
      for (size_t ms = first; ms <= last && ms < overlap.size(); ++ms) occluded = occluded || overlap[ms];
      if (occluded) continue;
    }
    average.add(score(truth.subspan(begin, end - begin), labels.subspan(begin, end - begin)));
  }
  if (chunks) *chunks = average.chunks();
  return average.mean();
}

TrackingReport scene_tracking(std::span<const TrackUpdate> updates, const Scene& scene, std::span<const std::int32_t> labels,
                              double tau_px) {
  return tracking_report(updates, scene.centres, static_cast<int>(scene.object_names.size()), tau_px, 15.0, 20000,
                         {scene.events, scene.truth, labels});
}

Evaluation evaluate(const Scene& scene, const Params& params, const std::string& backend, Chunking chunking, double tau_px) {
  Evaluation e;
  e.run = run_backend(backend, params, scene.sensor, scene.events);
  e.scores = score_chunks(scene, e.run.labels, chunking, &e.chunks);
  e.scores_clear = score_chunks(scene, e.run.labels, chunking, &e.chunks_clear, true);
  e.tracking = scene_tracking(e.run.tracks, scene, e.run.labels, tau_px);
  const double span = scene.events.size() > 1 ? static_cast<double>(scene.events.back().t - scene.events.front().t) * 1e-6 : 0;
  if (span > 0) {
    e.events_per_s_sensor = static_cast<double>(scene.events.size()) / span;
    e.kept_per_s_sensor = static_cast<double>(e.run.stats.events_kept) / span;
  }
  return e;
}

}  // namespace evms::eval

// evms metrics --truth LABELS.csv --pred EVENTS.csv [--tracks TRACKS.csv] : clustering scores
// of a labelling, printed as one line "ARI NMI P R F" (means over chunks). Both files hold the
// same events in the same order; the chunks are N consecutive events or fixed time windows.
// With the run's tracks.csv, two lines follow: identity (IDF1, ID switches) and the confirmed
// tracks' error against the centre of each object's labelled events in the 10 ms around each
// estimate (the paper's ground truth), each estimate scored against the object its track's
// events came from (host/eval/tracking_metrics.h), as `evms sweep` scores them. With
// `--touching-px R`, a last line scores the truth itself with the objects that touch in each
// chunk merged (host/eval/touching_objects.h): how far a clustering by position can get. With
// `--least`, a last line names the chunk of the least ARI: what two backends' agreement is
// judged by (one run's events.csv as the truth, the other's as the prediction).
#include <algorithm>
#include <cstdio>
#include <map>

#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/eval/clustering_metrics.h"
#include "host/eval/identity_metrics.h"
#include "host/eval/touching_objects.h"
#include "host/eval/tracking_metrics.h"
#include "host/read/input_error.h"
#include "host/read/labelled_csv.h"
#include "host/read/tracks_csv.h"

namespace evms::cli {
namespace {

struct MetricsOptions {
  std::string truth, pred, tracks;
  std::int64_t chunk_events = 0, chunk_us = 0;
  double touching_px = -1;  // < 0: no touching line
  bool least = false;
};

// The identity and tracking lines of `--tracks`. Object labels may be any non-negative
// integers; the scores index them densely.
void print_tracking(const std::string& tracks_path, const std::vector<Event>& events, const std::vector<std::int32_t>& truth,
                    const std::vector<std::int32_t>& predicted) {
  std::vector<TrackUpdate> confirmed;
  for (const TrackUpdate& u : read::read_tracks_csv(tracks_path)) {
    if (u.state == TrackState::kConfirmed) confirmed.push_back(u);
  }
  std::map<std::int32_t, std::int32_t> dense;
  for (std::int32_t label : truth) {
    if (label >= 0) dense.emplace(label, 0);
  }
  std::int32_t next = 0;
  for (auto& [label, index] : dense) index = next++;
  std::vector<std::int32_t> objects(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) objects[i] = truth[i] >= 0 ? dense[truth[i]] : -1;
  const eval::IdentityScores id = eval::identity_scores(events, objects, predicted);
  std::printf("IDF1 %.6f ID-precision %.6f ID-recall %.6f ID-switches %lld objects %lld\n", id.idf1, id.id_precision, id.id_recall,
              static_cast<long long>(id.id_switches), static_cast<long long>(id.objects));
  const eval::TrackingReport r = eval::tracking_report(confirmed, {}, next, 2.5, 15.0, 20000, {events, objects, predicted});
  const eval::ErrorStats& e = r.all_kalman_events;
  std::printf("tracking %.6f px within-2.5px %.6f estimates %lld (confirmed tracks against the labelled events' centre; %s updates on noise)\n",
              e.mean, e.within, static_cast<long long>(e.samples), grouped(r.spurious_updates).c_str());
}

void metrics(const MetricsOptions& o) {
  if (o.chunk_events > 0 && o.chunk_us > 0) throw std::invalid_argument("give --chunk-us or --chunk-events, not both");
  const std::int64_t chunk_events = o.chunk_us > 0 ? 0 : (o.chunk_events > 0 ? o.chunk_events : 256);
  read::LabelledCsvReader truth(o.truth), pred(o.pred);
  eval::ScoreAverage average, touching;
  std::vector<std::int32_t> t_labels, p_labels;
  std::vector<Event> chunk;  // with --touching-px: the chunk's events
  std::vector<Event> all_events;              // with --tracks: every event and both labels
  std::vector<std::int32_t> all_truth, all_pred;
  TimeUs window_end = 0;
  bool first = true;
  // With --least: the chunk of the least ARI, its scores, first event's time and truth line.
  eval::ClusteringScores least;
  TimeUs chunk_t = 0, least_t = 0;
  std::int64_t chunk_line = 0, least_line = 0;
  bool any_least = false;
  auto flush = [&] {
    if (t_labels.size() >= 2) {
      const eval::ClusteringScores chunk_scores = eval::score(t_labels, p_labels);
      average.add(chunk_scores);
      if (!any_least || chunk_scores.ari < least.ari) least = chunk_scores, least_t = chunk_t, least_line = chunk_line, any_least = true;
      if (o.touching_px >= 0) touching.add(eval::score(t_labels, eval::merge_touching_objects(chunk, t_labels, o.touching_px)));
    }
    t_labels.clear();
    p_labels.clear();
    chunk.clear();
  };
  LabelledEvent a, b;
  for (;;) {
    const bool more_truth = truth.next(a), more_pred = pred.next(b);
    if (more_truth != more_pred) {
      const auto& shorter = more_truth ? pred : truth;
      throw read::InputError(shorter.path() + ": line " + std::to_string(shorter.line() + 1) + ": ends while " +
                             (more_truth ? truth : pred).path() + " has more rows");
    }
    if (!more_truth) break;
    if (!(a.event == b.event)) {
      throw read::InputError(o.pred + ": line " + std::to_string(pred.line()) + ": event (" + std::to_string(b.event.t) + "," +
                             std::to_string(b.event.x) + "," + std::to_string(b.event.y) + ") differs from line " +
                             std::to_string(truth.line()) + " of " + o.truth);
    }
    if (o.chunk_us > 0) {
      if (first) window_end = a.event.t + o.chunk_us;
      while (a.event.t >= window_end) flush(), window_end += o.chunk_us;
    }
    if (!o.tracks.empty()) {
      if (!all_events.empty() && a.event.t < all_events.back().t) {
        throw read::InputError(o.truth + ": line " + std::to_string(truth.line()) + ": t_us " + std::to_string(a.event.t) +
                               " is earlier than the row before (--tracks scores events in time order)");
      }
      all_events.push_back(a.event), all_truth.push_back(a.label), all_pred.push_back(b.label);
    }
    first = false;
    if (t_labels.empty()) chunk_t = a.event.t, chunk_line = static_cast<std::int64_t>(truth.line());
    t_labels.push_back(a.label);
    p_labels.push_back(b.label);
    if (o.touching_px >= 0) chunk.push_back(a.event);
    if (chunk_events > 0 && static_cast<std::int64_t>(t_labels.size()) == chunk_events) flush();
  }
  flush();
  if (average.chunks() == 0) throw std::invalid_argument(o.truth + ": fewer than 2 events: nothing to score");
  const auto s = average.mean();
  std::printf("%.6f %.6f %.6f %.6f %.6f\n", s.ari, s.nmi, s.precision, s.recall, s.f);
  if (!o.tracks.empty()) print_tracking(o.tracks, all_events, all_truth, all_pred);
  if (o.touching_px >= 0) {
    const auto c = touching.mean();
    std::printf("touching-merged %.6f %.6f %.6f %.6f %.6f (the truth with objects within %g px of each other in a chunk merged)\n", c.ari,
                c.nmi, c.precision, c.recall, c.f, o.touching_px);
  }
  if (o.least) {
    std::printf("least-chunk %.6f %.6f %.6f %.6f %.6f (the chunk of the least ARI, from t_us %lld, line %lld of %s)\n", least.ari, least.nmi,
                least.precision, least.recall, least.f, static_cast<long long>(least_t), static_cast<long long>(least_line), o.truth.c_str());
  }
}

}  // namespace

void register_metrics(CLI::App& app) {
  auto o = std::make_shared<MetricsOptions>();
  CLI::App* cmd = app.add_subcommand("metrics", "score a labelling against the truth; prints 'ARI NMI P R F'");
  cmd->add_option("--truth", o->truth, "true labels: a CSV whose header names t_us (or t_s, ...), x, y, p and label in any order, or t_us,x,y,p,label rows without a header (label -1 = noise)")->required();
  cmd->add_option("--pred", o->pred, "predicted labels of the same events, same layout (-2, a label lost on the board's link, counts as noise)")->required();
  cmd->add_option("--chunk-events", o->chunk_events, "score chunks of N consecutive events (default 256)")->check(CLI::Range(2, 1000000000));
  cmd->add_option("--tracks", o->tracks, "the run's tracks.csv: also print IDF1 and ID switches, and the confirmed tracks' error against the "
                 "centre of each object's labelled events (two more lines)");
  cmd->add_option("--chunk-us", o->chunk_us, "score fixed time windows of N us instead")->check(CLI::Range(std::int64_t{1}, std::int64_t{1000000000000}));
  cmd->add_option("--touching-px", o->touching_px, "also score the truth with the objects whose events come within R px of each other in a "
                 "chunk merged: what a clustering that holds touching objects together scores at best (a last line)")
      ->check(finite_in(0.0, 1000.0));
  cmd->add_flag("--least", o->least, "also print the scores of the chunk of the least ARI, and where it starts (a last line): with one "
                "backend's events.csv as the truth and another's as the prediction, how far the two part");
  cmd->callback([o] { metrics(*o); });
}

}  // namespace evms::cli

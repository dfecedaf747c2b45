// evms metrics --truth LABELS.csv --pred EVENTS.csv : clustering scores of a labelling,
// printed as one line "ARI NMI P R F" (means over chunks). Both files hold the same events
// in the same order; the chunks are N consecutive events or fixed time windows.
#include <cstdio>

#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/eval/clustering_metrics.h"
#include "host/read/input_error.h"
#include "host/read/labelled_csv.h"

namespace evms::cli {
namespace {

struct MetricsOptions {
  std::string truth, pred;
  std::int64_t chunk_events = 0, chunk_us = 0;
};

void metrics(const MetricsOptions& o) {
  if (o.chunk_events > 0 && o.chunk_us > 0) throw std::invalid_argument("give --chunk-us or --chunk-events, not both");
  const std::int64_t chunk_events = o.chunk_us > 0 ? 0 : (o.chunk_events > 0 ? o.chunk_events : 256);
  read::LabelledCsvReader truth(o.truth), pred(o.pred);
  eval::ScoreAverage average;
  std::vector<std::int32_t> t_labels, p_labels;
  TimeUs window_end = 0;
  bool first = true;
  auto flush = [&] {
    if (t_labels.size() >= 2) average.add(eval::score(t_labels, p_labels));
    t_labels.clear();
    p_labels.clear();
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
    first = false;
    t_labels.push_back(a.label);
    p_labels.push_back(b.label);
    if (chunk_events > 0 && static_cast<std::int64_t>(t_labels.size()) == chunk_events) flush();
  }
  flush();
  if (average.chunks() == 0) throw std::invalid_argument(o.truth + ": fewer than 2 events: nothing to score");
  const auto s = average.mean();
  std::printf("%.6f %.6f %.6f %.6f %.6f\n", s.ari, s.nmi, s.precision, s.recall, s.f);
}

}  // namespace

void register_metrics(CLI::App& app) {
  auto o = std::make_shared<MetricsOptions>();
  CLI::App* cmd = app.add_subcommand("metrics", "score a labelling against the truth; prints 'ARI NMI P R F'");
  cmd->add_option("--truth", o->truth, "true labels, t_us,x,y,p,label (label -1 = noise)")->required();
  cmd->add_option("--pred", o->pred, "predicted labels of the same events, same layout (-2, a label lost on the board's link, counts as noise)")->required();
  cmd->add_option("--chunk-events", o->chunk_events, "score chunks of N consecutive events (default 256)")->check(CLI::Range(2, 1000000000));
  cmd->add_option("--chunk-us", o->chunk_us, "score fixed time windows of N us instead")->check(CLI::Range(std::int64_t{1}, std::int64_t{1000000000000}));
  cmd->callback([o] { metrics(*o); });
}

}  // namespace evms::cli

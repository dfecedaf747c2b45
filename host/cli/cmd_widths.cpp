// evms widths : the word-width study behind the core's formats (docs/widths.md). Each row is
// the host core with one width changed; each is scored against the truth and against golden.
#include <cstdio>
#include <functional>

#include "host/backend/fixed_backend.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/eval/agreement.h"
#include "host/eval/evaluation.h"
#include "host/eval/parallel.h"

namespace evms::cli {
namespace {

template <int FeatFrac, int WeightFrac, int ExpLog2, int PosFrac, int TsBits = 32, int TsShift = 0>
using Variant = hls::Shape<1280, 720, 256, 8, 8, 16, 16, TsBits, TsShift, 64 * 256, FeatFrac, WeightFrac, ExpLog2, PosFrac>;

struct Row {
  const char* name;
  std::function<std::unique_ptr<backend::Backend>(const backend::BackendOptions&)> make;
};

template <class S>
Row row(const char* name) {
  return {name, [](const backend::BackendOptions& o) { return std::make_unique<backend::FixedBackend<S>>(o); }};
}

struct WidthsOptions {
  double duration_s = 2.0;
  std::uint64_t seed = 1;
  int jobs = 2;
};

void widths(const WidthsOptions& o) {
  const std::vector<Row> rows = {
      row<hls::HostShape>("host core (default: features 5.13, weights 1.16, exp table 2^10, positions .12)"),
      row<Variant<7, 16, 10, 12>>("features 5.7"),
      row<Variant<9, 16, 10, 12>>("features 5.9"),
      row<Variant<11, 16, 10, 12>>("features 5.11"),
      row<Variant<15, 16, 10, 12>>("features 5.15"),
      row<Variant<13, 8, 10, 12>>("weights 1.8"),
      row<Variant<13, 12, 10, 12>>("weights 1.12"),
      row<Variant<13, 16, 6, 12>>("exp table 2^6 entries"),
      row<Variant<13, 16, 8, 12>>("exp table 2^8 entries"),
      row<Variant<13, 16, 10, 4>>("positions .4"),
      row<Variant<13, 16, 10, 8>>("positions .8"),
      row<Variant<11, 16, 9, 12, 16, 7>>("board core widths (features 5.11, exp 2^9, 16-bit 128 us timestamps)"),
  };
  const std::vector<gen::Motion> motions = {gen::Motion::kTranslation, gen::Motion::kRotation, gen::Motion::kSixDof};
  std::vector<eval::Scene> scenes(motions.size());
  std::vector<eval::RunResult> golden(motions.size());
  const Params params;
  eval::parallel_for(motions.size(), o.jobs, [&](size_t i) {
    gen::SceneConfig c;
    c.motion = motions[i];
    c.duration_s = o.duration_s;
    c.seed = o.seed;
    scenes[i] = eval::generate_scene(c);
    golden[i] = eval::run_backend("golden", params, scenes[i].sensor, scenes[i].events);
  });
  struct Cell {
    eval::ClusteringScores truth;
    eval::Agreement vs_golden;
    double track_err = 0;
  };
  std::vector<Cell> cells(rows.size() * scenes.size());
  eval::parallel_for(cells.size(), o.jobs, [&](size_t k) {
    const size_t r = k / scenes.size(), s = k % scenes.size();
    auto backend = rows[r].make(backend::options_for(params, scenes[s].sensor));
    const eval::RunResult run = eval::run_backend(*backend, scenes[s].events);
    cells[k].truth = eval::score_chunks(scenes[s], run.labels, {});
    cells[k].vs_golden = eval::agreement(scenes[s].events, golden[s], run, {});
    cells[k].track_err = eval::tracking_report(run.tracks, scenes[s].centres, static_cast<int>(scenes[s].object_names.size())).all_kalman.mean;
  });
  double golden_f = 0, golden_ari = 0, golden_err = 0;
  for (size_t s = 0; s < scenes.size(); ++s) {
    const auto sc = eval::score_chunks(scenes[s], golden[s].labels, {});
    golden_f += sc.f / scenes.size(), golden_ari += sc.ari / scenes.size();
    golden_err += eval::tracking_report(golden[s].tracks, scenes[s].centres, static_cast<int>(scenes[s].object_names.size())).all_kalman.mean /
                  scenes.size();
  }
  std::printf("| core | F (truth) | ARI (truth) | ARI against golden (min over scenes) | track error px | track position against golden: median / p90 px |\n"
              "|---|---|---|---|---|---|\n");
  std::printf("| golden (double) | %.4f | %.4f | 1 | %.2f | 0 / 0 |\n", golden_f, golden_ari, golden_err);
  for (size_t r = 0; r < rows.size(); ++r) {
    double f = 0, ari = 0, min_agree = 1, err = 0, median = 0, p90 = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
      const Cell& c = cells[r * scenes.size() + s];
      const double n = static_cast<double>(scenes.size());
      f += c.truth.f / n, ari += c.truth.ari / n, err += c.track_err / n;
      min_agree = std::min(min_agree, c.vs_golden.labels.ari);
      median += c.vs_golden.track_median_px / n, p90 += c.vs_golden.track_p90_px / n;
    }
    std::printf("| %s | %.4f | %.4f | %.4f | %.2f | %.3f / %.3f |\n", rows[r].name, f, ari, min_agree, err, median, p90);
    std::fflush(stdout);
  }
}

}  // namespace

void register_widths(CLI::App& app) {
  auto o = std::make_shared<WidthsOptions>();
  CLI::App* cmd = app.add_subcommand("widths", "the word-width study of the fixed-point core (Markdown table)");
  cmd->add_option("--duration-s", o->duration_s, "length of each scene")->default_val(o->duration_s)->check(CLI::Range(0.1, 600.0));
  cmd->add_option("--seed", o->seed, "scene seed")->default_val(o->seed);
  cmd->add_option("--jobs", o->jobs, "threads")->default_val(o->jobs)->check(CLI::Range(1, 64));
  cmd->callback([o] { widths(*o); });
}

}  // namespace evms::cli

// evms widths : the word-width study behind the core's formats (docs/widths.md). Each row is
// the host core with one width changed, or with a board build's words; each is scored against
// the truth and against golden, by the method given (the defaults, or --preset gaussian).
#include <cstdio>
#include <functional>
#include <string>
#include <type_traits>

#include "hls/core/configs.h"
#include "host/backend/fixed_backend.h"
#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/eval/agreement.h"
#include "host/eval/evaluation.h"
#include "host/eval/parallel.h"

namespace evms::cli {
namespace {

// hls::HostShape with the words the study varies as parameters.
template <int TimestampBits = 32, int TimestampShift = 0, int FeatFrac = 13, int WeightFrac = 16, int ExpTableLog2 = 10,
          int PosFrac = 12>
using HostVariant = hls::Shape<1280, 720, 4096, 8, 8, 128, 128, TimestampBits, TimestampShift, 64 * 4096, FeatFrac,
                               WeightFrac, ExpTableLog2, PosFrac, 64, 4096, 8, 32, 8, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1>;
static_assert(std::is_same_v<HostVariant<>, hls::HostShape>, "HostVariant<> is the host core");
// The host core with the words of the board build B: its sizes stay the host's, so that it
// runs the method's own packets and counts.
template <class B>
using WithWordsOf = HostVariant<B::kTimestampBits, B::kTimestampShift, B::kFeatFrac, B::kWeightFrac, B::kExpTableLog2, B::kPosFrac>;

template <class S>
std::string words_text() {
  std::string t = "features 5." + std::to_string(S::kFeatFrac) + ", positions ." + std::to_string(S::kPosFrac) + ", ";
  t += S::kTimestampBits == 32 && S::kTimestampShift == 0
           ? std::string("32-bit 1 us timestamps")
           : std::to_string(S::kTimestampBits) + "-bit " + std::to_string(1 << S::kTimestampShift) + " us timestamps";
  return t;
}

// The clustering path whose words a row changes: the Gaussian mean shift of every event (its
// kernel weights and exp table), the seeded climbs (the board builds, which hold only them), or
// words both use.
enum class Path { kBoth, kGaussian, kSeeded };

struct Row {
  std::string name;
  Path path;
  std::function<std::unique_ptr<backend::Backend>(const backend::BackendOptions&)> make;
};

template <class S>
Row row(std::string name, Path path = Path::kBoth) {
  return {std::move(name), path, [](const backend::BackendOptions& o) { return std::make_unique<backend::FixedBackend<S>>(o); }};
}

template <class B>
Row board_row(const char* build) {
  return row<WithWordsOf<B>>(std::string("the ") + build + " build's words (" + words_text<B>() + ")", Path::kSeeded);
}

struct WidthsOptions {
  double duration_s = 2.0;
  std::uint64_t seed = 1;
  int jobs = 2;
  Method method;
};

void widths(const WidthsOptions& o) {
  const std::vector<Row> all_rows = {
      row<hls::HostShape>("host core (" + words_text<hls::HostShape>() + "; weights 1.16, exp table 2^10)"),
      row<HostVariant<32, 0, 7>>("features 5.7"),
      row<HostVariant<32, 0, 11>>("features 5.11"),
      row<HostVariant<32, 0, 13, 8>>("weights 1.8", Path::kGaussian),
      row<HostVariant<32, 0, 13, 12>>("weights 1.12", Path::kGaussian),
      row<HostVariant<32, 0, 13, 16, 6>>("exp table 2^6 entries", Path::kGaussian),
      row<HostVariant<32, 0, 13, 16, 8>>("exp table 2^8 entries", Path::kGaussian),
      row<HostVariant<32, 0, 13, 16, 10, 4>>("positions .4"),
      row<HostVariant<32, 0, 13, 16, 10, 8>>("positions .8"),
      row<HostVariant<16, 7>>("16-bit 128 us timestamps"),
      board_row<hls::ArtyShape>("arty"),
      board_row<hls::Ice40Shape>("ice40"),
  };
  const std::vector<gen::Motion> motions = {gen::Motion::kTranslation, gen::Motion::kRotation, gen::Motion::kSixDof};
  std::vector<eval::Scene> scenes(motions.size());
  std::vector<Params> params(motions.size());
  std::vector<eval::RunResult> golden(motions.size());
  eval::parallel_for(motions.size(), o.jobs, [&](size_t i) {
    gen::SceneConfig c;
    c.motion = motions[i];
    c.duration_s = o.duration_s;
    c.seed = o.seed;
    scenes[i] = eval::generate_scene(c);
    params[i] = o.method.resolve(scenes[i].sensor);
  });
  // The rows that apply to the method's path.
  const Path path = params.front().seeding == Seeding::kEvery ? Path::kGaussian : Path::kSeeded;
  std::vector<Row> rows;
  for (const Row& r : all_rows)
    if (r.path == Path::kBoth || r.path == path) rows.push_back(r);
  // The host core refuses a method it does not implement in one line, before any row runs.
  for (size_t i = 0; i < scenes.size(); ++i) rows.front().make(backend::options_for(params[i], scenes[i].sensor));
  eval::parallel_for(motions.size(), o.jobs, [&](size_t i) {
    golden[i] = eval::run_backend("golden", params[i], scenes[i].sensor, scenes[i].events);
  });
  struct Cell {
    eval::ClusteringScores truth;
    eval::Agreement vs_golden;
    double track_err = 0;
  };
  std::vector<Cell> cells(rows.size() * scenes.size());
  eval::parallel_for(cells.size(), o.jobs, [&](size_t k) {
    const size_t r = k / scenes.size(), s = k % scenes.size();
    auto backend = rows[r].make(backend::options_for(params[s], scenes[s].sensor));
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
  std::printf("method: %s\n\n", o.method.describe().c_str());
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
    std::printf("| %s | %.4f | %.4f | %.4f | %.2f | %.3f / %.3f |\n", rows[r].name.c_str(), f, ari, min_agree, err, median, p90);
    std::fflush(stdout);
  }
}

}  // namespace

void register_widths(CLI::App& app) {
  auto o = std::make_shared<WidthsOptions>();
  CLI::App* cmd = app.add_subcommand("widths", "the word-width study of the fixed-point core (Markdown table)");
  cmd->add_option("--duration-s", o->duration_s, "length of each scene")->default_val(o->duration_s)->check(finite_in(0.01, 600.0));
  cmd->add_option("--seed", o->seed, "scene seed")->default_val(o->seed);
  cmd->add_option("--jobs", o->jobs, "threads")->default_val(o->jobs)->check(CLI::Range(1, 64));
  add_method_options(*cmd, o->method);
  cmd->callback([o] { widths(*o); });
}

}  // namespace evms::cli

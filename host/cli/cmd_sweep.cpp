// evms sweep : the method's choices measured on the scene family (host/gen/family.h), as
// Markdown. Three forms:
//   evms sweep                    the presets side by side on the tuning and validation splits
//                                 (with --preset or method options: that method alone)
//   evms sweep --vary NAME=A,B    one parameter at a time around the method given
//   evms sweep --search           coordinate ascent from the method given over the standard
//                                 grid on the tuning split, then the result checked on the
//                                 validation split beside the paper preset (docs/sweep.md)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "host/cli/commands.h"
#include "host/cli/common.h"
#include "host/eval/family_eval.h"

namespace evms::cli {
namespace {

struct SweepOptions {
  int seeds = 6;
  std::vector<std::string> types;
  int jobs = 2;
  std::vector<std::string> vary;
  bool search = false;
  bool per_scene = false;
  std::string split = "tuning";   // of --vary, and of the presets when given
  bool split_given = false;
  int rounds = 3;
  std::string backend = "golden";
  gen::FamilyPins pins;
  Method method;
  bool method_given = false;  // --preset or a method option on the command line
};

// The grid --search walks, one parameter at a time. Every event climbing (--seeding every, the
// paper's text) costs n^2 a sweep on 3,000-event packets, so it is measured through the presets
// (the gaussian preset) instead of here.
const std::vector<std::string> kSearchGrid = {
    "kernel=flat,epanechnikov,gaussian",
    "seeding=events,grid",
    "labelling=first,votes,nearest",
    "warm-start=false,true",
    "warm-scale=0,1,1.5,2",
    "warm-max-bandwidth=0.08,0.1,0.12,0.14,0.16",
    "xy-scale=axes,isotropic",
    "bandwidth=0.03,0.04,0.05,0.06,0.08,0.1,0.15",
    "merge-radius=0.01,0.02,0.03,0.04,0.06",
    "min-density=0,1,2,3",
    "link-px=0,2,4,6,8",
    "split-balance=0,0.2,0.3,0.4",
    "split-partial=false,true",
    "split-cell=0.3,0.4,0.5",
    "motion-split=0,0.4,0.6,0.8",
    "edge-join=0,3,5,8",
    "measure=centroid,box-centre,polarity-midpoint,pixel-centre",
    "min-cluster-size=4,8,16",
    "max-iterations=4,8,16",
    "packet-size=1000,2000,3000,4000",
    "packet-max-span-us=10000,20000,33333,50000",
    "filter-window-us=10000,30000,60000",
    "filter-support=1,2",
    "filter-warm-up-us=0,10000",
    "filter-noise-hz=0,0.35,0.7,1.4",
    "filter-quiet-hz=0,0.25",
    "packet-support=0,1",
    "association=kalman,last-measurement,nearest-centre",
    "gate-px=10,20,30",
    "gate-spread=0,1,2",
    "gate-boxes=false,true",
    "size-ratio=0,4",
    "confirm-hits=1,2,3",
    "coast-us=50000,100000,200000",
    "evict-stale=false,true",
    "accel-psd=1000,10000,100000",
    "meas-sigma-px=0.5,1,2",
    "motion-measure=0,600,1000,1500",
    "meas-noise-from-spread=false,true",
};

// What --search maximizes: the mean F over every scene, with the worst type counted again at
// half weight, so that no type is given up for the others, and identity and tracking at a
// tenth each (IDF1, and the share of estimates within 2.5 px of the true centre).
double objective(const eval::FamilyResult& r) {
  return r.mean_f + 0.5 * r.worst_type_f + 0.1 * r.idf1 + 0.1 * r.tracking.within;
}

// The family's types and the paper's scenes.
std::vector<std::string> types_of(const SweepOptions& o) {
  if (!o.types.empty()) return o.types;
  std::vector<std::string> types(gen::family_types().begin(), gen::family_types().end());
  types.insert(types.end(), eval::kPaperSceneTypes.begin(), eval::kPaperSceneTypes.end());
  return types;
}

void print_header(const std::vector<std::string>& types, const char* first) {
  std::printf("| %s |", first);
  for (const auto& t : types) std::printf(" %s |", t.c_str());
  std::printf(" mean F | worst type | ARI | IDF1 | ID switches/object | track err px | within 2.5 px | events' centre's own err px | within 2.5 px | velocity err px/s | err to events' centre px | within 2.5 px | MOTA | MOTP px | MOTP to events' centre px | within 2.5 px | kernel evals/event | events/s |\n|---|");
  for (size_t i = 0; i < types.size() + 18; ++i) std::printf("---|");
  std::printf("\n");
}

void print_row(const std::string& label, const eval::FamilyResult& r) {
  std::printf("| %s |", label.c_str());
  for (const auto& t : r.types) std::printf(" %.3f |", t.f);
  std::printf(" **%.3f** | %.3f | %.3f | %.3f | %.1f | %.2f | %.2f | %.2f | %.2f | %.1f | %.2f | %.2f | %.3f | %.2f | %.2f | %.2f | %.0f | %s |\n", r.mean_f,
              r.worst_type_f, r.mean_ari, r.idf1, r.id_switches_per_object, r.tracking.mean, r.tracking.within, r.events_centre.mean, r.events_centre.within, r.velocity.mean, r.tracking_to_events.mean,
              r.tracking_to_events.within, r.mot.mota(), r.mot.to_centres.mean, r.mot.to_events.mean, r.mot.to_events.within,
              r.kernel_evaluations_per_event, si(r.events_per_s).c_str());
  std::fflush(stdout);
}

std::vector<std::pair<std::string, std::vector<std::string>>> parse_grid(const std::vector<std::string>& specs) {
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;
  for (const std::string& spec : specs) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--vary: expected NAME=V1,V2,..., got '" + spec + "'");
    const std::string name = spec.substr(0, eq);
    const ParamInfo* info = find_param(name);
    if (!info) throw std::invalid_argument("--vary: unknown parameter '" + name + "'");
    std::vector<std::string> values;
    std::stringstream list(spec.substr(eq + 1));
    for (std::string v; std::getline(list, v, ',');) {
      Params scratch;
      if (std::string e = set_param(scratch, *info, v); !e.empty()) throw std::invalid_argument(e);
      values.push_back(v);
    }
    grid.emplace_back(name, values);
  }
  return grid;
}

Method with(const Method& base, const std::string& name, const std::string& value) {
  Method m = base;
  std::erase_if(m.settings, [&](const auto& s) { return s.first == name; });
  m.settings.emplace_back(name, value);
  return m;
}

std::string current_value(const Method& m, const std::string& name) {
  const ParamInfo* info = find_param(name);
  return param_text(m.resolve({240, 180}), *info);
}

// A method's name in the per-member and per-sensor columns: its preset, or the value --vary gave it.
const char* column_name(const Method& m) { return m.settings.empty() ? m.preset.c_str() : m.settings.back().second.c_str(); }

// A member's estimates beyond 2.5 px, a count (from its share within), so that a type's, a
// sensor's or the split's sum is exact: the split's pooled share weighs each member by its
// estimates, so a long, busy member can set it.
long long estimates_beyond(const eval::TrackingReport& t) {
  return std::llround(static_cast<double>(t.all_kalman.samples) * (1.0 - t.all_kalman.within));
}

// The members of each sensor together: their mean F, and their estimates pooled, as the split's
// share within 2.5 px pools them (a finer sensor's pixel is a smaller angle, docs/sweep.md).
void print_sensors(const std::vector<eval::FamilyScene>& family, const std::vector<Method>& methods,
                   const std::vector<eval::FamilyResult>& results) {
  std::vector<std::pair<int, int>> sensors;
  for (const auto& s : family) sensors.emplace_back(s.scene.config.width, s.scene.config.height);
  std::sort(sensors.begin(), sensors.end(), [](const auto& a, const auto& b) { return std::make_pair(a.first * a.second, a) < std::make_pair(b.first * b.second, b); });
  sensors.erase(std::unique(sensors.begin(), sensors.end()), sensors.end());
  std::printf("\n| sensor | members |");
  for (const Method& m : methods) {
    const char* name = column_name(m);
    std::printf(" mean F %s | estimates %s | beyond 2.5 px %s | within 2.5 px %s |", name, name, name, name);
  }
  std::printf("\n|---|---|");
  for (size_t m = 0; m < methods.size(); ++m) std::printf("---|---|---|---|");
  std::printf("\n");
  for (const auto& [width, height] : sensors) {
    std::vector<size_t> members;
    for (size_t i = 0; i < family.size(); ++i) {
      if (family[i].scene.config.width == width && family[i].scene.config.height == height) members.push_back(i);
    }
    std::printf("| %dx%d | %zu |", width, height, members.size());
    for (const auto& r : results) {
      double f = 0;
      long long estimates = 0, beyond = 0;
      for (size_t i : members) {
        const eval::TrackingReport& t = r.scenes[i].tracking;
        f += r.scenes[i].scores.f;
        estimates += static_cast<long long>(t.all_kalman.samples);
        beyond += estimates_beyond(t);
      }
      std::printf(" %.3f | %lld | %lld | %.3f |", f / static_cast<double>(members.size()), estimates, beyond,
                  estimates > 0 ? 1.0 - static_cast<double>(beyond) / static_cast<double>(estimates) : 0.0);
    }
    std::printf("\n");
  }
}

// Every member's F under each method, then each sensor's members together.
void print_scenes(const std::vector<eval::FamilyScene>& family, const std::vector<Method>& methods,
                  const std::vector<eval::FamilyResult>& results) {
  std::printf("\n| scene | events | noise |");
  for (const Method& m : methods) {
    const char* name = column_name(m);
    std::printf(" F %s | IDF1 %s | track err px %s | estimates %s | beyond 2.5 px %s | within 2.5 px %s | centroid err px %s | events' centre's own err px %s | err to events' centre px %s | MOTA %s | false tracks/frame %s |",
                name, name, name, name, name, name, name, name, name, name, name);
  }
  std::printf("\n|---|---|---|");
  for (size_t m = 0; m < methods.size(); ++m) std::printf("---|---|---|---|---|---|---|---|---|---|---|");
  std::printf("\n");
  for (size_t i = 0; i < family.size(); ++i) {
    const auto& s = family[i];
    const auto truth_noise = std::count(s.scene.truth.begin(), s.scene.truth.end(), kNoiseLabel);
    std::printf("| %s %llu: %s | %zu | %.0f%% |", s.type.c_str(), static_cast<unsigned long long>(s.seed),
                gen::describe(s.scene.config).c_str(), s.scene.events.size(), 100.0 * truth_noise / std::max<size_t>(1, s.scene.events.size()));
    for (const auto& r : results) {
      const eval::TrackingReport& t = r.scenes[i].tracking;
      const auto estimates = t.all_kalman.samples;
      const auto beyond = estimates_beyond(t);
      std::printf(" %.3f | %.3f | %.2f | %lld | %lld | %.2f | %.2f | %.2f | %.2f | %.3f | %.2f |", r.scenes[i].scores.f, r.scenes[i].identity.idf1,
                  t.all_kalman.mean, static_cast<long long>(estimates), static_cast<long long>(beyond), t.all_kalman.within, t.all_raw.mean,
                  t.all_events_centre.mean, t.all_kalman_events.mean, t.mot.mota(), t.mot.false_positives_per_frame());
    }
    std::printf("\n");
  }
  print_sensors(family, methods, results);
}

gen::Split split_of(const SweepOptions& o) { return o.split == "validation" ? gen::Split::kValidation : gen::Split::kTuning; }

// The presets on both splits (on --split alone when given), or the method the command line gives.
void compare_presets(const SweepOptions& o, const std::vector<std::string>& types) {
  std::vector<Method> methods;
  if (o.method_given) methods.push_back(o.method);
  else for (const char* name : preset_names()) methods.push_back({name, {}});
  for (gen::Split split : {gen::Split::kTuning, gen::Split::kValidation}) {
    if (o.split_given && split != split_of(o)) continue;
    const auto family = eval::generate_family(split, o.seeds, types, o.jobs, o.pins);
    std::printf("\n## %s split (%d seeds a type)\n\n", split == gen::Split::kTuning ? "Tuning" : "Validation", o.seeds);
    print_header(types, o.method_given ? "method" : "preset");
    const auto results = eval::evaluate_family(family, methods, o.backend, o.jobs);
    for (size_t m = 0; m < methods.size(); ++m) print_row(o.method_given ? methods[m].describe() : methods[m].preset, results[m]);
    if (o.per_scene) print_scenes(family, methods, results);
  }
}

void one_at_a_time(const SweepOptions& o, const std::vector<std::string>& types) {
  const gen::Split split = split_of(o);
  std::printf("\n%s split, %d seeds a type.\n", o.split.c_str(), o.seeds);
  const auto family = eval::generate_family(split, o.seeds, types, o.jobs, o.pins);
  for (const auto& [name, values] : parse_grid(o.vary)) {
    std::printf("\n## %s (around %s)\n\n", name.c_str(), o.method.describe().c_str());
    print_header(types, name.c_str());
    std::vector<Method> methods;
    for (const std::string& v : values) methods.push_back(with(o.method, name, v));
    const auto results = eval::evaluate_family(family, methods, o.backend, o.jobs);
    for (size_t k = 0; k < values.size(); ++k) print_row(values[k], results[k]);
    if (o.per_scene) print_scenes(family, methods, results);
  }
}

void search(const SweepOptions& o, const std::vector<std::string>& types) {
  const auto grid = parse_grid(o.vary.empty() ? kSearchGrid : o.vary);
  const auto tuning = eval::generate_family(gen::Split::kTuning, o.seeds, types, o.jobs, o.pins);
  Method best = o.method;
  eval::FamilyResult best_result = eval::evaluate_family(tuning, best, o.backend, o.jobs);
  std::printf("\nStart: `%s`, objective %.4f (mean F %.3f, worst type %.3f)\n", best.describe().c_str(), objective(best_result),
              best_result.mean_f, best_result.worst_type_f);
  for (int round = 1; round <= o.rounds; ++round) {
    bool changed = false;
    std::printf("\n## Round %d\n", round);
    for (const auto& [name, values] : grid) {
      const std::string current = current_value(best, name);
      std::vector<Method> methods;
      std::vector<std::string> tried;
      for (const std::string& v : values) {
        if (v == current) continue;
        methods.push_back(with(best, name, v));
        tried.push_back(v);
      }
      const auto results = eval::evaluate_family(tuning, methods, o.backend, o.jobs);
      std::printf("\n### %s\n\n", name.c_str());
      print_header(types, name.c_str());
      print_row(current + " (current)", best_result);
      size_t winner = results.size();
      for (size_t k = 0; k < results.size(); ++k) {
        print_row(tried[k], results[k]);
        // A change must gain clearly: small gains on the tuning split are noise.
        const double bar = winner < results.size() ? objective(results[winner]) : objective(best_result) + 0.002;
        if (objective(results[k]) > bar) winner = k;
      }
      if (winner < results.size()) {
        best = methods[winner];
        best_result = results[winner];
        changed = true;
        std::printf("\n%s -> %s: objective %.4f\n", name.c_str(), tried[winner].c_str(), objective(best_result));
      }
    }
    if (!changed) break;
  }
  std::printf("\n## Result\n\n`%s`\n\nTuning split: mean F %.3f, worst type %.3f, objective %.4f.\n", best.describe().c_str(), best_result.mean_f,
              best_result.worst_type_f, objective(best_result));
  const auto validation = eval::generate_family(gen::Split::kValidation, o.seeds, types, o.jobs, o.pins);
  const std::vector<Method> check = {best, {"paper", {}}, {"evms", {}}};
  const auto results = eval::evaluate_family(validation, check, o.backend, o.jobs);
  std::printf("\n## Validation split (%d seeds a type)\n\n", o.seeds);
  print_header(types, "method");
  print_row("search result", results[0]);
  print_row("paper preset", results[1]);
  print_row("evms preset (the defaults)", results[2]);
}

}  // namespace

void register_sweep(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand("sweep", "measure the method's choices on the scene family; print Markdown tables");
  cmd->add_option("--seeds", o->seeds, "members of each scene type in a split")->default_val(o->seeds)->check(CLI::Range(1, 999));
  cmd->add_option("--types", o->types, "scene types (default: the family's and the paper's: paper-translation, paper-rotation, paper-6dof)")
      ->delimiter(',');
  cmd->add_option("--jobs", o->jobs, "threads")->default_val(o->jobs)->check(CLI::Range(1, 64));
  cmd->add_option("--vary", o->vary, "NAME=V1,V2,... (repeatable): one table per parameter, or the grid of --search");
  cmd->add_flag("--search", o->search, "coordinate ascent over the grid on the tuning split, checked on the validation split");
  cmd->add_option("--split", o->split, "the split --vary measures on, and the only split the presets are compared on when given (the search tunes on tuning and checks on validation)")
      ->default_val(o->split)
      ->check(CLI::IsMember({"tuning", "validation"}));
  cmd->add_flag("--per-scene", o->per_scene, "every member's F, IDF1, tracking errors (the Kalman estimate's and the raw centroid's), its estimates and their share within 2.5 px, MOTA and false tracks a frame too, then each sensor's members together: their mean F and their estimates pooled (presets and --vary)");
  cmd->add_option("--rounds", o->rounds, "passes of --search over the grid")->default_val(o->rounds)->check(CLI::Range(1, 20));
  cmd->add_option("--backend", o->backend, "implementation to measure")->default_val(o->backend);
  cmd->add_option("--sensor", o->pins.width, "the family's members on this sensor instead of the seed's draw: WxH")
      ->transform([o](std::string v) {
        const size_t x = v.find('x');
        try {
          if (x == std::string::npos) throw std::invalid_argument(v);
          o->pins.height = std::stoi(v.substr(x + 1));
          if (o->pins.height < 64 || o->pins.height > 4096) throw std::invalid_argument(v);
          return v.substr(0, x);
        } catch (const std::exception&) {
          throw CLI::ValidationError("expected WxH between 64 and 4096 px, got '" + v + "'");
        }
      })
      ->check(CLI::Range(64, 4096));
  cmd->add_option("--objects", o->pins.objects, "the family's members with this many shapes instead of the seed's draw")
      ->check(CLI::Range(1, 16));
  cmd->add_option("--noise-hz", o->pins.noise_hz, "the family's members with this background activity a pixel instead of the seed's draw")
      ->check(finite_in(0.0, 1000.0));
  add_method_options(*cmd, o->method);
  cmd->callback([o, cmd] {
    o->method_given = cmd->count("--preset") > 0 || !o->method.settings.empty();
    o->split_given = cmd->count("--split") > 0;
    const auto types = types_of(*o);
    for (const auto& t : types) eval::member_scene(t, 1);  // throws for an unknown type
    parse_grid(o->vary);  // a bad --vary is refused before any output
    std::printf("<!-- %s -->\n", invocation().c_str());
    if (o->search) search(*o, types);
    else if (!o->vary.empty()) one_at_a_time(*o, types);
    else compare_presets(*o, types);
  });
}

}  // namespace evms::cli

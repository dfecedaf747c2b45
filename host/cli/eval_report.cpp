#include "host/cli/eval_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "host/eval/evaluation.h"
#include "host/eval/kmeans.h"
#include "host/eval/parallel.h"
#include "host/eval/touching_objects.h"
#include "host/show/plot.h"
#include "host/read/event_source.h"
#include "host/show/frame_renderer.h"

namespace evms::eval {
namespace {

namespace fs = std::filesystem;
using show::BarChart;
using show::Plot;
using show::Series;
using show::render;

constexpr double kBinS = 0.05;   // clusters-over-time bins

struct Curve {
  std::vector<double> t, v;
};

// One implementation on one scene at one speed.
struct RunSummary {
  std::string scene, backend;
  double speed = 1;
  ClusteringScores ems, km, paper;
  bool has_km = false;
  IdentityScores identity, paper_identity;
  std::int64_t chunks = 0;
  TrackingReport tracking;
  double events_per_s = 0, kept_per_s = 0, kernel_per_s = 0, wall_s = 0, iterations = 0, clusters = 0;
  std::int64_t events = 0;
  Curve clusters_over_time, visible_over_time;
  std::vector<TrackUpdate> tracks;             // speed 1 only
  std::vector<std::int32_t> labels;            // speed 1 only: the tracks' ownership (tracking_metrics.h)
};

struct BandwidthPoint {
  std::string scene;
  double h = 0;
  double f = 0;
};

struct RealSummary {
  std::string file, format;
  SensorSize sensor;
  std::int64_t events = 0, kept = 0;
  double duration_s = 0, wall_s = 0, clusters = 0;
  std::int64_t tracks_confirmed = 0, tracks_started = 0, noise = 0;
  Curve clusters_over_time;
  std::string picture;
};

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

Curve bin_clusters(const std::vector<PacketSummary>& packets, TimeUs t0, double bin_s = kBinS) {
  std::map<long, std::pair<double, int>> bins;
  for (const PacketSummary& p : packets) {
    auto& b = bins[static_cast<long>(static_cast<double>(p.t_last - t0) * 1e-6 / bin_s)];
    b.first += p.clusters, b.second += 1;
  }
  Curve c;
  for (const auto& [k, v] : bins) c.t.push_back((k + 0.5) * bin_s), c.v.push_back(v.first / v.second);
  return c;
}

// A real recording's bins: 50 ms, or a 25th of a shorter recording (at least 1 ms), so that
// each curve has points enough to show a trend.
double real_bin_s(double duration_s) { return std::clamp(duration_s / 25.0, 0.001, kBinS); }

// Objects with at least 2 % of a bin's object events are visible in it.
Curve bin_visible(const Scene& s) {
  std::map<long, std::map<int, int>> bins;
  const TimeUs t0 = s.events.empty() ? 0 : s.events.front().t;
  for (size_t i = 0; i < s.events.size(); ++i) {
    if (s.truth[i] >= 0) ++bins[static_cast<long>(static_cast<double>(s.events[i].t - t0) * 1e-6 / kBinS)][s.truth[i]];
  }
  Curve c;
  for (const auto& [k, objects] : bins) {
    int total = 0, visible = 0;
    for (const auto& [o, n] : objects) total += n;
    for (const auto& [o, n] : objects) visible += n >= 0.02 * total;
    c.t.push_back((k + 0.5) * kBinS), c.v.push_back(visible);
  }
  return c;
}

RunSummary summarise(const Scene& scene, const std::string& name, double speed, const std::string& backend, const EvalOptions& o,
                     bool with_km) {
  const Evaluation e = evaluate(scene, o.method.resolve(scene.sensor), backend, o.chunking, o.tau_px);
  RunSummary r;
  r.scene = name, r.backend = backend, r.speed = speed;
  r.ems = e.scores, r.chunks = e.chunks;
  r.tracking = e.tracking;
  r.identity = identity_scores(scene.events, scene.truth, e.run.labels);
  r.events = static_cast<std::int64_t>(scene.events.size());
  r.events_per_s = e.events_per_s_sensor, r.kept_per_s = e.kept_per_s_sensor, r.wall_s = e.run.wall_s;
  const double span = scene.events.size() > 1 ? static_cast<double>(scene.events.back().t - scene.events.front().t) * 1e-6 : 1;
  r.kernel_per_s = static_cast<double>(e.run.stats.kernel_evaluations) / span;
  const auto packets = std::max<std::int64_t>(1, e.run.stats.packets);
  r.iterations = static_cast<double>(e.run.stats.iterations) / static_cast<double>(packets);
  r.clusters = static_cast<double>(e.run.stats.clusters) / static_cast<double>(packets);
  r.clusters_over_time = bin_clusters(e.run.packets, scene.events.empty() ? 0 : scene.events.front().t);
  r.visible_over_time = bin_visible(scene);
  if (speed == 1) r.tracks = e.run.tracks, r.labels = e.run.labels;
  if (with_km) {
    const auto km = kmeans_labels(scene.events, scene.truth, scene.sensor, o.method.resolve(scene.sensor), o.chunking, o.seed);
    r.km = score_chunks(scene, km, o.chunking);
    r.has_km = true;
    const RunResult paper = run_backend("golden", preset("paper", scene.sensor), scene.sensor, scene.events);
    r.paper = score_chunks(scene, paper.labels, o.chunking);
    r.paper_identity = identity_scores(scene.events, scene.truth, paper.labels);
  }
  return r;
}

Scene make_scene(const std::string& name, double speed, const EvalOptions& o) {
  gen::Motion motion;
  if (!gen::parse_motion(name, motion)) throw std::invalid_argument("--scenes: unknown scene '" + name + "'");
  return generate_scene(gen::paper_scene(motion, o.seed, o.duration_s, speed));
}

RealSummary run_real(const std::string& path, const EvalOptions& o, const std::string& fig_dir) {
  auto source = read::open_source(path, {});
  RealSummary r;
  r.file = fs::path(path).filename().string();
  r.format = source->info().format;
  r.sensor = source->info().sensor;
  std::vector<Event> events, batch(8192);
  while (size_t n = source->read(batch)) events.insert(events.end(), batch.begin(), batch.begin() + static_cast<long>(n));
  const RunResult run = run_backend("golden", o.method.resolve(r.sensor), r.sensor, events);
  r.events = static_cast<std::int64_t>(events.size());
  r.kept = run.stats.events_kept;
  r.wall_s = run.wall_s;
  r.duration_s = events.size() > 1 ? static_cast<double>(events.back().t - events.front().t) * 1e-6 : 0;
  r.clusters = run.stats.packets ? static_cast<double>(run.stats.clusters) / static_cast<double>(run.stats.packets) : 0;
  std::set<std::int32_t> confirmed;
  for (const TrackUpdate& u : run.tracks) {
    if (u.state == TrackState::kConfirmed) confirmed.insert(u.id);
  }
  r.tracks_confirmed = static_cast<std::int64_t>(confirmed.size());
  r.tracks_started = run.stats.tracks_started;
  r.noise = std::count(run.labels.begin(), run.labels.end(), kNoiseLabel);
  r.clusters_over_time = bin_clusters(run.packets, events.empty() ? 0 : events.front().t, real_bin_s(r.duration_s));
  // The picture: the last 20 ms of events (at least 2 % of the recording) and the last second
  // of trails, at the end of the recording.
  show::ViewStyle style;
  style.scale = r.sensor.width >= 640 ? 1 : (r.sensor.width >= 320 ? 2 : 3);
  style.event_window_us = std::max<TimeUs>(20000, static_cast<TimeUs>(r.duration_s * 1e6 * 0.02));
  style.track_fade_us = style.trail_us;  // the summary keeps every track of its last second
  show::FrameRenderer renderer(r.sensor, style);
  const TimeUs end = events.empty() ? 0 : events.back().t;
  for (size_t i = 0; i < events.size(); ++i) {
    if (end - events[i].t <= style.event_window_us) renderer.add(LabelledEvent{events[i], run.labels[i]});
  }
  for (const TrackUpdate& u : run.tracks) {
    if (end - u.t <= style.trail_us) renderer.add(u);
  }
  show::Canvas canvas = renderer.make_canvas();
  renderer.render(end, canvas, {r.file, "events of the last " + std::to_string(style.event_window_us / 1000) + " ms, trails of the last 1 s"});
  r.picture = fig_dir + "/real_" + fs::path(path).stem().string() + ".png";
  canvas.save_png(r.picture);
  return r;
}

// Steadiness of the cluster count: over stretches of at least 200 ms in which the number of
// visible objects does not change, the standard deviation of the 50 ms cluster means; and the
// mean absolute difference between clusters and visible objects over all bins.
struct Steadiness {
  double std_within = 0, mean_abs_diff = 0;
  int stretches = 0;
};

Steadiness steadiness(const RunSummary& r) {
  std::map<double, double> visible;
  for (size_t i = 0; i < r.visible_over_time.t.size(); ++i) visible[r.visible_over_time.t[i]] = r.visible_over_time.v[i];
  Steadiness s;
  double sum_var = 0, diff = 0;
  int n_diff = 0;
  std::vector<double> stretch;
  double stretch_visible = -1;
  auto close = [&] {
    if (stretch.size() * kBinS >= 0.2 - 1e-9) {
      double mean = 0, var = 0;
      for (double c : stretch) mean += c;
      mean /= stretch.size();
      for (double c : stretch) var += (c - mean) * (c - mean);
      sum_var += var / stretch.size();
      ++s.stretches;
    }
    stretch.clear();
  };
  for (size_t i = 0; i < r.clusters_over_time.t.size(); ++i) {
    auto it = visible.find(r.clusters_over_time.t[i]);
    if (it == visible.end()) continue;
    diff += std::abs(r.clusters_over_time.v[i] - it->second), ++n_diff;
    if (it->second != stretch_visible) close(), stretch_visible = it->second;
    stretch.push_back(r.clusters_over_time.v[i]);
  }
  close();
  s.std_within = s.stretches ? std::sqrt(sum_var / s.stretches) : 0;
  s.mean_abs_diff = n_diff ? diff / n_diff : 0;
  return s;
}

const RunSummary* find(const std::vector<RunSummary>& runs, const std::string& scene, double speed, const std::string& backend) {
  for (const RunSummary& r : runs) {
    if (r.scene == scene && r.speed == speed && r.backend == backend) return &r;
  }
  return nullptr;
}

std::string mark(bool ok) { return ok ? "met" : "**missed**"; }

// What the labelled events' centre itself scores against the outlines' centres at the same
// estimates: the part of a tracking error against the outline that a centroid cannot remove.
std::string floor_note(const ErrorStats& e) {
  return " (the labelled events' centre itself: " + fmt("%.2f", e.mean) + " px, " + fmt("%.0f %%", 100 * e.within) + ")";
}

// The targets' row for tracking against the labelled events' centres (the paper's ground truth).
std::string paper_truth_row(const std::string& where, const ErrorStats& e) {
  return "| the same against the labelled events' centre (the paper's) | " + where + " | " + fmt("%.2f", e.mean) + " px, " +
         fmt("%.0f %%", 100 * e.within) + " | " + mark(e.mean <= 1.5 && e.within >= 0.9) + " |\n";
}

// The targets' row for the same against the labelled events' centres, one track per object at a
// time (CLEAR MOT's MOTP: a second track on an object is a false positive, counted in MOTA).
std::string mot_row(const std::string& where, const ClearMot& m) {
  return "| the same, one track per object at a time (CLEAR MOT's MOTP; MOTA " + fmt("%.3f", m.mota()) + ") | " + where + " | " +
         fmt("%.2f", m.to_events.mean) + " px, " + fmt("%.0f %%", 100 * m.to_events.within) + " | " +
         mark(m.to_events.mean <= 1.5 && m.to_events.within >= 0.9) + " |\n";
}

}  // namespace

std::string write_report(const EvalOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const std::string fig_dir = o.out + "/fig";
  fs::create_directories(fig_dir);

  // Phase 1: the speed-1 scenes, kept for the bandwidth sweep and the tracking plots.
  std::vector<Scene> base(o.scenes.size());
  parallel_for(base.size(), o.jobs, [&](size_t i) { base[i] = make_scene(o.scenes[i], 1.0, o); });

  // Phase 2: everything else, in parallel.
  // Every recording of the folder, ROS 2 bag folders included; what is not one is named with
  // the reason, never passed over in silence.
  std::vector<std::string> real_files;
  std::vector<std::pair<std::string, std::string>> real_skipped;  // name, why
  if (!o.real_dir.empty() && fs::is_directory(o.real_dir)) {
    const std::set<std::string> event_files = {".aedat4", ".aedat", ".raw", ".dat", ".txt", ".csv", ".db3"};
    for (const auto& entry : fs::directory_iterator(o.real_dir)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_directory()) {
        // A bag, or a folder of bags (as ros2/NAME/).
        std::vector<std::string> bags;
        if (fs::exists(entry.path() / "metadata.yaml")) bags.push_back(entry.path().string());
        for (const auto& inner : fs::directory_iterator(entry.path())) {
          if (inner.is_directory() && fs::exists(inner.path() / "metadata.yaml")) bags.push_back(inner.path().string());
        }
        if (bags.empty()) real_skipped.emplace_back(name + "/", "a folder that holds no ROS 2 bag (metadata.yaml)");
        real_files.insert(real_files.end(), bags.begin(), bags.end());
      } else if (event_files.count(entry.path().extension().string())) {
        real_files.push_back(entry.path().string());
      } else {
        real_skipped.emplace_back(name, "not an event file (" + std::string(entry.path().has_extension() ? "extension " + entry.path().extension().string() : "no extension") + ")");
      }
    }
    std::sort(real_files.begin(), real_files.end());
    std::sort(real_skipped.begin(), real_skipped.end());
  }
  struct Task {
    enum Kind { kSpeed, kBandwidth, kReal } kind;
    size_t scene = 0;
    double value = 0;
    size_t real = 0;
  };
  std::vector<Task> tasks;
  for (size_t s = 0; s < o.scenes.size(); ++s) {
    for (double v : o.speeds) tasks.push_back({Task::kSpeed, s, v, 0});
    for (double h : o.bandwidths) tasks.push_back({Task::kBandwidth, s, h, 0});
  }
  for (size_t i = 0; i < real_files.size(); ++i) tasks.push_back({Task::kReal, 0, 0, i});
  // Longest first: higher speeds make more events.
  std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) {
    return (a.kind == Task::kSpeed ? a.value : 1.0) > (b.kind == Task::kSpeed ? b.value : 1.0);
  });

  std::mutex mutex;
  std::vector<RunSummary> runs;
  std::vector<BandwidthPoint> bandwidth_points;
  std::vector<RealSummary> reals(real_files.size());
  parallel_for(tasks.size(), o.jobs, [&](size_t i) {
    const Task& t = tasks[i];
    if (t.kind == Task::kSpeed) {
      Scene fast;
      if (t.value != 1) fast = make_scene(o.scenes[t.scene], t.value, o);
      const Scene& scene = t.value == 1 ? base[t.scene] : fast;
      for (const std::string& backend : o.backends) {
        RunSummary r = summarise(scene, o.scenes[t.scene], t.value, backend, o, t.value == 1 && backend == o.backends[0]);
        std::lock_guard lock(mutex);
        runs.push_back(std::move(r));
      }
    } else if (t.kind == Task::kBandwidth) {
      Params p = o.method.resolve(base[t.scene].sensor);
      p.bandwidth = t.value;
      const Evaluation e = evaluate(base[t.scene], p, o.backends[0], o.chunking, o.tau_px);
      std::lock_guard lock(mutex);
      bandwidth_points.push_back({o.scenes[t.scene], t.value, e.scores.f});
    } else {
      try {
        reals[t.real] = run_real(real_files[t.real], o, fig_dir);
      } catch (const read::InputError& e) {
        std::lock_guard lock(mutex);
        real_skipped.emplace_back(fs::path(real_files[t.real]).filename().string(), e.what());
      }
    }
  });
  // Recordings that could not be read are reported with the others that were skipped.
  reals.erase(std::remove_if(reals.begin(), reals.end(), [](const RealSummary& r) { return r.file.empty(); }), reals.end());
  for (const auto& [name, why] : real_skipped) std::fprintf(stderr, "eval: skipped %s: %s\n", name.c_str(), why.c_str());

  // The scene family's validation split: the method, the paper preset and K-means.
  std::vector<FamilyScene> family;
  std::vector<FamilyResult> family_results;
  std::vector<ClusteringScores> family_km, family_touching;
  double family_km_mean = 0, family_touching_mean = 0;
  if (o.family_seeds > 0) {
    std::vector<std::string> types = o.family_types;
    if (types.empty()) types.assign(gen::family_types().begin(), gen::family_types().end());
    family = generate_family(gen::Split::kValidation, o.family_seeds, types, o.jobs);
    family_results = evaluate_family(family, {o.method, Method{"paper", {}}}, o.backends[0], o.jobs);
    family_km.resize(family.size());
    family_touching.resize(family.size());
    parallel_for(family.size(), o.jobs, [&](size_t i) {
      const Scene& s = family[i].scene;
      family_km[i] = score_chunks(s, kmeans_labels(s.events, s.truth, s.sensor, o.method.resolve(s.sensor), kFamilyChunking, o.seed), kFamilyChunking);
      family_touching[i] = score_chunks(s, merge_touching_objects(s.events, s.truth, kFamilyChunking, kTouchingReachPx), kFamilyChunking);
    });
    for (size_t i = 0; i < family.size(); ++i) {
      family_km_mean += family_km[i].f / static_cast<double>(family.size());
      family_touching_mean += family_touching[i].f / static_cast<double>(family.size());
    }
  }

  // ---- figures ----
  const std::string& first_backend = o.backends[0];
  for (size_t s = 0; s < o.scenes.size(); ++s) {
    const RunSummary* r = find(runs, o.scenes[s], 1, first_backend);
    if (!r) continue;
    render(Plot{"Clusters over time: " + o.scenes[s], "time (s)", "clusters per packet",
                {{"E-MS clusters (mean per 50 ms)", r->clusters_over_time.t, r->clusters_over_time.v, "lines lw 2"},
                 {"objects visible", r->visible_over_time.t, r->visible_over_time.v, "steps dt 2 lw 2"}},
                false, std::pair{0.0, 12.0}},
           fig_dir + "/clusters_" + o.scenes[s]);
  }
  {
    Plot ops{"Operations per second against speed", "speed factor", "operations per second", {}, true, std::nullopt};
    Plot fspeed{"F-measure against speed", "speed factor", "F", {}, false, std::pair{0.5, 1.0}};
    double frame_ops = 0;
    for (const auto& scene_name : o.scenes) {
      Series events{"E-MS events/s, " + scene_name, {}, {}, "linespoints lw 2 pt 7"};
      Series kernel{"E-MS kernel evaluations/s, " + scene_name, {}, {}, "linespoints dt 3 pt 6"};
      Series f{scene_name, {}, {}, "linespoints lw 2 pt 7"};
      for (double v : o.speeds) {
        if (const RunSummary* r = find(runs, scene_name, v, first_backend)) {
          events.x.push_back(v), events.y.push_back(r->kept_per_s);
          kernel.x.push_back(v), kernel.y.push_back(r->kernel_per_s);
          f.x.push_back(v), f.y.push_back(r->ems.f);
        }
      }
      ops.series.push_back(events);
      ops.series.push_back(kernel);
      fspeed.series.push_back(f);
    }
    if (!base.empty()) frame_ops = 30.0 * base[0].sensor.width * base[0].sensor.height;
    ops.series.push_back({"frame-based, 30 fps x W x H", {o.speeds.front(), o.speeds.back()}, {frame_ops, frame_ops}, "lines lw 3 lc rgb 'red'"});
    render(ops, fig_dir + "/ops_vs_speed");
    render(fspeed, fig_dir + "/f_vs_speed");
  }
  {
    Plot fh{"F-measure against bandwidth h (the other parameters the method's)", "h", "F", {}, false, std::pair{0.0, 1.0}};
    for (const auto& scene_name : o.scenes) {
      Series f{scene_name, {}, {}, "linespoints lw 2 pt 7"};
      std::vector<BandwidthPoint> pts;
      for (const auto& p : bandwidth_points) if (p.scene == scene_name) pts.push_back(p);
      std::sort(pts.begin(), pts.end(), [](auto& a, auto& b) { return a.h < b.h; });
      for (const auto& p : pts) f.x.push_back(p.h), f.y.push_back(p.f);
      fh.series.push_back(f);
    }
    render(fh, fig_dir + "/f_vs_bandwidth");
  }
  for (size_t s = 0; s < o.scenes.size(); ++s) {
    const RunSummary* r = find(runs, o.scenes[s], 1, first_backend);
    if (!r) continue;
    const Scene& scene = base[s];
    std::map<std::int32_t, int> owner;
    for (const ObjectTracking& ot : r->tracking.objects) for (std::int32_t id : ot.tracks) owner[id] = ot.object;
    Plot px{"x", "time (s)", "x (px)", {}, false, std::nullopt, 900, 360, true};
    Plot py{"y", "time (s)", "y (px)", {}, false, std::nullopt, 900, 360, true};
    const TimeUs t0 = scene.events.empty() ? 0 : scene.events.front().t;
    for (size_t obj = 0; obj < scene.object_names.size(); ++obj) {
      // One colour per object, as the viewer gives tracks (gnuplot's own list repeats after 8).
      const show::Rgb rgb = show::label_colour(static_cast<std::int32_t>(obj));
      const std::string lc = " lc rgb '" + fmt("#%06x", (rgb.r << 16) | (rgb.g << 8) | rgb.b) + "'";
      Series gx{std::to_string(obj) + " " + scene.object_names[obj], {}, {}, "lines dt 2 lw 1.5" + lc};
      Series gy = gx;
      TimeUs last = -1;
      for (const auto& c : scene.centres) {
        if (c.object != static_cast<int>(obj)) continue;
        const double t = static_cast<double>(c.t - t0) * 1e-6;
        if (last >= 0 && c.t - last > 1000) {  // a gap: the object was not wholly in view
          gx.x.push_back(NAN), gx.y.push_back(NAN), gy.x.push_back(NAN), gy.y.push_back(NAN);
        }
        last = c.t;
        gx.x.push_back(t), gx.y.push_back(c.x), gy.x.push_back(t), gy.y.push_back(c.y);
      }
      Series kx{"", {}, {}, "points pt 7 ps 0.25" + lc}, ky = kx, rx{"", {}, {}, "points pt 1 ps 0.2" + lc}, ry = rx;
      for (const TrackUpdate& u : r->tracks) {
        auto it = owner.find(u.id);
        if (it == owner.end() || it->second != static_cast<int>(obj)) continue;
        const double t = static_cast<double>(u.t - t0) * 1e-6;
        kx.x.push_back(t), kx.y.push_back(u.x), ky.x.push_back(t), ky.y.push_back(u.y);
        rx.x.push_back(t), rx.y.push_back(u.zx), ry.x.push_back(t), ry.y.push_back(u.zy);
      }
      px.series.insert(px.series.end(), {gx, rx, kx});
      py.series.insert(py.series.end(), {gy, ry, ky});
    }
    render(std::vector<Plot>{px, py},
           "Tracked position against ground truth, " + o.scenes[s] + " (dashed: truth, +: raw centroid, dots: Kalman)",
           fig_dir + "/tracks_" + o.scenes[s]);

    // Share within tau as a function of tau, Kalman against raw.
    Plot share{"Share of estimates within tau, " + o.scenes[s], "tau (px)", "share", {}, false, std::pair{0.0, 1.0}};
    Series sk{"Kalman", {}, {}, "lines lw 2"}, sr{"raw centroid", {}, {}, "lines lw 2 dt 2"};
    for (double tau = 0; tau <= 8.0001; tau += 0.25) {
      const TrackingReport at = tracking_report(r->tracks, scene.centres, static_cast<int>(scene.object_names.size()), tau, 15.0, 20000,
                                                {scene.events, scene.truth, r->labels});
      sk.x.push_back(tau), sk.y.push_back(at.all_kalman.within);
      sr.x.push_back(tau), sr.y.push_back(at.all_raw.within);
    }
    share.series = {sk, sr, {"tau = " + fmt("%.1f", o.tau_px) + " px", {o.tau_px, o.tau_px}, {0, 1}, "lines lc rgb 'red'"}};
    render(share, fig_dir + "/within_tau_" + o.scenes[s]);
  }
  if (!reals.empty()) {
    Plot c{"Clusters over time, real recordings (bins of a 25th of each recording, at most 50 ms)", "time (s)", "clusters per packet", {},
           false, std::nullopt};
    for (const RealSummary& r : reals) c.series.push_back({r.file, r.clusters_over_time.t, r.clusters_over_time.v, "lines lw 2"});
    render(c, fig_dir + "/clusters_real");
  }

  // ---- report.md ----
  std::ostringstream md;
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  md << "# evms evaluation report\n\nGenerated " << date << " by `" << o.command_line << "`, method `" << o.method.describe()
     << "`.\n\nThe paper's scenes: the shapes poster at 240x180 seen by a translating, rotating or 6-DoF camera, " << o.duration_s
     << " s each, seed " << o.seed << ", with background noise, threshold mismatch, refractory period and timestamp jitter "
        "(`host/gen/scene_generator.h`). Clustering scores are means over "
     << (o.chunking.kind == Chunking::Kind::kEvents ? std::to_string(o.chunking.size) + "-event" : std::to_string(o.chunking.size / 1000) + " ms")
     << " chunks; noise (-1) counts as singleton clusters in truth and prediction (`host/eval/clustering_metrics.h`). "
        "IDF1 is over the whole scene, in events (`host/eval/identity_metrics.h`). E-MS is the method given; the paper preset is "
        "the authors' published code (`--preset paper`); KM is K-means given the true number of objects in each chunk.\n\n";

  md << "## Table I: clustering accuracy\n\n| scene | method | ARI | NMI | Precision | Recall | F | IDF1 | ID switches | chunks |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& scene_name : o.scenes) {
    for (const std::string& backend : o.backends) {
      if (const RunSummary* r = find(runs, scene_name, 1, backend)) {
        md << "| " << scene_name << " | E-MS (" << backend << ") | " << fmt("%.3f", r->ems.ari) << " | " << fmt("%.3f", r->ems.nmi) << " | "
           << fmt("%.3f", r->ems.precision) << " | " << fmt("%.3f", r->ems.recall) << " | **" << fmt("%.3f", r->ems.f) << "** | "
           << fmt("%.3f", r->identity.idf1) << " | " << r->identity.id_switches << " | " << r->chunks << " |\n";
      }
    }
    if (const RunSummary* r = find(runs, scene_name, 1, first_backend); r && r->has_km) {
      md << "| " << scene_name << " | paper preset | " << fmt("%.3f", r->paper.ari) << " | " << fmt("%.3f", r->paper.nmi) << " | "
         << fmt("%.3f", r->paper.precision) << " | " << fmt("%.3f", r->paper.recall) << " | " << fmt("%.3f", r->paper.f) << " | "
         << fmt("%.3f", r->paper_identity.idf1) << " | " << r->paper_identity.id_switches << " | |\n";
      md << "| " << scene_name << " | KM (true k) | " << fmt("%.3f", r->km.ari) << " | " << fmt("%.3f", r->km.nmi) << " | "
         << fmt("%.3f", r->km.precision) << " | " << fmt("%.3f", r->km.recall) << " | " << fmt("%.3f", r->km.f) << " | | | |\n";
    }
  }
  md << "\nThe paper's Table I, for comparison: E-MS F 0.951 / 0.955 / 0.926 on shapes_translation / rotation / 6dof, "
        "KM 0.815 / 0.828 / 0.763.\n\n";

  if (!family.empty()) {
    md << "## The scene family\n\nThe validation split of the scene family (`host/gen/family.h`), " << o.family_seeds
       << " members of each type, scored as above over 10 ms chunks. The method's choices were made on the tuning split "
          "(`docs/sweep.md`). \"Touching merged\" is the truth itself with the objects whose events come within "
       << fmt("%g", kTouchingReachPx) << " px of each other in a chunk merged (`host/eval/touching_objects.h`): what a clustering "
          "that holds touching objects together scores at best.\n\n| type | E-MS F | paper preset F | KM (true k) F | touching merged F | "
          "E-MS IDF1 | paper IDF1 |\n|---|---|---|---|---|---|---|\n";
    for (size_t t = 0; t < family_results[0].types.size(); ++t) {
      const std::string& type = family_results[0].types[t].type;
      double km = 0, touching = 0, idf1 = 0, idf1_paper = 0;
      int n = 0;
      for (size_t i = 0; i < family.size(); ++i) {
        if (family[i].type != type) continue;
        km += family_km[i].f, touching += family_touching[i].f, ++n;
        idf1 += family_results[0].scenes[i].identity.idf1, idf1_paper += family_results[1].scenes[i].identity.idf1;
      }
      md << "| " << type << " | **" << fmt("%.3f", family_results[0].types[t].f) << "** | " << fmt("%.3f", family_results[1].types[t].f)
         << " | " << fmt("%.3f", km / n) << " | " << fmt("%.3f", touching / n) << " | " << fmt("%.3f", idf1 / n) << " | "
         << fmt("%.3f", idf1_paper / n) << " |\n";
    }
    md << "| all | **" << fmt("%.3f", family_results[0].mean_f) << "** | " << fmt("%.3f", family_results[1].mean_f) << " | " << fmt("%.3f", family_km_mean)
       << " | " << fmt("%.3f", family_touching_mean) << " | " << fmt("%.3f", family_results[0].idf1) << " | " << fmt("%.3f", family_results[1].idf1) << " |\n\n"
       << "Tracking error over the split: E-MS " << fmt("%.2f", family_results[0].tracking.mean) << " px ("
       << fmt("%.0f %%", 100 * family_results[0].tracking.within) << " within 2.5 px), paper preset " << fmt("%.2f", family_results[1].tracking.mean)
       << " px (" << fmt("%.0f %%", 100 * family_results[1].tracking.within) << "). Against the centre of each object's labelled events (the "
       << "paper's ground truth): E-MS " << fmt("%.2f", family_results[0].tracking_to_events.mean) << " px ("
       << fmt("%.0f %%", 100 * family_results[0].tracking_to_events.within) << "), paper preset "
       << fmt("%.2f", family_results[1].tracking_to_events.mean) << " px (" << fmt("%.0f %%", 100 * family_results[1].tracking_to_events.within)
       << "). The tracks' velocities against the objects' true velocities (the central difference of the true centre): E-MS "
       << fmt("%.1f", family_results[0].velocity.mean) << " px/s, paper preset " << fmt("%.1f", family_results[1].velocity.mean) << " px/s.\n\n";
    const auto mot_text = [](const ClearMot& m) {
      return "MOTA " + fmt("%.3f", m.mota()) + ", MOTP " + fmt("%.2f", m.to_centres.mean) + " px (" + fmt("%.2f", m.to_events.mean) +
             " px to the labelled events' centre, " + fmt("%.0f %%", 100 * m.to_events.within) + " within 2.5 px), " +
             fmt("%.2f", m.false_positives_per_frame()) + " false tracks a frame and " + fmt("%.2f", m.ignored_per_frame()) +
             " on objects without a true centre (ignored)";
    };
    md << "CLEAR MOT over the split (`host/eval/tracking_metrics.h`: one track per object at a time, 10 ms frames): E-MS "
       << mot_text(family_results[0].mot) << "; paper preset " << mot_text(family_results[1].mot) << ".\n\n";
  }

  md << "## Targets\n\n| target | scene | reached | |\n|---|---|---|---|\n";
  for (const auto& scene_name : o.scenes) {
    const RunSummary* r = find(runs, scene_name, 1, first_backend);
    if (!r) continue;
    md << "| E-MS F >= 0.95 | " << scene_name << " | " << fmt("%.3f", r->ems.f) << " | " << mark(r->ems.f >= 0.95) << " |\n";
    if (r->has_km) {
      md << "| E-MS F >= the paper preset's | " << scene_name << " | " << fmt("%+.3f", r->ems.f - r->paper.f) << " | "
         << mark(r->ems.f >= r->paper.f) << " |\n";
      md << "| E-MS beats KM by >= 0.10 F | " << scene_name << " | " << fmt("%+.3f", r->ems.f - r->km.f) << " | "
         << mark(r->ems.f - r->km.f >= 0.10) << " |\n";
    }
    md << "| mean tracking error <= 1.5 px | " << scene_name << " | " << fmt("%.2f", r->tracking.all_kalman.mean) << " px" << floor_note(r->tracking.all_events_centre)
       << " | " << mark(r->tracking.all_kalman.mean <= 1.5) << " |\n";
    md << "| >= 90 % of estimates within 2.5 px | " << scene_name << " | " << fmt("%.0f %%", 100 * r->tracking.all_kalman.within)
       << " | " << mark(r->tracking.all_kalman.within >= 0.9) << " |\n";
    md << paper_truth_row(scene_name, r->tracking.all_kalman_events);
    md << mot_row(scene_name, r->tracking.mot);
    const Steadiness st = steadiness(*r);
    md << "| steady cluster count (std <= 0.5 while no object enters or leaves) | " << scene_name << " | std "
       << fmt("%.2f", st.std_within) << " over " << st.stretches << " stretches; mean abs(clusters - visible objects) "
       << fmt("%.2f", st.mean_abs_diff) << " | " << mark(st.stretches > 0 && st.std_within <= 0.5) << " |\n";
  }
  if (!family.empty()) {
    const auto& e = family_results[0];
    const auto& paper = family_results[1];
    bool no_type_below = true;
    for (size_t t = 0; t < e.types.size(); ++t) no_type_below = no_type_below && e.types[t].f >= paper.types[t].f;
    md << "| family mean F >= the paper preset's + 0.05 | validation split | " << fmt("%+.3f", e.mean_f - paper.mean_f) << " | "
       << mark(e.mean_f >= paper.mean_f + 0.05) << " |\n";
    md << "| no family type below the paper preset | validation split | worst type " << fmt("%.3f", e.worst_type_f) << " | "
       << mark(no_type_below) << " |\n";
    md << "| family tracking error <= 1.5 px, >= 90 % within 2.5 px | validation split | " << fmt("%.2f", e.tracking.mean) << " px, "
       << fmt("%.0f %%", 100 * e.tracking.within) << floor_note(e.events_centre) << " | " << mark(e.tracking.mean <= 1.5 && e.tracking.within >= 0.9) << " |\n";
    md << paper_truth_row("validation split", e.tracking_to_events);
    md << mot_row("validation split", e.mot);
  }
  md << "\nTracking errors are against each object's true centre (the centroid of its outline), and against the centre of mass "
        "of the object's labelled events in the 10 ms around the estimate's time (the paper's ground truth, \"the ground-truth labeled cluster "
        "center\"). The estimate is the Kalman-filtered centre of mass of the events that fired, which is not the outline's "
        "centroid when some edges fire more than others (an edge parallel to the motion does not fire, and under zoom or "
        "rotation the edges farther from the centre of motion move faster and fire more) or the object is partly occluded; "
        "the bracket after a tracking error against the true centre gives the labelled events' centre's own distance from it at "
        "the same estimates.\n\n";

  md << "## Clusters over time\n\nMean clusters per packet in 50 ms bins, against the number of objects with events in the bin. "
        "The paper's Fig. 5a: a steady count while no object enters or leaves.\n\n";
  for (const auto& scene_name : o.scenes) md << "![clusters " << scene_name << "](fig/clusters_" << scene_name << ".svg)\n";

  md << "\n## Cost against speed\n\nThe paper counts frame-based mean shift as 30 fps x W x H operations per second and the "
        "event-based method as the events it processes. Kernel evaluations (packet size x packet size x iterations per packet) "
        "are the cost a hardware designer pays, shown for honesty.\n\n![ops](fig/ops_vs_speed.svg)\n\n"
        "| scene | speed | events/s in | events/s clustered | kernel evaluations/s | frame-based ops/s | reduction (paper's count) | F |\n"
        "|---|---|---|---|---|---|---|---|\n";
  const double frame_ops = base.empty() ? 0 : 30.0 * base[0].sensor.width * base[0].sensor.height;
  for (const auto& scene_name : o.scenes) {
    for (double v : o.speeds) {
      if (const RunSummary* r = find(runs, scene_name, v, first_backend)) {
        md << "| " << scene_name << " | " << v << " | " << fmt("%.0f", r->events_per_s) << " | " << fmt("%.0f", r->kept_per_s) << " | "
           << fmt("%.3g", r->kernel_per_s) << " | " << fmt("%.0f", frame_ops) << " | " << fmt("%.0f %%", 100 * (1 - r->kept_per_s / frame_ops))
           << " | " << fmt("%.3f", r->ems.f) << " |\n";
      }
    }
  }
  md << "\n![F against speed](fig/f_vs_speed.svg)\n\n## F against bandwidth\n\n![F against h](fig/f_vs_bandwidth.svg)\n\n";

  md << "## Tracking\n\nEach update of a track is an estimate of the object whose events the track labelled most in the 10 ms "
        "around it; an object's tracks are those whose events were mostly its own (`host/eval/tracking_metrics.h`). Kalman: the "
        "filtered estimate written to tracks.csv; raw: the cluster's centre of mass of the same update.\n\n";
  for (size_t s = 0; s < o.scenes.size(); ++s) {
    const RunSummary* r = find(runs, o.scenes[s], 1, first_backend);
    if (!r) continue;
    md << "### " << o.scenes[s] << "\n\n![tracks](fig/tracks_" << o.scenes[s] << ".png)\n\nShare of estimates within tau, "
       << "Kalman against raw centroid:\n\n![within](fig/within_tau_" << o.scenes[s] << ".svg)\n\n| object | tracks | estimates | Kalman error px | Kalman within " << o.tau_px << " px | raw error px | raw within | coverage |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const ObjectTracking& ot : r->tracking.objects) {
      md << "| " << ot.object << " " << base[s].object_names[static_cast<size_t>(ot.object)] << " | " << ot.tracks.size() << " | "
         << ot.kalman.samples << " | " << fmt("%.2f", ot.kalman.mean) << " ± " << fmt("%.2f", ot.kalman.std) << " | "
         << fmt("%.0f %%", 100 * ot.kalman.within) << " | " << fmt("%.2f", ot.raw.mean) << " ± " << fmt("%.2f", ot.raw.std) << " | "
         << fmt("%.0f %%", 100 * ot.raw.within) << " | " << fmt("%.0f %%", 100 * ot.coverage) << " |\n";
    }
    md << "| all | | " << r->tracking.all_kalman.samples << " | " << fmt("%.2f", r->tracking.all_kalman.mean) << " | "
       << fmt("%.0f %%", 100 * r->tracking.all_kalman.within) << " | " << fmt("%.2f", r->tracking.all_raw.mean) << " | "
       << fmt("%.0f %%", 100 * r->tracking.all_raw.within) << " | |\n\nUpdates of tracks that belong to no object: "
       << r->tracking.spurious_updates << ".\n\n";
  }

  if (o.backends.size() > 1) {
    md << "## Backends side by side\n\n| scene | speed | backend | F | ARI | track error px | within 2.5 px | wall s |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& scene_name : o.scenes) {
      for (double v : o.speeds) {
        for (const auto& b : o.backends) {
          if (const RunSummary* r = find(runs, scene_name, v, b)) {
            md << "| " << scene_name << " | " << v << " | " << b << " | " << fmt("%.3f", r->ems.f) << " | " << fmt("%.3f", r->ems.ari) << " | "
               << fmt("%.2f", r->tracking.all_kalman.mean) << " | " << fmt("%.0f %%", 100 * r->tracking.all_kalman.within) << " | "
               << fmt("%.2f", r->wall_s) << " |\n";
          }
        }
      }
    }
    md << "\n";
  }

  md << "## Real recordings\n\n";
  if (reals.empty()) {
    md << "No real recordings were found (" << (o.real_dir.empty() ? std::string("none given") : o.real_dir) << ").\n";
  } else {
    md << "From `" << o.real_dir << "`, golden backend, the method given. Events/s processed is wall clock on one core, "
          "reading excluded.\n\n| recording | format | sensor | events | duration s | kept by the filter | labelled noise | "
          "events/s processed | clusters per packet | tracks started | confirmed |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RealSummary& r : reals) {
      md << "| " << r.file << " | " << r.format << " | " << r.sensor.width << "x" << r.sensor.height << " | " << r.events << " | "
         << fmt("%.3f", r.duration_s) << " | " << fmt("%.0f %%", r.events ? 100.0 * r.kept / r.events : 0) << " | "
         << fmt("%.0f %%", r.events ? 100.0 * r.noise / r.events : 0) << " | " << fmt("%.0f", r.wall_s > 0 ? r.events / r.wall_s : 0)
         << " | " << fmt("%.2f", r.clusters) << " | " << r.tracks_started << " | " << r.tracks_confirmed << " |\n";
    }
    md << "\n![clusters real](fig/clusters_real.svg)\n\n";
    for (const RealSummary& r : reals) md << "![" << r.file << "](fig/" << fs::path(r.picture).filename().string() << ")\n\n";
  }
  if (!real_skipped.empty()) {
    md << "Skipped in `" << o.real_dir << "`:\n\n";
    for (const auto& [name, why] : real_skipped) md << "- " << name << ": " << why << "\n";
    md << "\n";
  }
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  md << "\n---\nThe evaluation took " << fmt("%.0f", took) << " s with " << o.jobs << " threads.\n";

  const std::string path = o.out + "/report.md";
  std::ofstream(path) << md.str();
  return path;
}

}  // namespace evms::eval

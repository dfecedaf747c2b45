#include "host/eval/family_eval.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "host/eval/parallel.h"

namespace evms::eval {

std::vector<FamilyScene> generate_family(gen::Split split, int seeds, const std::vector<std::string>& types, int jobs,
                                         const gen::FamilyPins& pins) {
  std::vector<FamilyScene> family;
  for (const std::string& type : types) {
    for (int k = 0; k < seeds; ++k) family.push_back({type, gen::split_seed(split, k), {}});
  }
  parallel_for(family.size(), jobs, [&](size_t i) { family[i].scene = generate_scene(member_scene(family[i].type, family[i].seed, pins)); });
  return family;
}

gen::SceneConfig member_scene(const std::string& type, std::uint64_t seed, const gen::FamilyPins& pins) {
  const std::string paper = "paper-";
  if (type.rfind(paper, 0) == 0) {
    gen::Motion motion;
    if (!gen::parse_motion(type.substr(paper.size()), motion)) throw std::invalid_argument("unknown scene type '" + type + "'");
    return gen::paper_scene(motion, seed, kPaperSceneSeconds);
  }
  return gen::family_scene(type, seed, pins);
}

namespace {

SceneResult run_member(const FamilyScene& member, const Method& method, const std::string& backend) {
  const Scene& scene = member.scene;
  const Params params = method.resolve(scene.sensor);
  SceneResult r;
  const RunResult run = run_backend(backend, params, scene.sensor, scene.events);
  r.scores = score_chunks(scene, run.labels, kFamilyChunking);
  std::vector<TrackUpdate> confirmed;
  for (const TrackUpdate& u : run.tracks) {
    if (u.state == TrackState::kConfirmed) confirmed.push_back(u);
  }
  r.tracking = scene_tracking(confirmed, scene, run.labels);
  r.identity = identity_scores(scene.events, scene.truth, run.labels);
  r.events = static_cast<std::int64_t>(scene.events.size());
  r.noise_share = r.events ? static_cast<double>(std::count(run.labels.begin(), run.labels.end(), kNoiseLabel)) / static_cast<double>(r.events) : 0;
  r.kernel_evaluations = run.stats.kernel_evaluations;
  r.wall_s = run.wall_s;
  return r;
}

// Error statistics pooled over scenes, each weighing by its samples.
class PooledErrors {
 public:
  void add(const ErrorStats& e) {
    const auto n = static_cast<double>(e.samples);
    samples_ += e.samples;
    sum_ += e.mean * n;
    sum_sq_ += (e.std * e.std + e.mean * e.mean) * n;
    within_ += e.within * n;
  }
  ErrorStats stats() const {
    ErrorStats s;
    s.samples = samples_;
    if (samples_ == 0) return s;
    const auto n = static_cast<double>(samples_);
    s.mean = sum_ / n;
    s.std = std::sqrt(std::max(0.0, sum_sq_ / n - s.mean * s.mean));
    s.within = within_ / n;
    return s;
  }

 private:
  std::int64_t samples_ = 0;
  double sum_ = 0, sum_sq_ = 0, within_ = 0;
};

FamilyResult summarise(const std::vector<FamilyScene>& family, std::vector<SceneResult> scenes) {
  FamilyResult out;
  std::map<std::string, TypeSummary> by_type;
  std::vector<std::string> order;
  std::int64_t events = 0, evaluations = 0, switches = 0, objects = 0;
  double wall = 0;
  PooledErrors to_centres, to_events, events_centre, velocity, mot_to_centres, mot_to_events;
  for (size_t i = 0; i < family.size(); ++i) {
    const SceneResult& r = scenes[i];
    auto [it, fresh] = by_type.try_emplace(family[i].type);
    if (fresh) order.push_back(family[i].type), it->second.type = family[i].type, it->second.worst_f = 1;
    TypeSummary& t = it->second;
    ++t.scenes;
    t.f += r.scores.f;
    t.ari += r.scores.ari;
    t.worst_f = std::min(t.worst_f, r.scores.f);
    out.mean_f += r.scores.f;
    out.mean_ari += r.scores.ari;
    out.idf1 += r.identity.idf1;
    switches += r.identity.id_switches;
    objects += r.identity.objects;
    events += r.events;
    evaluations += r.kernel_evaluations;
    wall += r.wall_s;
    to_centres.add(r.tracking.all_kalman);
    to_events.add(r.tracking.all_kalman_events);
    events_centre.add(r.tracking.all_events_centre);
    velocity.add(r.tracking.all_velocity);
    const ClearMot& m = r.tracking.mot;
    out.mot.add_counts(m);
    mot_to_centres.add(m.to_centres);
    mot_to_events.add(m.to_events);
  }
  const double n = static_cast<double>(std::max<size_t>(1, family.size()));
  out.mean_f /= n;
  out.mean_ari /= n;
  out.idf1 /= n;
  out.id_switches_per_object = objects ? static_cast<double>(switches) / static_cast<double>(objects) : 0;
  out.worst_type_f = 1;
  for (const std::string& type : order) {
    TypeSummary t = by_type[type];
    t.f /= t.scenes;
    t.ari /= t.scenes;
    out.worst_type_f = std::min(out.worst_type_f, t.f);
    out.types.push_back(t);
  }
  out.tracking = to_centres.stats();
  out.tracking_to_events = to_events.stats();
  out.events_centre = events_centre.stats();
  out.velocity = velocity.stats();
  out.mot.to_centres = mot_to_centres.stats();
  out.mot.to_events = mot_to_events.stats();
  out.kernel_evaluations_per_event = events ? static_cast<double>(evaluations) / static_cast<double>(events) : 0;
  out.events_per_s = wall > 0 ? static_cast<double>(events) / wall : 0;
  out.scenes = std::move(scenes);
  return out;
}

}  // namespace

std::vector<FamilyResult> evaluate_family(const std::vector<FamilyScene>& family, const std::vector<Method>& methods,
                                          const std::string& backend, int jobs) {
  std::vector<std::vector<SceneResult>> results(methods.size(), std::vector<SceneResult>(family.size()));
  // Largest scenes first, so that no thread is left with a long one at the end.
  std::vector<size_t> order(family.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return family[a].scene.events.size() > family[b].scene.events.size(); });
  parallel_for(methods.size() * family.size(), jobs, [&](size_t task) {
    const size_t m = task / family.size(), i = order[task % family.size()];
    results[m][i] = run_member(family[i], methods[m], backend);
  });
  std::vector<FamilyResult> out;
  for (auto& r : results) out.push_back(summarise(family, std::move(r)));
  return out;
}

FamilyResult evaluate_family(const std::vector<FamilyScene>& family, const Method& method, const std::string& backend, int jobs) {
  return evaluate_family(family, std::vector<Method>{method}, backend, jobs).front();
}

}  // namespace evms::eval

#include "host/eval/tracking_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

#include "host/eval/assignment.h"

namespace evms::eval {
namespace {

class CentreLookup {
 public:
  CentreLookup(std::span<const gen::TruthSample> centres, int objects) : per_object_(static_cast<size_t>(objects)) {
    for (const auto& c : centres) per_object_[static_cast<size_t>(c.object)][c.t / 1000] = {c.x, c.y};
  }
  // The centre at time t, interpolated between the neighbouring millisecond samples.
  std::optional<std::pair<double, double>> at(int object, TimeUs t) const {
    const auto& m = per_object_[static_cast<size_t>(object)];
    const TimeUs k = t / 1000;
    auto a = m.find(k), b = m.find(k + 1);
    if (a == m.end()) return std::nullopt;
    if (t % 1000 == 0 || b == m.end()) return t % 1000 == 0 ? std::optional(a->second) : std::nullopt;
    const double f = static_cast<double>(t % 1000) / 1000.0;
    return std::pair{a->second.first + f * (b->second.first - a->second.first),
                     a->second.second + f * (b->second.second - a->second.second)};
  }
  // Central difference over +-1 ms, px/s.
  std::optional<std::pair<double, double>> velocity(int object, TimeUs t) const {
    const auto a = at(object, t - 1000), b = at(object, t + 1000);
    if (!a || !b) return std::nullopt;
    return std::pair{(b->first - a->first) / 2e-3, (b->second - a->second) / 2e-3};
  }
  const std::unordered_map<TimeUs, std::pair<double, double>>& samples(int object) const {
    return per_object_[static_cast<size_t>(object)];
  }

 private:
  std::vector<std::unordered_map<TimeUs, std::pair<double, double>>> per_object_;
};

// The centre of mass of each object's labelled events in (t - window/2, t + window/2], from
// prefix sums.
class EventCentreLookup {
 public:
  EventCentreLookup(const LabelledEvents& labelled, int objects, TimeUs window_us)
      : per_object_(static_cast<size_t>(objects)), window_us_(window_us) {
    for (auto& o : per_object_) o.sx.push_back(0), o.sy.push_back(0);
    for (size_t i = 0; i < labelled.events.size() && i < labelled.truth.size(); ++i) {
      const std::int32_t o = labelled.truth[i];
      if (o < 0 || o >= objects) continue;
      Object& ob = per_object_[static_cast<size_t>(o)];
      const Event& e = labelled.events[i];
      any_ = true;
      ob.t.push_back(e.t);
      ob.sx.push_back(ob.sx.back() + e.x);
      ob.sy.push_back(ob.sy.back() + e.y);
    }
  }
  bool any() const { return any_; }
  std::optional<std::pair<double, double>> at(int object, TimeUs t) const {
    const Object& ob = per_object_[static_cast<size_t>(object)];
    const size_t end = static_cast<size_t>(std::upper_bound(ob.t.begin(), ob.t.end(), t + window_us_ / 2) - ob.t.begin());
    const size_t begin = static_cast<size_t>(std::upper_bound(ob.t.begin(), ob.t.end(), t - window_us_ / 2) - ob.t.begin());
    if (end < begin + static_cast<size_t>(kEventCentreMinEvents)) return std::nullopt;
    const double n = static_cast<double>(end - begin);
    return std::pair{(ob.sx[end] - ob.sx[begin]) / n, (ob.sy[end] - ob.sy[begin]) / n};
  }

 private:
  struct Object {
    std::vector<TimeUs> t;            // in input order, which is time order
    std::vector<double> sx, sy;       // prefix sums, one longer than t
  };
  std::vector<Object> per_object_;
  TimeUs window_us_;
  bool any_ = false;  // some object has a labelled event
};

struct Accumulator {
  std::vector<double> errors;
  ErrorStats stats(double tau) const {
    ErrorStats s;
    s.samples = static_cast<std::int64_t>(errors.size());
    if (errors.empty()) return s;
    double sum = 0, sum2 = 0;
    for (double e : errors) sum += e, sum2 += e * e, s.within += e <= tau;
    const double n = static_cast<double>(errors.size());
    s.mean = sum / n;
    s.std = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
    s.within /= n;
    return s;
  }
};

// CLEAR MOT over the frames of the truth's time span (tracking_metrics.h). `measured_from[i]` is
// the object updates[i] was measured from (-1: noise or none), empty without the run's labels.
ClearMot clear_mot(std::span<const TrackUpdate> updates, std::span<const int> measured_from, const CentreLookup& centres,
                   const EventCentreLookup& event_centres, int objects, double tau_px, double radius_px) {
  ClearMot mot;
  TimeUs first = -1, last = -1;
  for (int o = 0; o < objects; ++o) {
    for (const auto& [ms, xy] : centres.samples(o)) {
      first = first < 0 ? ms * 1000 : std::min(first, ms * 1000);
      last = std::max(last, ms * 1000);
    }
  }
  if (first < 0) return mot;
  std::vector<size_t> order(updates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return updates[a].t < updates[b].t; });
  std::map<std::int32_t, size_t> latest;                 // track -> its latest update so far
  std::vector<std::int32_t> previous(static_cast<size_t>(objects), -1);  // each object's last matched track
  Accumulator to_centres, to_events;
  size_t next = 0;
  constexpr double kPairFirst = 1e9;  // a pair's weight: this minus its distance, so more pairs always win
  for (TimeUs t = (first + kMotFrameUs - 1) / kMotFrameUs * kMotFrameUs; t <= last; t += kMotFrameUs) {
    while (next < order.size() && updates[order[next]].t <= t) latest[updates[order[next]].id] = order[next], ++next;
    std::vector<int> present_objects;
    for (int o = 0; o < objects; ++o) {
      if (centres.at(o, t) && (!event_centres.any() || event_centres.at(o, t))) present_objects.push_back(o);
    }
    std::vector<const TrackUpdate*> tracks;
    for (const auto& [id, i] : latest) {
      if (t - updates[i].t <= kMotTrackWindowUs) tracks.push_back(&updates[i]);
    }
    ++mot.frames;
    mot.objects += static_cast<std::int64_t>(present_objects.size());
    // distance[k][j]: object present_objects[k] to tracks[j], or infinity without a truth then.
    const double kFar = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> distance(present_objects.size(), std::vector<double>(tracks.size(), kFar));
    for (size_t k = 0; k < present_objects.size(); ++k) {
      for (size_t j = 0; j < tracks.size(); ++j) {
        if (const auto c = centres.at(present_objects[k], tracks[j]->t)) distance[k][j] = std::hypot(tracks[j]->x - c->first, tracks[j]->y - c->second);
      }
    }
    std::vector<int> match(present_objects.size(), -1);
    std::vector<bool> taken(tracks.size(), false);
    for (size_t k = 0; k < present_objects.size(); ++k) {
      for (size_t j = 0; j < tracks.size(); ++j) {
        if (tracks[j]->id == previous[static_cast<size_t>(present_objects[k])] && !taken[j] && distance[k][j] <= radius_px) {
          match[k] = static_cast<int>(j), taken[j] = true;
        }
      }
    }
    std::vector<size_t> rows, cols;
    for (size_t k = 0; k < present_objects.size(); ++k) if (match[k] < 0) rows.push_back(k);
    for (size_t j = 0; j < tracks.size(); ++j) if (!taken[j]) cols.push_back(j);
    std::vector<std::vector<double>> weight(rows.size(), std::vector<double>(cols.size()));
    for (size_t a = 0; a < rows.size(); ++a) {
      for (size_t b = 0; b < cols.size(); ++b) {
        const double d = distance[rows[a]][cols[b]];
        weight[a][b] = d <= radius_px ? kPairFirst - d : 0.0;
      }
    }
    const std::vector<int> assigned = max_weight_assignment(weight);
    for (size_t a = 0; a < rows.size(); ++a) {
      if (assigned[a] < 0) continue;
      const size_t k = rows[a], j = cols[static_cast<size_t>(assigned[a])];
      if (distance[k][j] <= radius_px) match[k] = static_cast<int>(j), taken[j] = true;
    }
    for (size_t k = 0; k < present_objects.size(); ++k) {
      const int o = present_objects[k];
      if (match[k] < 0) {
        ++mot.misses;
        continue;
      }
      const TrackUpdate& u = *tracks[static_cast<size_t>(match[k])];
      ++mot.matches;
      std::int32_t& was = previous[static_cast<size_t>(o)];
      mot.mismatches += was >= 0 && was != u.id;
      was = u.id;
      to_centres.errors.push_back(distance[k][static_cast<size_t>(match[k])]);
      if (const auto m = event_centres.at(o, u.t)) to_events.errors.push_back(std::hypot(u.x - m->first, u.y - m->second));
    }
    for (size_t j = 0; j < tracks.size(); ++j) {
      if (taken[j]) continue;
      const int o = measured_from.empty() ? -1 : measured_from[static_cast<size_t>(tracks[j] - updates.data())];
      const bool unscored = o >= 0 && std::find(present_objects.begin(), present_objects.end(), o) == present_objects.end();
      ++(unscored ? mot.ignored : mot.false_positives);
    }
  }
  mot.to_centres = to_centres.stats(tau_px);
  mot.to_events = to_events.stats(tau_px);
  return mot;
}

}  // namespace

TrackingReport tracking_report(std::span<const TrackUpdate> updates, std::span<const gen::TruthSample> centres, int objects,
                               double tau_px, double association_radius_px, TimeUs coverage_window_us, LabelledEvents labelled,
                               TimeUs event_window_us) {
  const CentreLookup lookup(centres, objects);
  const EventCentreLookup event_lookup(labelled, objects, event_window_us);
  std::map<std::int32_t, std::vector<int>> votes;  // track -> votes per object
  std::map<std::int32_t, std::int64_t> noise_votes;  // track -> its events that were noise (with the run's labels)
  std::unordered_map<std::int32_t, std::vector<size_t>> labelled_by;  // track -> its events, in time order
  const bool by_labels = !labelled.predicted.empty() && labelled.predicted.size() == labelled.truth.size() &&
                         labelled.events.size() == labelled.truth.size();
  if (by_labels) {
    for (const TrackUpdate& u : updates) votes[u.id].resize(static_cast<size_t>(objects), 0);
    for (size_t i = 0; i < labelled.truth.size(); ++i) {
      const auto v = votes.find(labelled.predicted[i]);
      if (v == votes.end()) continue;
      labelled_by[v->first].push_back(i);
      const std::int32_t o = labelled.truth[i];
      if (o >= 0 && o < objects) ++v->second[static_cast<size_t>(o)];
      else ++noise_votes[v->first];
    }
  } else {
    for (const TrackUpdate& u : updates) {
      int best = -1;
      double best_d = association_radius_px;
      for (int o = 0; o < objects; ++o) {
        const auto c = lookup.at(o, u.t);
        if (!c) continue;
        const double d = std::hypot(u.x - c->first, u.y - c->second);
        if (d <= best_d) best = o, best_d = d;
      }
      auto& v = votes[u.id];
      v.resize(static_cast<size_t>(objects), 0);
      if (best >= 0) ++v[static_cast<size_t>(best)];
    }
  }
  std::map<std::int32_t, int> owner;
  for (const auto& [id, v] : votes) {
    const auto it = std::max_element(v.begin(), v.end());
    owner[id] = (it == v.end() || *it == 0 || *it < noise_votes[id]) ? -1 : static_cast<int>(it - v.begin());
  }

  // With the run's labels, each update belongs to the object whose events its track labelled
  // in the window around it (an estimate is measured from those events), or, when the track
  // labelled none there, to the track's owner.
  std::vector<std::int64_t> count(static_cast<size_t>(objects));  // update_owner's tally, reused
  const auto update_owner = [&](const TrackUpdate& u) {
    const int whole = owner[u.id];
    if (!by_labels) return whole;
    const auto labelled_events = labelled_by.find(u.id);
    if (labelled_events == labelled_by.end()) return whole;
    const std::vector<size_t>& mine = labelled_events->second;
    const auto time_of = [&](size_t i) { return labelled.events[i].t; };
    auto it = std::upper_bound(mine.begin(), mine.end(), u.t - event_window_us / 2, [&](TimeUs t, size_t i) { return t < time_of(i); });
    std::fill(count.begin(), count.end(), 0);
    std::int64_t noise = 0, any = 0;
    for (; it != mine.end() && time_of(*it) <= u.t + event_window_us / 2; ++it, ++any) {
      const std::int32_t o = labelled.truth[*it];
      if (o >= 0 && o < objects) ++count[static_cast<size_t>(o)];
      else ++noise;
    }
    if (any == 0) return whole;
    const auto best = std::max_element(count.begin(), count.end());
    return best == count.end() || *best == 0 || *best < noise ? -1 : static_cast<int>(best - count.begin());
  };

  TrackingReport report;
  std::vector<Accumulator> kalman(static_cast<size_t>(objects)), raw(static_cast<size_t>(objects)),
      kalman_events(static_cast<size_t>(objects));
  Accumulator all_kalman, all_raw, all_velocity, all_kalman_events, all_events_centre;
  std::vector<Accumulator> velocity(static_cast<size_t>(objects));
  std::vector<std::vector<TimeUs>> update_times(static_cast<size_t>(objects));
  std::vector<int> measured_from;  // each update's object, for CLEAR MOT (with the run's labels only)
  if (by_labels) measured_from.reserve(updates.size());
  for (const TrackUpdate& u : updates) {
    const int o = update_owner(u);
    if (by_labels) measured_from.push_back(o);
    if (o < 0) {
      ++report.spurious_updates;
      continue;
    }
    update_times[static_cast<size_t>(o)].push_back(u.t);
    const auto m = event_lookup.at(o, u.t);
    if (m) {
      const double e = std::hypot(u.x - m->first, u.y - m->second);
      kalman_events[static_cast<size_t>(o)].errors.push_back(e);
      all_kalman_events.errors.push_back(e);
    }
    const auto c = lookup.at(o, u.t);
    if (!c) continue;
    if (m) all_events_centre.errors.push_back(std::hypot(m->first - c->first, m->second - c->second));
    const double ek = std::hypot(u.x - c->first, u.y - c->second), er = std::hypot(u.zx - c->first, u.zy - c->second);
    kalman[static_cast<size_t>(o)].errors.push_back(ek);
    raw[static_cast<size_t>(o)].errors.push_back(er);
    all_kalman.errors.push_back(ek);
    all_raw.errors.push_back(er);
    if (const auto v = lookup.velocity(o, u.t)) {
      const double ev = std::hypot(u.vx - v->first, u.vy - v->second);
      velocity[static_cast<size_t>(o)].errors.push_back(ev);
      all_velocity.errors.push_back(ev);
    }
  }
  for (int o = 0; o < objects; ++o) {
    ObjectTracking t;
    t.object = o;
    for (const auto& [id, obj] : owner) {
      if (obj == o) t.tracks.push_back(id);
    }
    t.kalman = kalman[static_cast<size_t>(o)].stats(tau_px);
    t.raw = raw[static_cast<size_t>(o)].stats(tau_px);
    t.kalman_events = kalman_events[static_cast<size_t>(o)].stats(tau_px);
    t.velocity_error = velocity[static_cast<size_t>(o)].stats(0).mean;
    auto& times = update_times[static_cast<size_t>(o)];
    std::sort(times.begin(), times.end());
    std::int64_t covered = 0, total = 0;
    for (const auto& [ms, xy] : lookup.samples(o)) {
      ++total;
      const TimeUs t = ms * 1000;
      auto it = std::upper_bound(times.begin(), times.end(), t);
      covered += it != times.begin() && t - *(it - 1) <= coverage_window_us;
    }
    t.coverage = total ? static_cast<double>(covered) / static_cast<double>(total) : 0.0;
    report.objects.push_back(t);
  }
  report.all_kalman = all_kalman.stats(tau_px);
  report.all_raw = all_raw.stats(tau_px);
  report.all_kalman_events = all_kalman_events.stats(tau_px);
  report.all_events_centre = all_events_centre.stats(tau_px);
  report.all_velocity = all_velocity.stats(0);
  report.mot = clear_mot(updates, measured_from, lookup, event_lookup, objects, tau_px, association_radius_px);
  return report;
}

}  // namespace evms::eval

#include "golden/track/outline_split.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace evms::golden {

OutlineSplit::OutlineSplit(const Params& params, SensorSize sensor)
    : history_us_(static_cast<TimeUs>(params.outline_split_us)),
      width_(sensor.width),
      height_(sensor.height),
      memory_(history_us_ > 0 ? 2 * static_cast<size_t>(sensor.width) * static_cast<size_t>(sensor.height) : 0),
      slopes_(sensor),
      max_clusters_(params.max_clusters) {}

void OutlineSplit::remember(std::span<const Event> events, std::span<const std::int32_t> labels) {
  for (size_t i = 0; i < events.size(); ++i) {
    if (labels[i] < 0) continue;
    const Event& e = events[i];
    at(e.p, e.x, e.y) = {e.t, labels[i]};
  }
}

bool OutlineSplit::parts_of(std::span<const Event> events, std::span<const int> members, const Box& box,
                            std::span<const TrackPrediction* const> near, std::vector<int>& part) {
  // An event e and a remembered pixel m of track q are |e - (m + v_q (e.t - m.t))| apart: the
  // distance between the two moved on with v_q to any common time. So each near track's
  // remembered pixels are moved on once, to the cluster's first event's time, onto a map of the
  // cluster's box grown by kMostSearchPx (to the nearest pixel); each event, moved back to that
  // time with each track's velocity, looks for the nearest marked pixel of the map within kReachPx.
  TimeUs first = events[static_cast<size_t>(members[0])].t;
  for (int i : members) first = std::min(first, events[static_cast<size_t>(i)].t);
  const int gx0 = std::max(0, box.x0 - kMostSearchPx), gy0 = std::max(0, box.y0 - kMostSearchPx);
  const int gx1 = std::min(width_ - 1, box.x1 + kMostSearchPx), gy1 = std::min(height_ - 1, box.y1 + kMostSearchPx);
  const int map_w = gx1 - gx0 + 1, map_h = gy1 - gy0 + 1;
  const size_t map_size = static_cast<size_t>(map_w) * static_cast<size_t>(map_h);
  // Per near track and polarity, a map of where its remembered pixels lie, moved on to `first`.
  moved_on_.assign(near.size() * 2 * map_size, 0);
  const auto map_of = [&](size_t q, int polarity) { return moved_on_.data() + (q * 2 + static_cast<size_t>(polarity != 0)) * map_size; };
  for (int polarity = 0; polarity < 2; ++polarity) {
    for (int y = gy0; y <= gy1; ++y) {
      for (int x = gx0; x <= gx1; ++x) {
        const Remembered& r = at(polarity, x, y);
        if (r.track < 0 || first - r.t > history_us_) continue;
        for (size_t q = 0; q < near.size(); ++q) {
          if (near[q]->id != r.track) continue;
          const double age_s = static_cast<double>(first - r.t) * 1e-6;
          const auto mx = static_cast<int>(std::lround(x + near[q]->velocity.x() * age_s)) - gx0;
          const auto my = static_cast<int>(std::lround(y + near[q]->velocity.y() * age_s)) - gy0;
          if (mx >= 0 && my >= 0 && mx < map_w && my < map_h) map_of(q, polarity)[static_cast<size_t>(my) * map_w + mx] = 1;
        }
      }
    }
  }
  const int reach = static_cast<int>(std::floor(kReachPx));
  std::vector<int> taken(near.size(), 0);
  part.assign(members.size(), -1);
  for (size_t k = 0; k < members.size(); ++k) {
    const Event& e = events[static_cast<size_t>(members[k])];
    double nearest = kReachPx * kReachPx;
    const double back_s = static_cast<double>(e.t - first) * 1e-6;
    for (size_t q = 0; q < near.size(); ++q) {
      const std::uint8_t* map = map_of(q, e.p);
      const double ex = e.x - near[q]->velocity.x() * back_s - gx0, ey = e.y - near[q]->velocity.y() * back_s - gy0;
      const auto cx = static_cast<int>(std::lround(ex)), cy = static_cast<int>(std::lround(ey));
      for (int my = std::max(0, cy - reach); my <= std::min(map_h - 1, cy + reach); ++my) {
        for (int mx = std::max(0, cx - reach); mx <= std::min(map_w - 1, cx + reach); ++mx) {
          if (!map[static_cast<size_t>(my) * map_w + mx]) continue;
          const double d2 = (mx - ex) * (mx - ex) + (my - ey) * (my - ey);
          if (d2 < nearest) nearest = d2, part[k] = static_cast<int>(q);
        }
      }
    }
    if (part[k] >= 0) ++taken[static_cast<size_t>(part[k])];
  }
  const auto most = static_cast<int>(std::max_element(taken.begin(), taken.end()) - taken.begin());
  for (int& q : part) {
    if (q < 0) q = most, ++taken[static_cast<size_t>(most)];
  }
  // A track that took too few events gives them to the one that took the most.
  for (int& q : part) {
    if (taken[static_cast<size_t>(q)] < kLeastPartEvents) q = most;
  }
  int parts = 0;
  for (int count : taken) parts += count >= kLeastPartEvents;
  if (parts < kMeetingTracks) return false;
  // Number the parts 0.. in the order of the tracks.
  std::vector<int> number(near.size(), -1);
  int next = 0;
  for (size_t q = 0; q < near.size(); ++q) {
    if (taken[q] >= kLeastPartEvents) number[q] = next++;
  }
  for (int& q : part) q = number[static_cast<size_t>(q)];
  return parts_move_apart(events, members, part, parts);
}

bool OutlineSplit::parts_move_apart(std::span<const Event> events, std::span<const int> members, std::span<const int> part, int parts) {
  if (!slopes_added_) slopes_.add(events), slopes_added_ = true;
  slope_.resize(members.size());
  std::vector<int> sloped;
  std::vector<std::vector<int>> sloped_of(static_cast<size_t>(parts));
  for (size_t k = 0; k < members.size(); ++k) {
    const std::optional<Eigen::Vector2d> slope = slopes_.at(events[static_cast<size_t>(members[k])]);
    if (!slope) continue;
    slope_[k] = *slope;
    sloped.push_back(static_cast<int>(k));
    sloped_of[static_cast<size_t>(part[k])].push_back(static_cast<int>(k));
  }
  if (sloped.empty()) return false;
  const Eigen::Vector2d one = fit_velocity(slope_, sloped);
  std::vector<Eigen::Vector2d> velocity(static_cast<size_t>(parts));
  for (size_t q = 0; q < velocity.size(); ++q) velocity[q] = fit_velocity(slope_, sloped_of[q]);
  double one_residual = 0, parts_residual = 0;
  for (int k : sloped) {
    one_residual += capped_misfit(slope_[static_cast<size_t>(k)], one);
    parts_residual += capped_misfit(slope_[static_cast<size_t>(k)], velocity[static_cast<size_t>(part[static_cast<size_t>(k)])]);
  }
  if (parts_residual > kMotionShare * one_residual) return false;
  for (size_t a = 0; a < velocity.size(); ++a) {
    for (size_t b = a + 1; b < velocity.size(); ++b) {
      if ((velocity[a] - velocity[b]).norm() >= kLeastVelocityDifference * std::max(velocity[a].norm(), velocity[b].norm())) return true;
    }
  }
  return false;
}

void OutlineSplit::split(std::span<const Event> events, const FeatureMatrix& features, std::span<const TrackPrediction> tracks,
                         PacketClusters& clusters) {
  if (history_us_ <= 0 || tracks.size() < static_cast<size_t>(kMeetingTracks)) return;
  std::vector<std::vector<int>> members(static_cast<size_t>(clusters.count));
  for (size_t i = 0; i < events.size(); ++i) {
    if (clusters.cluster_of[i] >= 0) members[static_cast<size_t>(clusters.cluster_of[i])].push_back(static_cast<int>(i));
  }
  std::vector<const TrackPrediction*> near;
  std::vector<int> part;
  for (size_t c = 0; c < members.size(); ++c) {
    if (members[c].size() < static_cast<size_t>(kLeastClusterEvents)) continue;
    Box box{width_, height_, -1, -1};
    for (int i : members[c]) {
      const Event& e = events[static_cast<size_t>(i)];
      box.x0 = std::min<int>(box.x0, e.x), box.x1 = std::max<int>(box.x1, e.x), box.y0 = std::min<int>(box.y0, e.y), box.y1 = std::max<int>(box.y1, e.y);
    }
    near.clear();
    for (const TrackPrediction& track : tracks) {
      const Eigen::Vector2d& q = track.position;
      if (track.matched && q.x() >= box.x0 - kBoxMarginPx && q.x() <= box.x1 + kBoxMarginPx && q.y() >= box.y0 - kBoxMarginPx &&
          q.y() <= box.y1 + kBoxMarginPx) {
        near.push_back(&track);
      }
    }
    if (near.size() < static_cast<size_t>(kMeetingTracks) || !parts_of(events, members[c], box, near, part)) continue;
    const int parts = *std::max_element(part.begin(), part.end()) + 1;
    if (clusters.count + parts - 1 > max_clusters_) continue;
    // Part 0 keeps the cluster's index; the others are appended.
    std::vector<int> cluster_of_part(static_cast<size_t>(parts));
    cluster_of_part[0] = static_cast<int>(c);
    for (int q = 1; q < parts; ++q) cluster_of_part[static_cast<size_t>(q)] = clusters.count++;
    clusters.modes.resize(static_cast<size_t>(clusters.count));
    clusters.spreads.resize(static_cast<size_t>(clusters.count));
    std::vector<Eigen::Vector4d> sum(static_cast<size_t>(parts), Eigen::Vector4d::Zero());
    std::vector<double> squares(static_cast<size_t>(parts), 0.0);
    std::vector<int> count(static_cast<size_t>(parts), 0);
    for (size_t k = 0; k < members[c].size(); ++k) {
      const int i = members[c][k];
      const auto q = static_cast<size_t>(part[k]);
      clusters.cluster_of[static_cast<size_t>(i)] = cluster_of_part[q];
      sum[q] += features.col(i), squares[q] += features.col(i).squaredNorm(), ++count[q];
    }
    for (size_t q = 0; q < sum.size(); ++q) {
      const Eigen::Vector4d mean = sum[q] / count[q];
      clusters.modes[static_cast<size_t>(cluster_of_part[q])] = mean;
      clusters.spreads[static_cast<size_t>(cluster_of_part[q])] = std::sqrt(std::max(0.0, squares[q] / count[q] - mean.squaredNorm()));
    }
  }
  if (slopes_added_) slopes_.clear(), slopes_added_ = false;
}

}  // namespace evms::golden

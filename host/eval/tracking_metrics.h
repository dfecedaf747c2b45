// Tracking accuracy against two ground truths:
//  - the object's true centre (the centre of its outline, from the generator), and
//  - the centre of mass of the events the generator labelled as the object's in the window of
//    `event_window_us` centred on the estimate's time (the paper's ground truth: "the
//    ground-truth labeled cluster center"). Centred, because an estimate is timed at the mean
//    timestamp of the events its cluster was measured from: a window that ended there would trail a moving object
//    by half of what it moves in the window.
// They differ where some edges of a shape fire more events than others (the paper, section V,
// explains its rectangle and hexagon by this); the first includes that offset, the second
// measures what clustering and the Kalman filter add to it.
//
// Association of estimates to objects:
//  - With the run's labels (`LabelledEvents::predicted`), each update is an estimate of the
//    object whose events its track labelled most in the `event_window_us` around it (ties: the
//    lower object index), or of none (spurious) when more of those events were noise than any
//    one object's. Where the track labelled no event in that window, the update goes with the
//    track's owner: the object whose events it labelled most over its life. An estimate is
//    scored against what it was measured from: a cluster that merged two objects is an error
//    of the object most of its events came from, a track that followed one object and then
//    another (an identity switch, which IDF1 counts) is scored on each in turn, and an object
//    whose outline reaches past the sensor's edge has no true centre to score its track
//    against, however near a small neighbour's centre it stands.
//  - Without them, at every update of a track the object whose true centre (interpolated
//    between the millisecond samples) is nearest votes for it, if it is within
//    `association_radius_px`. A track belongs to the object with most votes (ties: the lower
//    object index) and each of its updates is an estimate of that object; tracks without a vote
//    belong to none and are counted as spurious.
// An object may own several tracks in turn (after it left the view, say).
//
// For each object, every estimate of it at a time when its true centre is known counts, its
// error the distance to that centre. Reported side by side for the
// Kalman-filtered estimate and the raw cluster centroid of the same update, and (when the
// events are given) against the labelled events' centre, beside the labelled events' centre's
// own distance from the true centre at the same estimates. Coverage is the
// share of the object's true-centre samples that have one of its track updates within
// `coverage_window_us` before them.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "types/event.h"
#include "host/gen/scene_generator.h"

namespace evms::eval {

struct ErrorStats {
  std::int64_t samples = 0;
  double mean = 0, std = 0, within = 0;  // px, px, share within tau
};

struct ObjectTracking {
  int object = 0;
  std::vector<std::int32_t> tracks;  // IDs associated with the object
  ErrorStats kalman, raw;            // against the true centre
  ErrorStats kalman_events;          // against the centre of the object's labelled events
  double velocity_error = 0;         // mean |v_kalman - v_true|, px/s (true: central difference)
  double coverage = 0;
};

// CLEAR MOT (Bernardin and Stiefelhagen 2008), in frames of `kMotFrameUs`: the standard
// multi-object tracking scores, where each object is matched to at most one track at a time, so
// that a second track on one object (a fragment) is a false positive, not a second estimate.
//  - An object is present at a frame's time when its true centre is known there and, when the
//    labelled events are given, it has a labelled centre there (it fired: a still object
//    that fires nothing cannot be tracked by its events).
//  - A track is present when it was updated within `kMotTrackWindowUs` before, and stands at
//    its latest estimate, which is compared with the truth at that estimate's own time.
//  - An object keeps its previous frame's track while that track is present and within the
//    association radius. The others are matched one to one (Hungarian): the most pairs first,
//    then the least total distance; a pair beyond the radius never.
//  - Unmatched objects are misses and unmatched tracks false positives. An object matched to
//    another track than at its previous match is a mismatch.
//  - With the run's labels, an unmatched track whose latest estimate was measured from an object
//    that is not present in the frame (its outline reaches past the sensor's edge, so it has no
//    true centre, or it fired too little there to have a labelled centre) is ignored, neither
//    matched nor a false positive: the truth cannot score it, as MOTChallenge ignores a track on
//    a distractor. A track on noise, or a second track on a present object, stays a false positive.
// MOTA = 1 - (misses + false positives + mismatches) / objects present, summed over frames;
// MOTP is the mean distance of the matched pairs.
inline constexpr TimeUs kMotFrameUs = 10000;       // the scoring chunk (family_eval.h)
inline constexpr TimeUs kMotTrackWindowUs = 34000;  // a packet spans at most 33.3 ms by default

struct ClearMot {
  std::int64_t frames = 0, objects = 0, matches = 0, misses = 0, false_positives = 0, mismatches = 0;
  std::int64_t ignored = 0;  // unmatched tracks on an object the frame cannot score (not in MOTA)
  ErrorStats to_centres;  // matched pairs: the estimate against the object's true centre (MOTP)
  ErrorStats to_events;   // ... against the centre of its labelled events, where it has one
  double mota() const {
    return objects ? 1.0 - static_cast<double>(misses + false_positives + mismatches) / static_cast<double>(objects) : 0.0;
  }
  double false_positives_per_frame() const { return frames ? static_cast<double>(false_positives) / static_cast<double>(frames) : 0.0; }
  double ignored_per_frame() const { return frames ? static_cast<double>(ignored) / static_cast<double>(frames) : 0.0; }
  // Adds another run's counts (its error statistics pool elsewhere: host/eval/family_eval.cpp).
  void add_counts(const ClearMot& m) {
    frames += m.frames, objects += m.objects, matches += m.matches;
    misses += m.misses, false_positives += m.false_positives, mismatches += m.mismatches, ignored += m.ignored;
  }
};

struct TrackingReport {
  std::vector<ObjectTracking> objects;
  ClearMot mot;
  std::int64_t spurious_updates = 0;   // updates of tracks associated with no object
  ErrorStats all_kalman, all_raw;      // pooled over every object, against the true centres
  ErrorStats all_kalman_events;        // pooled, against the labelled events' centres (paper)
  // Pooled over the estimates where both truths are known: the labelled events' centre against
  // the true centre, which is what a track sitting on its object's events' centre of mass would
  // score against the outline's centre (the part of all_kalman that no centroid tracker removes).
  ErrorStats all_events_centre;
  ErrorStats all_velocity;             // pooled |v_kalman - v_true|, px/s (true: central difference)
};

// The events with their true labels (object index or -1), for the paper's ground truth; empty
// spans leave the *_events statistics empty. `predicted`, the run's labels of the same events
// (track ID or -1), makes each estimate's object the one its track's events came from; empty,
// the nearest true centre decides.
struct LabelledEvents {
  std::span<const Event> events;
  std::span<const std::int32_t> truth;
  std::span<const std::int32_t> predicted = {};
};

inline constexpr TimeUs kEventCentreWindowUs = 10000;  // the scoring chunk (family_eval.h)
inline constexpr int kEventCentreMinEvents = 8;        // fewer: the object has no labelled centre then

TrackingReport tracking_report(std::span<const TrackUpdate> updates, std::span<const gen::TruthSample> centres,
                               int objects, double tau_px = 2.5, double association_radius_px = 15.0,
                               TimeUs coverage_window_us = 20000, LabelledEvents labelled = {},
                               TimeUs event_window_us = kEventCentreWindowUs);

}  // namespace evms::eval

// Identity over a whole recording, from the labels: does each object keep one ID, and does
// each ID stay on one object?
//
// IDF1 (Ristani et al. 2016), counted in events: the true objects and the predicted IDs are
// matched one to one so that the most events agree (Hungarian assignment on their contingency
// table). IDTP are the events whose predicted ID is matched to their true object; IDFP the
// other events with an ID; IDFN the other events of an object. IDF1 = 2 IDTP / (2 IDTP +
// IDFP + IDFN). Noise (-1) in both labellings counts nowhere.
//
// ID switches and fragmentations, in frames of `frame_us`: in each frame where an object has
// events, the ID most of them carry (noise counts as "no ID") is the object's ID in that
// frame, or none. A switch is a change from one ID to another between the object's frames
// (with or without frames of none between them); a fragmentation is a return to an ID after
// one or more frames of none.
#pragma once

#include <cstdint>
#include <span>

#include "types/event.h"

namespace evms::eval {

struct IdentityScores {
  double idf1 = 0;
  double id_precision = 0, id_recall = 0;  // IDTP / (IDTP + IDFP), IDTP / (IDTP + IDFN)
  std::int64_t id_switches = 0;
  std::int64_t fragmentations = 0;
  std::int64_t objects = 0;                // true objects with events
};

IdentityScores identity_scores(std::span<const Event> events, std::span<const std::int32_t> truth,
                               std::span<const std::int32_t> predicted, TimeUs frame_us = 10000);

}  // namespace evms::eval

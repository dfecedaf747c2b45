// What clustering by position cannot separate: the true labelling of a window with every two
// objects whose events touch merged into one label.
//
// Two objects touch in a window when an event of one lies within `reach_px` (Euclidean, on the
// pixel grid) of an event of the other; touching is transitive (union-find over the objects).
// Scoring these labels against the truth (`evms metrics --touching-px`) gives the F of a
// clustering that is perfect except that it always holds touching objects together, which is
// what a method that groups events by position and connectivity (mean shift, links, a grid)
// does while two objects overlap. Every touching group takes its smallest object label; noise
// (-1) stays noise and touches nothing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "host/eval/chunks.h"
#include "types/event.h"

namespace evms::eval {

// The reach `evms eval` reports: events at most one empty pixel apart touch.
inline constexpr double kTouchingReachPx = 2.0;

std::vector<std::int32_t> merge_touching_objects(std::span<const Event> events, std::span<const std::int32_t> truth,
                                                 double reach_px);

// The same, chunk by chunk over a whole sequence, on the chunks its clustering is scored on.
std::vector<std::int32_t> merge_touching_objects(std::span<const Event> events, std::span<const std::int32_t> truth,
                                                 Chunking chunking, double reach_px);

}  // namespace evms::eval

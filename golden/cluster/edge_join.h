// The leading and trailing edges of one outline, joined into one cluster.
//
// An object moving over its background fires its leading edge in one polarity and its trailing
// edge in the other, and its edges parallel to the motion fire little. An outline wider than the
// warm ball therefore falls apart into two clusters of one polarity each, some distance apart
// along the motion, and each becomes a track off the object's centre. A cluster is mostly ON
// (mostly OFF) when it holds at least edge_min_events (and min_cluster_size) events and
// ON - OFF (OFF - ON) is at least edge_balance times its events. A mostly-ON cluster and a
// mostly-OFF cluster become one when their centres lie within edge_join bandwidths of the
// sensor's larger side (edge_join h max(W, H) px; a distance in pixels), neither holds more than kEdgeSizeRatio times the other's events,
// and each is the other's nearest such cluster (ties: the lower index). The later cluster's
// events join the earlier one. Centres are in 1/16 px, rounded half up, and every test is on
// integers (EdgeRule, types/params.h), so the fixed-point core (hls/cluster/edge_join.h) joins the
// same clusters.
//
// A small object's two edges lie in one ball, so its cluster holds both polarities and is never
// looked at; two objects side by side under one motion fire their facing edges in opposite
// polarities only when their contrasts differ in sign. docs/sweep.md ("Joining the two edges of
// an outline") has the measurements.
#pragma once

#include <span>
#include <vector>

#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

// `cluster_of`: per event, a cluster in 0 .. clusters - 1, or -1; joined clusters' events take
// the earlier cluster, and the later one is left empty.
void join_edges(std::span<const Event> events, const EdgeRule& rule, int clusters, std::vector<int>& cluster_of);

}  // namespace evms::golden

// What of a source a run takes (every source, every subcommand that reads one):
//   --start-us T      events from the first event's time + T on
//   --duration-us D   ... up to that time + D (0: to the end)
//   --limit N         at most N events (0: all)
//   --roi X,Y,W,H     only events inside the rectangle, moved to its corner: the sensor becomes WxH
//   --hot-pixels F    events of the pixels listed in F ("x,y" a line, '#' comments) are masked;
//                     "auto" lists the pixels that fire more than hot_factor times both the
//                     median active pixel's count and their 8 neighbours' mean, from a first
//                     pass over a recorded source
// Masked and cropped events are counted as skipped (evms info and run list them), never dropped
// silently; events before --start-us and after the end of the window are not part of the input.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/read/event_source.h"

namespace evms::read {

// "X,Y,W,H"; throws std::invalid_argument naming what is wrong.
Roi parse_roi(const std::string& text);

// `reopen` gives a fresh copy of the source, for the first pass of --hot-pixels auto (null for
// live sources, which cannot be read twice).
std::unique_ptr<EventSource> window_source(std::unique_ptr<EventSource> source, const SourceWindow& window,
                                           const std::function<std::unique_ptr<EventSource>()>& reopen);

// The pixels --hot-pixels auto masks in `source`, read to its end: those whose event count
// exceeds `factor` times the larger of the median count of the pixels that fired and the mean
// count of their 8 neighbours (a busy edge fires its neighbours too), most active first.
std::vector<std::pair<int, int>> find_hot_pixels(EventSource& source, double factor);

}  // namespace evms::read

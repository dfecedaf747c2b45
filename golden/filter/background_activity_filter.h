// Background-activity filter: a real edge excites neighbouring pixels within a short time,
// while background-activity noise fires pixels in isolation.
//
// Rule: an event at (x, y, t) is kept when at least `support` of its 8 neighbours (one, by
// default) fired an event (of either polarity) at a time t' with t - t' <= window. The event's own pixel does not
// count, so a pixel firing repeatedly on its own is still noise. Neighbours outside the
// sensor do not exist: a border pixel has 5 neighbours and a corner pixel 3. A pixel that has
// never fired gives no support, so the very first event of a scene is always noise. Every
// event, kept or not, records its time at its own pixel and so can support later
// neighbours. A window of 0 turns the filter off: every event is kept.
//
// With noise_count > 0 the filter watches its own noise: it counts, in intervals of
// 2^kFilterNoiseIntervalLog2 us of event time (types/params.h), the events that no neighbour
// supported at all. An interval that held noise_count or more makes the next one noisy, and in a
// noisy interval an event needs support + 1 neighbours. A long window keeps the sparse edges of
// slow objects, but at a noisy sensor's rate it lets background activity support itself; the
// count tells the two apart. An interval that follows an empty one is never noisy.
//
// With quiet_count > 0 the same count, always taken against `window`, also marks quiet
// intervals: an interval that held fewer than quiet_count makes the next one quiet, and in a
// quiet interval an event's supporters are its neighbours that fired within quiet_window_us. The
// edges of slow objects fire their neighbours far apart, and on a quiet sensor a long window lets
// little background activity through (docs/sweep.md, "The filter's quiet window").
//
// With warm_up_us > 0, every event of the stream's first warm_up_us is kept too: its neighbours'
// history is shorter than the window, so an edge pixel whose neighbours have not fired yet
// cannot be told from noise. A short, dense recording keeps its first edges, and the scene
// family scores the same with it as without (docs/sweep.md, "The filter's first window").
// hls/filter/ba_filter.h keeps the same events.
//
// The filter only looks back. golden/pipeline.h can look ahead as well (--filter-look-ahead-us),
// with neighbours_fired_after() once the events after a dropped one have been recorded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

class BackgroundActivityFilter {
 public:
  BackgroundActivityFilter(SensorSize sensor, TimeUs window_us, int support = 1, TimeUs warm_up_us = 0,
                           std::int64_t noise_count = 0, std::int64_t quiet_count = 0, TimeUs quiet_window_us = 0);

  // Records the event and says whether it is supported by a neighbour. Events must come in
  // non-decreasing time order.
  bool accept(const Event& e);

  // How many of (x, y)'s 8 neighbours fired at or after `since` (their latest event).
  int neighbours_fired_since(int x, int y, TimeUs since) const;
  // How many of (x, y)'s 8 neighbours' latest events lie in (after, until].
  int neighbours_fired_after(int x, int y, TimeUs after, TimeUs until) const;
  // The supporting neighbours the last event accept() judged was asked for.
  int support_asked() const { return support_ + (noisy_ ? 1 : 0); }
  // The latest event time recorded at (x, y); far in the past for a pixel that never fired and
  // for the pixels just outside the sensor (x or y of -1, or the width or height).
  TimeUs latest(int x, int y) const { return last_fired(x, y); }

 private:
  // Longer ago than any window: a time difference to it cannot overflow, as times are at most
  // 2^62 us (host/read/event_source.h).
  static constexpr TimeUs kNever = -(TimeUs{1} << 61);
  TimeUs& last_fired(int x, int y) { return last_fired_[static_cast<std::size_t>(y + 1) * stride_ + static_cast<std::size_t>(x + 1)]; }
  TimeUs last_fired(int x, int y) const { return last_fired_[static_cast<std::size_t>(y + 1) * stride_ + static_cast<std::size_t>(x + 1)]; }

  SensorSize sensor_;
  TimeUs window_us_;
  int support_;
  TimeUs warm_up_us_;
  std::int64_t noise_count_;
  bool started_ = false;
  TimeUs interval_ = 0;                 // the current noise interval (time >> kFilterNoiseIntervalLog2)
  std::int64_t unsupported_ = 0;        // events of it that no neighbour supported
  bool noisy_ = false;                  // the previous interval held noise_count_ or more
  std::int64_t quiet_count_;
  TimeUs quiet_window_us_;
  bool quiet_ = false;                  // the previous interval held fewer than quiet_count_
  TimeUs warm_until_ = 0;               // events before this time are kept; set by the first event
  std::size_t stride_;                  // a row of the map: the sensor's width and a border pixel each side
  std::vector<TimeUs> last_fired_;  // per pixel, row-major, with a border of pixels that never fire
};

}  // namespace evms::golden

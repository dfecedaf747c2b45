// Draws what a user sees: recent events coloured by track ID (shaded by polarity); for each
// confirmed track its trail over the last second, the box of the cluster that last measured it,
// its ID and a velocity arrow; for each tentative track a faint dot; and an overlay of figures
// that ends with the count of tracks shown.
// A track that stops being updated fades out over track_fade_us (the tracker's coasting time:
// after it, the tracker has ended the track), and so does its trail.
// The live viewer, its headless PNG frames and the evaluation pictures share it.
#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "types/event.h"
#include "host/show/canvas.h"

namespace evms::show {

struct ViewStyle {
  TimeUs event_window_us = 20000;    // events shown: the last 20 ms
  TimeUs trail_us = 1000000;         // trails: the last second
  int scale = 2;                     // screen pixels per sensor pixel
  double arrow_s = 0.1;              // a velocity arrow shows where the track will be in 0.1 s,
  double arrow_max_px = 40;          // ... at most this many sensor pixels long, inside the frame
  TimeUs track_fade_us = 100000;     // a track without updates fades out over this long
};

class FrameRenderer {
 public:
  FrameRenderer(SensorSize sensor, ViewStyle style);

  void add(const LabelledEvent& e);
  void add(const TrackUpdate& u);
  struct TracksShown {
    int confirmed = 0, tentative = 0;
  };
  // Draws the scene as of time `now` (events and trails older than their windows fade out),
  // with `overlay` lines of text in the top-left corner; returns the tracks it drew.
  TracksShown render(TimeUs now, Canvas& canvas, const std::vector<std::string>& overlay = {});
  Canvas make_canvas() const;
  TimeUs latest() const { return latest_; }
  const ViewStyle& style() const { return style_; }

 private:
  void prune(TimeUs now);

  SensorSize sensor_;
  ViewStyle style_;
  std::deque<LabelledEvent> events_;
  std::map<std::int32_t, std::deque<TrackUpdate>> trails_;
  TimeUs latest_ = 0;
};

}  // namespace evms::show

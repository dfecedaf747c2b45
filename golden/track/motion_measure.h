// A fast object's cluster measured from the pixels its own motion explains.
//
// A cluster whose bounding box, grown by 2 px, holds the prediction of a confirmed track matched
// in the packet before and moving at least motion_measure px/s (of those, the one nearest the
// cluster's position), and the prediction of another confirmed track (coasting or not, at any
// speed), is measured from the pixels of its events whose time-surface slopes
// (golden/cluster/time_surface_slopes.h) that fast track's velocity v explains,
// |slope · v - 1| <= 0.5, when those are at least half of its pixels: the mean of those pixels,
// each once, replaces the cluster's pixel centre.
//
// Why: a fast object that passes over slow ones takes their events into its cluster while they
// touch, and with each pixel counted once a slow shape's outline pulls the centre as hard as the
// fast object's own, however many more events the fast one fires. The slow shape's edges fire
// with slopes the fast velocity does not explain. Only fast tracks: a slow track's velocity is
// small beside the spread of the velocities along a turning or growing outline, whose own edges
// it would then leave out. Only beside another track: the shapes a fast one passes have tracks of
// their own, and a fast object alone (a Gen3 recording's blob) costs the slopes of every pixel of
// its cluster for no change. docs/sweep.md ("A fast track measured from its own motion") has the
// measurements. The fixed-point core holds it (hls/track/motion_measure.h); no RTL build does.
#pragma once

#include <span>
#include <vector>

#include "golden/cluster/time_surface_slopes.h"
#include "golden/track/tracker.h"
#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

class MotionMeasure {
 public:
  MotionMeasure(const Params& params, SensorSize sensor);

  // `measurements`: per cluster, its box and pixel centre (cluster_of: per event, its cluster or
  // -1), whose x and y this replaces where the rule holds.
  void measure(std::span<const Event> events, std::span<const int> cluster_of, std::span<const TrackPrediction> tracks,
               std::vector<Measurement>& measurements);

 private:
  double least_speed_;
  int width_;
  TimeSurfaceSlopes slopes_;
  std::vector<char> pixel_taken_;  // per pixel, within one packet
};

}  // namespace evms::golden

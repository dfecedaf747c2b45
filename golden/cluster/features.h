// The feature of an event inside its packet, as the paper defines it:
//   [ s_xy * x / W,  s_xy * y / H,  s_p * p,  s_t * exp(-(t_newest - t) / tau) ]
// where t_newest is the newest event of the packet, so the newest event has time feature s_t
// and older events decay towards 0. A scale of 0 removes a dimension from the distance. With
// xy-scale isotropic, x and y are both divided by max(W, H), so the kernel is round in pixels.
#pragma once

#include <Eigen/Core>
#include <span>

#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

// Column i holds the feature of events[i]; rows are x, y, p, time.
using FeatureMatrix = Eigen::Matrix<double, 4, Eigen::Dynamic>;

// The pixel size of one unit of the x and y features.
Eigen::Vector2d feature_pixels(SensorSize sensor, const Params& params);

FeatureMatrix packet_features(std::span<const Event> events, SensorSize sensor,
                              const Params& params);

}  // namespace evms::golden

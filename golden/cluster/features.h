// The feature of an event inside its packet, as the paper defines it:
//   [ s_xy * x / W,  s_xy * y / H,  s_p * p,  s_t * exp(-(t_newest - t) / tau) ]
// where t_newest is the newest event of the packet, so the newest event has time feature s_t
// and older events decay towards 0. A scale of 0 removes a dimension from the distance.
#pragma once

#include <Eigen/Core>
#include <span>

#include "golden/event.h"
#include "golden/params.h"

namespace evms::golden {

// Column i holds the feature of events[i]; rows are x, y, p, time.
using FeatureMatrix = Eigen::Matrix<double, 4, Eigen::Dynamic>;

FeatureMatrix packet_features(std::span<const Event> events, SensorSize sensor,
                              const Params& params);

}  // namespace evms::golden

#include "golden/cluster/features.h"

#include <cmath>

namespace evms::golden {

Eigen::Vector2d feature_pixels(SensorSize sensor, const Params& params) {
  const FeatureSides side = feature_sides(params, sensor);
  return {side.x, side.y};
}

FeatureMatrix packet_features(std::span<const Event> events, SensorSize sensor,
                              const Params& params) {
  FeatureMatrix f(4, static_cast<Eigen::Index>(events.size()));
  if (events.empty()) return f;
  const Eigen::Vector2d px = feature_pixels(sensor, params);
  const TimeUs newest = events.back().t;
  for (size_t i = 0; i < events.size(); ++i) {
    const Event& e = events[i];
    const double dt = static_cast<double>(newest - e.t);
    f.col(static_cast<Eigen::Index>(i)) << params.scale_xy * e.x / px.x(),
        params.scale_xy * e.y / px.y(), params.scale_p * e.p,
        params.scale_t == 0 ? 0.0 : params.scale_t * std::exp(-dt / params.tau_us);
  }
  return f;
}

}  // namespace evms::golden

// Constant-velocity Kalman filter of one target, as in the paper: state [x, y, vx, vy] in px
// and px/s, measurement z = [x, y] (a cluster's centre of mass), and
//
//   A = [[I, dt I], [0, I]],   H = [I 0],   R = r I (r = sigma_z^2, or given per measurement),
//   Q = q [[dt^3/3 I, dt^2/2 I], [dt^2/2 I, dt I]]   (white-noise acceleration, q in px^2/s^3)
//
// with dt the time between the measurements' event timestamps. The covariance is updated in
// Joseph form so it stays symmetric and positive.
#pragma once

#include <Eigen/Core>

#include "types/event.h"
#include "types/params.h"

namespace evms::golden {

class KalmanFilter {
 public:
  using State = Eigen::Vector4d;
  using Covariance = Eigen::Matrix4d;

  // Starts at the first measurement with zero velocity and P0 = diag(sp^2, sp^2, sv^2, sv^2).
  KalmanFilter(double x, double y, TimeUs t, const Params& params);

  // Advances the state and covariance to time t (no-op when t is not newer).
  void predict(TimeUs t);
  // Corrects with a measured position at the current time, of variance r px^2 per axis
  // (without r: sigma_z^2, Params::meas_sigma_px).
  void update(double zx, double zy) { update(zx, zy, r_); }
  void update(double zx, double zy, double r);
  // Where the target is expected at time t, without changing the filter.
  Eigen::Vector2d predicted_position(TimeUs t) const;

  const State& state() const { return x_; }
  const Covariance& covariance() const { return p_; }
  TimeUs time() const { return t_; }

 private:
  State x_;
  Covariance p_;
  TimeUs t_;
  double q_;       // px^2/s^3
  double r_;       // px^2
};

}  // namespace evms::golden

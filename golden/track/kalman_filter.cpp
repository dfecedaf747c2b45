#include "golden/track/kalman_filter.h"

#include <Eigen/Dense>

namespace evms::golden {

KalmanFilter::KalmanFilter(double x, double y, TimeUs t, const Params& params)
    : t_(t), q_(params.accel_psd), r_(params.meas_sigma_px * params.meas_sigma_px) {
  x_ << x, y, 0, 0;
  const double sp2 = params.init_sigma_px * params.init_sigma_px;
  const double sv2 = params.init_sigma_vel * params.init_sigma_vel;
  p_ = Eigen::Vector4d(sp2, sp2, sv2, sv2).asDiagonal();
}

void KalmanFilter::predict(TimeUs t) {
  if (t <= t_) return;
  const double dt = static_cast<double>(t - t_) * 1e-6;
  Eigen::Matrix4d a = Eigen::Matrix4d::Identity();
  a(0, 2) = a(1, 3) = dt;
  Eigen::Matrix4d q = Eigen::Matrix4d::Zero();
  q(0, 0) = q(1, 1) = q_ * dt * dt * dt / 3.0;
  q(0, 2) = q(2, 0) = q(1, 3) = q(3, 1) = q_ * dt * dt / 2.0;
  q(2, 2) = q(3, 3) = q_ * dt;
  x_ = a * x_;
  p_ = a * p_ * a.transpose() + q;
  t_ = t;
}

void KalmanFilter::update(double zx, double zy, double r_px2) {
  Eigen::Matrix<double, 2, 4> h = Eigen::Matrix<double, 2, 4>::Zero();
  h(0, 0) = h(1, 1) = 1.0;
  const Eigen::Matrix2d r = Eigen::Matrix2d::Identity() * r_px2;
  const Eigen::Matrix2d s = h * p_ * h.transpose() + r;
  const Eigen::Matrix<double, 4, 2> k = p_ * h.transpose() * s.inverse();
  const Eigen::Vector2d innovation = Eigen::Vector2d(zx, zy) - h * x_;
  x_ += k * innovation;
  const Eigen::Matrix4d i_kh = Eigen::Matrix4d::Identity() - k * h;
  p_ = i_kh * p_ * i_kh.transpose() + k * r * k.transpose();
}

Eigen::Vector2d KalmanFilter::predicted_position(TimeUs t) const {
  const double dt = t > t_ ? static_cast<double>(t - t_) * 1e-6 : 0.0;
  return x_.head<2>() + dt * x_.tail<2>();
}

}  // namespace evms::golden

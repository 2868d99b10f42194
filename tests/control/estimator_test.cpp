// Estimator (docs/swath-control.md): Mahony's attitude converging from a wrong start on
// noise-free data; the per-axis Kalman filter's steady-state gain against the discrete algebraic
// Riccati equation (solved by the structured doubling algorithm) and against Kalata's closed form
// for the α-β filter; unbiasedness and consistency over fixed seeds; Δv rotated to world with
// gravity removed.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "swath/control/estimator.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::control {
namespace {

constexpr double kStandardGravity = 9.80665;

double angle_between(const Quat& a, const Quat& b) {
  return norm(vehicle::rotation_vector(conjugate(a) * b));
}

// Earth's field in world ENU: north, dipping 60° down.
const Vec3 kField{0, std::cos(60 * std::numbers::pi / 180), -std::sin(60 * std::numbers::pi / 180)};

// One execution's inputs from a true attitude q at body rate ω (held over dt), with gyro bias b.
EstimatorInput imu_from_truth(const Quat& q, const Vec3& rate, const Vec3& bias, double dt) {
  EstimatorInput in;
  in.imu.delta_angle_rad = (rate + bias) * dt;
  in.imu.delta_velocity_m_s = rotate_inverse(q, Vec3{0, 0, kStandardGravity}) * dt;
  in.imu.interval_s = dt;
  in.mag = {rotate_inverse(q, kField), true};
  return in;
}

TEST(Estimator, AttitudeConvergesFromAWrongStart) {
  const Quat truth0 = vehicle::from_rotation_vector({0.15, -0.1, 0.7});
  for (const Vec3 rate : {Vec3{0, 0, 0}, Vec3{0.3, -0.2, 0.5}}) {
    EstimatorSettings s;
    s.bias_gain_1_s = 0;  // the bias is GyroBiasIsLearnt's
    EstimatorState e = initial_estimate({}, vehicle::from_rotation_vector({0.6, 0.4, -1.2}));
    const double dt = 0.0025;
    Quat truth = truth0;
    double first = angle_between(e.attitude, truth), last = first;
    for (int k = 0; k < 60 * 400; ++k) {
      // A constant body rate turns the attitude exactly by exp(ω dt) each step.
      estimator_update(s, e, imu_from_truth(truth, rate, {}, dt));
      truth = normalized(truth * vehicle::from_rotation_vector(rate * dt));
      last = angle_between(e.attitude, truth);
    }
    EXPECT_GT(first, 1.0);
    EXPECT_LT(last, 1e-4) << "rate " << rate.x;
  }
}

TEST(Estimator, GyroBiasIsLearnt) {
  EstimatorSettings s;
  s.bias_gain_1_s = 0.2;
  const Quat truth = vehicle::from_rotation_vector({0.1, 0.2, -0.4});
  const Vec3 bias{0.02, -0.01, 0.015};
  EstimatorState e = initial_estimate({}, truth);
  for (int k = 0; k < 200 * 400; ++k)
    estimator_update(s, e, imu_from_truth(truth, {}, bias, 0.0025));
  EXPECT_NEAR(e.gyro_bias_rad_s.x, bias.x, 1e-5);
  EXPECT_NEAR(e.gyro_bias_rad_s.y, bias.y, 1e-5);
  EXPECT_NEAR(e.gyro_bias_rad_s.z, bias.z, 1e-5);
  EXPECT_LT(angle_between(e.attitude, truth), 1e-4);
  EXPECT_LT(norm(e.body_rate_rad_s), 1e-5);
}

TEST(Estimator, DeltaVelocityIsRotatedToWorldWithGravityRemoved) {
  EstimatorSettings s;
  s.attitude_gain_1_s = s.mag_gain_1_s = s.bias_gain_1_s = 0;  // hold the true attitude
  const Quat truth = vehicle::from_rotation_vector({0.3, -0.2, 1.1});
  const Vec3 accel{0.5, -0.2, 0.3};
  EstimatorState e = initial_estimate({1, 2, 3}, truth);
  const double dt = 0.0025;
  for (int k = 0; k < 400; ++k) {
    EstimatorInput in;
    in.imu.delta_velocity_m_s = rotate_inverse(truth, accel + Vec3{0, 0, kStandardGravity}) * dt;
    in.imu.interval_s = dt;
    estimator_update(s, e, in);
  }
  const Vec3 v = e.velocity_m_s(), p = e.position_m();
  EXPECT_NEAR(v.x, 0.5, 1e-9);
  EXPECT_NEAR(v.y, -0.2, 1e-9);
  EXPECT_NEAR(v.z, 0.3, 1e-9);
  EXPECT_NEAR(p.x, 1 + 0.25, 1e-9);
  EXPECT_NEAR(p.y, 2 - 0.1, 1e-9);
  EXPECT_NEAR(p.z, 3 + 0.15, 1e-9);
}

// The steady predicted covariance of x' = F x + w (cov Q), z = H x + v (cov R): the DARE
// X = F X Fᵀ − F X Hᵀ (H X Hᵀ + R)⁻¹ H X Fᵀ + Q by the structured doubling algorithm (Chu, Fan,
// Lin 2005) on X = Aᵀ X (I + G X)⁻¹ A + H with A = Fᵀ, G = Hᵀ R⁻¹ H, H = Q.
Eigen::Matrix2d dare_by_doubling(const Eigen::Matrix2d& f, const Eigen::RowVector2d& h, double r,
                                 const Eigen::Matrix2d& q) {
  Eigen::Matrix2d a = f.transpose(), g = h.transpose() * h / r, x = q;
  for (int k = 0; k < 60; ++k) {
    const Eigen::Matrix2d w = (Eigen::Matrix2d::Identity() + g * x).inverse();
    const Eigen::Matrix2d a1 = a * w * a, g1 = g + a * w * g * a.transpose(),
                          x1 = x + a.transpose() * x * w * a;
    a = a1, g = g1, x = x1;
  }
  return x;
}

TEST(Estimator, KalmanSteadyGainSolvesTheRiccatiEquation) {
  const double dt = 0.01, sigma_a = 0.5, sigma_z = 0.1;
  AxisFilter axis{0, 0, 4, 0, 4};
  double k0 = 0, k1 = 0;
  for (int n = 0; n < 5000; ++n) {
    kalman_predict(axis, 0.0, dt, sigma_a);
    const double s = axis.p_pp + sigma_z * sigma_z;
    k0 = axis.p_pp / s, k1 = axis.p_pv / s;
    kalman_update_position(axis, 0.0, sigma_z);
  }
  Eigen::Matrix2d f;
  f << 1, dt, 0, 1;
  const Eigen::Vector2d gam(dt * dt / 2, dt);
  const Eigen::Matrix2d q = sigma_a * sigma_a * gam * gam.transpose();
  const Eigen::Matrix2d x = dare_by_doubling(f, Eigen::RowVector2d(1, 0), sigma_z * sigma_z, q);
  const double s = x(0, 0) + sigma_z * sigma_z;
  EXPECT_NEAR(k0, x(0, 0) / s, 1e-10);
  EXPECT_NEAR(k1, x(1, 0) / s, 1e-9);
  // Kalata's α-β closed form for this (piecewise constant white acceleration) model:
  // λ = σ_a dt² / σ_z, α = −(λ² + 8λ − (λ + 4)√(λ² + 8λ)) / 8, β = (λ² + 4λ − λ√(λ² + 8λ)) / 4,
  // K = [α, β / dt].
  const double lambda = sigma_a * dt * dt / sigma_z;
  const double root = std::sqrt(lambda * lambda + 8 * lambda);
  const double alpha = -(lambda * lambda + 8 * lambda - (lambda + 4) * root) / 8;
  const double beta = (lambda * lambda + 4 * lambda - lambda * root) / 4;
  EXPECT_NEAR(k0, alpha, 1e-9);
  EXPECT_NEAR(k1, beta / dt, 1e-7);
}

TEST(Estimator, KalmanIsUnbiasedAndConsistentOverSeeds) {
  // The truth follows the filter's own model (piecewise constant white acceleration), so the
  // error must have mean 0 and variance P.
  const double dt = 0.01, sigma_a = 0.5, sigma_z = 0.1;
  const int seeds = 400, steps = 300;
  double sum_p = 0, sum_p2 = 0, sum_v = 0, sum_v2 = 0, p_pp = 0, p_vv = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    auto process = vehicle::SplitMix64::stream(static_cast<std::uint64_t>(seed), "process");
    auto meas = vehicle::SplitMix64::stream(static_cast<std::uint64_t>(seed), "measurement");
    double p = 0, v = 1;
    AxisFilter f{0, 1, 0, 0, 0};
    for (int k = 0; k < steps; ++k) {
      const double a = sigma_a * process.normal();
      p += v * dt + a * dt * dt / 2, v += a * dt;
      kalman_predict(f, 0.0, dt, sigma_a);
      kalman_update_position(f, p + sigma_z * meas.normal(), sigma_z);
    }
    const double ep = f.position_m - p, ev = f.velocity_m_s - v;
    sum_p += ep, sum_p2 += ep * ep, sum_v += ev, sum_v2 += ev * ev;
    p_pp = f.p_pp, p_vv = f.p_vv;
  }
  const double n = seeds;
  EXPECT_LT(std::abs(sum_p / n), 3 * std::sqrt(p_pp / n));
  EXPECT_LT(std::abs(sum_v / n), 3 * std::sqrt(p_vv / n));
  // Sample variance against P: its standard error is P √(2 / n) ≈ 7 % for n = 400.
  EXPECT_NEAR(sum_p2 / n / p_pp, 1.0, 0.22);
  EXPECT_NEAR(sum_v2 / n / p_vv, 1.0, 0.22);
}

TEST(Estimator, TruthModeHandsTheStateThrough) {
  EstimatorSettings s;
  s.type = EstimatorType::truth;
  EstimatorState e = initial_estimate({}, {});
  EstimatorInput in;
  in.truth = {{1, 2, 3}, {4, 5, 6}, vehicle::from_rotation_vector({0.1, 0.2, 0.3}), {7, 8, 9}};
  estimator_update(s, e, in);
  EXPECT_EQ(e.position_m(), (Vec3{1, 2, 3}));
  EXPECT_EQ(e.velocity_m_s(), (Vec3{4, 5, 6}));
  EXPECT_EQ(e.attitude, in.truth.attitude);
  EXPECT_EQ(e.body_rate_rad_s, (Vec3{7, 8, 9}));
}

}  // namespace
}  // namespace swath::control

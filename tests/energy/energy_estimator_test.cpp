#include "swath/energy/energy_estimator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "swath/energy/period_estimate.hpp"
#include "swath/energy/power_model.hpp"

namespace swath::energy {
namespace {

constexpr double kPi = std::numbers::pi;

double truth(double t, double T) {
  const double w = 2 * kPi / T;
  return 150.0 + 10.0 * std::sin(w * t) + 6.0 * std::cos(2 * w * t) - 3.0 * std::sin(3 * w * t);
}

// The filter learns a periodic signal it was not initialised with: after three periods its error
// against the noiseless signal is below the measurement noise.
TEST(EnergyEstimator, TracksAPeriodicSignalWithinThreePeriods) {
  const double T = 20.0, dt = 0.01, sigma = 3.0;
  GaussianNoise noise(11, sigma);
  KalmanSettings k;
  k.measurement_w = sigma;
  k.process_w = 0.5;
  k.gate_w = 0.0;  // always correct: the plain Kalman filter
  EnergyEstimator est(fourier_model(3, T, dt), k, truth(0, T) + noise.next());
  KalmanSettings off = k;
  off.gate_w = 1e9;  // the same model never corrected
  EnergyEstimator open_loop(fourier_model(3, T, dt), off, truth(0, T));
  double open_loop_rms = 0.0;
  std::vector<double> rms_by_period(6, 0.0);
  const int per_period = static_cast<int>(T / dt);
  for (int i = 1; i < 6 * per_period; ++i) {
    const double t = i * dt;
    est.predict();
    est.correct(truth(t, T) + noise.next());
    const double e = est.output_w() - truth(t, T);
    rms_by_period[i / per_period] += e * e / per_period;
    open_loop.predict();
    const double e_open = open_loop.output_w() - truth(t, T);
    open_loop_rms += e_open * e_open / (6 * per_period);
  }
  for (double& r : rms_by_period) r = std::sqrt(r);
  EXPECT_GT(std::sqrt(open_loop_rms), 2 * sigma);  // it had something to learn
  for (int p = 3; p < 6; ++p) EXPECT_LT(rms_by_period[p], 0.5 * sigma) << "period " << p + 1;
}

TEST(EnergyEstimator, TheGateKeepsTheModelOpenLoop) {
  KalmanSettings k;
  k.gate_w = 50.0;
  EnergyEstimator est(fourier_model(3, 20.0, 0.01), k, 150.0);
  for (int i = 0; i < 500; ++i) {
    est.predict();
    EXPECT_FALSE(est.correct(150.0 + 40.0 * std::sin(i * 0.01)));
  }
  EXPECT_EQ(est.corrections(), 0);
  EXPECT_NEAR(est.output_w(), 150.0, 1e-9);
  est.predict();
  EXPECT_TRUE(est.correct(260.0));  // beyond the gate
  EXPECT_GT(est.output_w(), 150.0);
  EXPECT_FALSE(est.correct(std::nan("")));  // no measurement: open loop
}

// One correction against a dense, textbook computation (Eigen): the same state, and the Joseph
// covariance equals (I - K C) P for the optimal gain and stays symmetric.
TEST(EnergyEstimator, CorrectionMatchesTheDenseFormulas) {
  const double T = 15.0, dt = 0.05;
  KalmanSettings k;
  k.gate_w = 0.0;
  k.process_w = 2.0;
  EnergyEstimator est(fourier_model(2, T, dt), k, 120.0);
  for (int i = 0; i < 37; ++i) {
    est.predict();
    est.correct(120.0 + 8.0 * std::sin(2 * kPi * i * dt / T * 3.0));
  }
  const int n = est.model().states();
  Eigen::MatrixXd a(n, n), p(n, n);
  const std::vector<double> av = transition_matrix(est.model());
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      a(r, c) = av[r * n + c];
      p(r, c) = est.covariance()[r * n + c];
    }
  Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(est.state().data(), n);
  Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(n);
  c(0) = 1.0 / T;
  for (int j = 1; j < n; j += 2) c(j) = 1.0 / T;
  const double y = 131.0;
  const Eigen::VectorXd q_minus = a * q;
  const double qn = T * k.process_w;
  const Eigen::MatrixXd p_minus =
      a * p * a.transpose() + qn * qn * dt * Eigen::MatrixXd::Identity(n, n);
  const double s = (c * p_minus * c.transpose())(0, 0) + k.measurement_w * k.measurement_w;
  const Eigen::VectorXd gain = p_minus * c.transpose() / s;
  const Eigen::VectorXd q_plus = q_minus + gain * (y - (c * q_minus)(0));
  const Eigen::MatrixXd p_plus = (Eigen::MatrixXd::Identity(n, n) - gain * c) * p_minus;

  est.predict();
  ASSERT_TRUE(est.correct(y));
  for (int r = 0; r < n; ++r) {
    EXPECT_NEAR(est.state()[r], q_plus(r), 1e-9 * std::max(1.0, std::abs(q_plus(r))));
    for (int col = 0; col < n; ++col) {
      const double got = est.covariance()[r * n + col];
      EXPECT_NEAR(got, p_plus(r, col), 1e-7 * std::max(1.0, std::abs(p_plus(r, col))));
      EXPECT_DOUBLE_EQ(got, est.covariance()[col * n + r]);
    }
  }
}

TEST(PeriodEstimate, FindsThePeriodNotAMultiple) {
  const double dt = 0.1, T = 12.5;
  std::vector<double> x;
  GaussianNoise noise(5, 1.0);
  for (int i = 0; i < 1000; ++i) x.push_back(truth(i * dt, T) + noise.next());
  const auto found = estimate_period_s(x, dt, 5.0, 40.0);
  ASSERT_TRUE(found);
  EXPECT_NEAR(*found, T, 0.01 * T);
  // White noise does not repeat.
  std::vector<double> white;
  for (int i = 0; i < 1000; ++i) white.push_back(noise.next());
  EXPECT_FALSE(estimate_period_s(white, dt, 5.0, 40.0));
  // Too short a window for the lags asked.
  EXPECT_FALSE(estimate_period_s(std::vector<double>(x.begin(), x.begin() + 60), dt, 5.0, 40.0));
}

TEST(EnergyEstimator, PeriodChangeKeepsOutputAndScalesCovariance) {
  KalmanSettings k;
  EnergyEstimator est(fourier_model(2, 20.0, 0.01), k, 100.0);
  for (int i = 0; i < 100; ++i) {
    est.predict();
    est.correct(100.0 + 5.0 * std::sin(i * 0.05));
  }
  const double before = est.output_w();
  const double p00 = est.covariance()[0];
  est.set_period(30.0);
  EXPECT_NEAR(est.output_w(), before, 1e-9);
  EXPECT_NEAR(est.covariance()[0], p00 * 2.25, 1e-9 * p00);
}

}  // namespace
}  // namespace swath::energy

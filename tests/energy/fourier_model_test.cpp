#include "swath/energy/fourier_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

namespace swath::energy {
namespace {

// h(t) of paper 004 eq. 4.
double series(double a0, const std::vector<double>& a, const std::vector<double>& b, double T,
              double t) {
  double h = a0 / T;
  for (std::size_t j = 0; j < a.size(); ++j) {
    const double wj = 2 * std::numbers::pi / T * static_cast<double>(j + 1);
    h += 2.0 / T * (a[j] * std::cos(wj * t) + b[j] * std::sin(wj * t));
  }
  return h;
}

// Lemma II.2: no noise, no input, initialised from the series: the output is the series.
TEST(FourierModel, OutputEqualsTheSeriesOverManyPeriods) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> coef(-50.0, 50.0);
  for (int order : {0, 1, 3, 6}) {
    const double T = 7.3, dt = 0.01;
    const double a0 = 1500.0;
    std::vector<double> a, b;
    for (int j = 0; j < order; ++j) {
      a.push_back(coef(rng));
      b.push_back(coef(rng));
    }
    const FourierModel m = fourier_model(order, T, dt);
    std::vector<double> q = state_of_series(a0, a, b, T);
    double worst = 0.0;
    const int steps = static_cast<int>(100 * T / dt);  // 100 periods
    for (int k = 0; k <= steps; ++k) {
      worst = std::max(worst, std::abs(output_w(m, q) - series(a0, a, b, T, k * dt)));
      advance_state(m, q);
    }
    EXPECT_LT(worst, 1e-9) << "order " << order;
  }
}

// The exact discretisation is the matrix exponential of A dt (Eigen's Pade approximant).
TEST(FourierModel, TransitionIsTheMatrixExponential) {
  const FourierModel m = fourier_model(4, 13.0, 0.37);
  const int n = m.states();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  const double w = 2 * std::numbers::pi / 13.0;
  for (int j = 1; j <= 4; ++j) {
    a(2 * j - 1, 2 * j) = w * j;
    a(2 * j, 2 * j - 1) = -w * j;
  }
  const Eigen::MatrixXd expected = (a * 0.37).exp();
  const std::vector<double> got = transition_matrix(m);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) EXPECT_NEAR(got[r * n + c], expected(r, c), 1e-13);
}

TEST(FourierModel, EnergyOverAHorizonIsTheIntegralOfTheOutput) {
  const double T = 20.0;
  const std::vector<double> a{12.0, -4.0}, b{3.0, 7.5};
  const FourierModel m = fourier_model(2, T, 0.01);
  const std::vector<double> q = state_of_series(3000.0, a, b, T);
  for (double horizon : {0.5, 7.0, 20.0, 53.3}) {
    // Simpson's rule on the series, 20,000 intervals.
    const int n = 20000;
    const double h = horizon / n;
    double sum = series(3000.0, a, b, T, 0) + series(3000.0, a, b, T, horizon);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * series(3000.0, a, b, T, i * h);
    EXPECT_NEAR(energy_over_j(m, q, horizon), sum * h / 3.0, 1e-6) << horizon;
  }
  // Over whole periods only the mean remains: alpha_0 per period.
  EXPECT_NEAR(energy_over_j(m, q, 3 * T), 3 * 3000.0, 1e-9);
}

TEST(FourierModel, MeasurementInitialisationAndSteps) {
  const FourierModel m = fourier_model(3, 30.0, 0.01);
  std::vector<double> q = state_of_measurement(172.5, m);
  EXPECT_DOUBLE_EQ(output_w(m, q), 172.5);
  apply_power_step(m, q, -9.75);  // detection switched off
  EXPECT_NEAR(output_w(m, q), 162.75, 1e-12);
  for (int k = 0; k < 1000; ++k) advance_state(m, q);
  EXPECT_NEAR(output_w(m, q), 162.75, 1e-12);  // no harmonics: constant
}

TEST(FourierModel, ChangingThePeriodKeepsTheOutputNow) {
  FourierModel m = fourier_model(2, 20.0, 0.01);
  std::vector<double> q = state_of_series(3000.0, {12.0, -4.0}, {3.0, 7.5}, 20.0);
  for (int k = 0; k < 321; ++k) advance_state(m, q);
  const double before = output_w(m, q);
  m = with_period(m, q, 26.0);
  EXPECT_NEAR(output_w(m, q), before, 1e-12);
  EXPECT_DOUBLE_EQ(m.period_s, 26.0);
}

}  // namespace
}  // namespace swath::energy

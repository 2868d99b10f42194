// PID (docs/swath-control.md: PI and PD closed-form step responses): closed loops on a
// first-order plant τ ẏ = −y + u against their continuous closed forms, with the error falling
// linearly in the step (the discrete loop converges to the continuous one); the derivative on the
// measurement, its low-pass and the integrator clamp against exact recurrences.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "swath/control/pid.hpp"

namespace swath::control {
namespace {

// The largest |y_k − closed(t_k)| over [0, t_end] for the plant τ ẏ = −y + u, discretised exactly
// under a zero-order hold of u over each step dt.
double worst_error(const PidGains& g, double tau, double dt, double t_end,
                   const std::function<double(double)>& closed) {
  PidState s;
  double y = 0, worst = 0;
  const double phi = std::exp(-dt / tau);
  const int steps = static_cast<int>(std::lround(t_end / dt));
  for (int k = 0; k < steps; ++k) {
    worst = std::max(worst, std::abs(y - closed(k * dt)));
    const double u = pid_update(g, s, 1.0, y, dt);
    y = phi * y + (1 - phi) * u;
  }
  return worst;
}

TEST(Pid, PiStepResponseMatchesTheContinuousClosedForm) {
  // Ki / Kp = 1 / τ cancels the plant's pole: the loop is Kp / (τ s), so y = 1 − e^(−Kp t / τ).
  const double tau = 0.5, kp = 2.0;
  const PidGains g{kp, kp / tau, 0, 100, 0};
  const auto closed = [&](double t) { return 1 - std::exp(-kp * t / tau); };
  const double e1 = worst_error(g, tau, 1e-3, 3.0, closed);
  const double e2 = worst_error(g, tau, 5e-4, 3.0, closed);
  EXPECT_LT(e1, 5e-3);
  EXPECT_NEAR(e1 / e2, 2.0, 0.1);  // first order in dt: the loops agree in the limit
}

TEST(Pid, PdStepResponseMatchesTheContinuousClosedForm) {
  // D on the measurement: (τ + Kd) ẏ = −(1 + Kp) y + Kp r, so
  // y = Kp / (1 + Kp) · (1 − e^(−(1 + Kp) t / (τ + Kd))), no overshoot and a steady offset.
  const double tau = 0.5, kp = 3.0, kd = 0.1;
  const PidGains g{kp, 0, kd, 0, 0};
  const auto closed = [&](double t) {
    return kp / (1 + kp) * (1 - std::exp(-(1 + kp) * t / (tau + kd)));
  };
  const double e1 = worst_error(g, tau, 1e-3, 2.0, closed);
  const double e2 = worst_error(g, tau, 5e-4, 2.0, closed);
  EXPECT_LT(e1, 5e-3);
  EXPECT_NEAR(e1 / e2, 2.0, 0.15);
}

TEST(Pid, NoDerivativeKickOnASetpointStep) {
  const PidGains g{2.0, 3.0, 5.0, 10, 0};
  PidState s;
  const double dt = 0.01;
  double out = 0;
  for (int k = 0; k < 10; ++k) out = pid_update(g, s, 0.0, 0.0, dt);
  EXPECT_EQ(out, 0.0);
  // Only P and I see the step; D (on the unchanged measurement) adds nothing.
  out = pid_update(g, s, 1.0, 0.0, dt);
  EXPECT_DOUBLE_EQ(out, 2.0 + 3.0 * dt);
}

TEST(Pid, DerivativeLowPassFollowsItsRecurrence) {
  // A ramp y = c t: the raw derivative is c from the second update on, and the filtered one is
  // c (1 − (1 − α)^(n−1)) after n updates, α = dt / (dt + 1 / (2π f)).
  const double c = 0.7, dt = 0.002, f = 30, kd = 0.5;
  const PidGains g{0, 0, kd, 0, f};
  const double alpha = dt / (dt + 1 / (2 * std::numbers::pi * f));
  PidState s;
  for (int n = 1; n <= 200; ++n) {
    const double out = pid_update(g, s, 0.0, c * n * dt, dt);
    const double expected = -kd * c * (1 - std::pow(1 - alpha, n - 1));
    EXPECT_NEAR(out, expected, 1e-12) << n;
  }
}

TEST(Pid, IntegratorIsClampedBothWays) {
  const PidGains g{1.0, 10.0, 0, 0.5, 0};
  PidState s;
  double out = 0;
  for (int k = 0; k < 100; ++k) out = pid_update(g, s, 1.0, 0.0, 0.01);
  EXPECT_DOUBLE_EQ(s.integral, 0.5);
  EXPECT_DOUBLE_EQ(out, 1.5);
  for (int k = 0; k < 100; ++k) out = pid_update(g, s, -1.0, 0.0, 0.01);
  EXPECT_DOUBLE_EQ(s.integral, -0.5);
  EXPECT_DOUBLE_EQ(out, -1.5);
}

}  // namespace
}  // namespace swath::control

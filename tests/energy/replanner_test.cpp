#include "swath/energy/replanner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lawnmower_plan.hpp"
#include "swath/energy/simulation.hpp"

namespace swath::energy {
namespace {

// The solver against brute force over every level and 2,001 lambdas, on random small problems:
// the rest takes longer with a wider trajectory, and each level costs its own power.
TEST(Replanner, MatchesBruteForce) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int feasible_cases = 0, infeasible_cases = 0;
  for (int trial = 0; trial < 60; ++trial) {
    ReplanProblem p;
    p.computation_bounds = {{2, 2 + std::floor(6 * u(rng))}, {0, std::floor(4 * u(rng))}};
    p.quality_weights = {1.0, 0.5 + u(rng)};
    p.trajectory_free = trial % 3 != 0;
    const double base_w = 20 + 30 * u(rng), t0 = 300 + 600 * u(rng), stretch = 0.5 * u(rng);
    const double w1 = 0.5 + u(rng), w2 = 0.2 + u(rng);
    p.rest_time_s = [=](double l) { return t0 * (1 + stretch * l); };
    p.rest_energy_j = [=](double l, const std::vector<double>& c) {
      return t0 * (1 + stretch * l) * (base_w + w1 * c[0] + w2 * c[1]);
    };
    p.battery.capacity_ah = 0.1 + 1.2 * u(rng);
    p.soc = 0.4 + 0.6 * u(rng);
    const ReplanChoice got = choose_parameters(p);

    // Brute force: the best quality, then the widest lambda, among choices that fit.
    bool any = false;
    double best_q = -1, best_l = -1;
    std::vector<double> best_c;
    for (double c0 = p.computation_bounds[0].lo; c0 <= p.computation_bounds[0].hi; ++c0)
      for (double c1 = p.computation_bounds[1].lo; c1 <= p.computation_bounds[1].hi; ++c1)
        for (int i = 0; i <= 2000; ++i) {
          const double l = p.trajectory_free ? i / 2000.0 : 1.0;
          if (!fits(p, l, {c0, c1})) continue;
          const double q = computation_quality(p.computation_bounds, p.quality_weights, {c0, c1});
          if (!any || q > best_q + 1e-12 || (std::abs(q - best_q) <= 1e-12 && l > best_l)) {
            any = true;
            best_q = q;
            best_l = l;
            best_c = {c0, c1};
          }
          if (!p.trajectory_free) break;
        }
    ASSERT_EQ(got.feasible, any) << trial;
    if (!any) {
      ++infeasible_cases;
      EXPECT_EQ(got.computations, (std::vector<double>{p.computation_bounds[0].lo, 0.0}));
      continue;
    }
    ++feasible_cases;
    EXPECT_NEAR(computation_quality(p.computation_bounds, p.quality_weights, got.computations),
                best_q, 1e-12)
        << trial;
    EXPECT_NEAR(got.lambda, best_l, 1e-3) << trial;
    EXPECT_TRUE(fits(p, got.lambda, got.computations));
  }
  EXPECT_GE(feasible_cases, 20);
  EXPECT_GT(infeasible_cases, 3);
}

SimConfig lawnmower_config(double capacity_ah) {
  SimConfig c;
  c.source = "test.yaml";
  c.start = {0, -20};
  c.output_interval_s = 1.0;
  c.power.mechanical.cruise_w = 25.0;
  c.power.noise_w = 2.0;
  c.power.computations = {{"fps", {{2, 4.75}, {10, 9.75}}}};
  c.battery.capacity_ah = capacity_ah;
  c.battery.reserve_soc = 0.1;
  return c;
}

const Plan& lawnmower() {
  static const Plan plan = parse_plan(test::lawnmower_plan(24, 50, 400), "lawnmower.stages");
  return plan;
}

TEST(Replanning, EnoughBatteryKeepsTheHighestParameters) {
  const SimulationResult r = simulate(lawnmower(), lawnmower_config(5.0));
  ASSERT_EQ(r.status, SimulationEnd::completed);
  EXPECT_GT(r.replans, 900);
  EXPECT_EQ(r.control.size(), 1u);  // never changed
  EXPECT_NEAR(r.mean_computations[0], 10.0, 1e-9);
}

// 0.51 Ah: the highest level does not reach the end, the lowest does with charge to spare.
TEST(Replanning, TightBatteryFinishesAboveTheReserveBetweenTheLevels) {
  const SimConfig c = lawnmower_config(0.51);
  const FixedComparison fixed = compare_fixed(lawnmower(), c);
  EXPECT_EQ(fixed.highest.status, SimulationEnd::battery_empty);
  ASSERT_EQ(fixed.lowest.status, SimulationEnd::completed);
  EXPECT_GT(fixed.lowest.final_soc, c.battery.reserve_soc);
  EXPECT_GT(fixed.minutes_per_hour, 5.0);
  const SimulationResult r = simulate(lawnmower(), c);
  ASSERT_EQ(r.status, SimulationEnd::completed);
  EXPECT_GE(r.final_soc, c.battery.reserve_soc);
  EXPECT_GT(r.mean_computations[0], 2.2);
  EXPECT_LT(r.mean_computations[0], 9.8);
  EXPECT_GT(r.control.size(), 2u);
}

TEST(Replanning, TooSmallForAnythingSaysSo) {
  const SimulationResult r = simulate(lawnmower(), lawnmower_config(0.3));
  EXPECT_EQ(r.status, SimulationEnd::battery_empty);
  EXPECT_GT(r.infeasible_replans, 0);
  ASSERT_GE(r.control.size(), 2u);
  EXPECT_FALSE(r.control.back().feasible);
  EXPECT_DOUBLE_EQ(r.control.back().computations[0], 2.0);  // the lowest level
}

}  // namespace
}  // namespace swath::energy

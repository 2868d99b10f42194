// swath-energy: one simulation step, a one-hour mission at dt = 0.01 s (target < 1 s), and the
// Kalman step with the model's block structure beside the textbook dense update (Eigen).
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cmath>

#include "lawnmower_plan.hpp"
#include "swath/energy/energy_estimator.hpp"
#include "swath/energy/guidance.hpp"
#include "swath/energy/simulation.hpp"

namespace {

using namespace swath::energy;

SimConfig lawnmower_config() {
  SimConfig c;
  c.source = "bench";
  c.time_step_s = 0.01;
  c.start = {0, -20};
  c.initial_period_s = 60;
  c.power.noise_w = 3;
  c.battery.capacity_ah = 40;  // enough for the hour
  c.max_time_s = 7200;
  c.power.computations = {{"fps", {{2, 4.75}, {10, 9.75}}}};
  c.computation_parameters = {10};
  return c;
}

// 90 lanes of 400 m, 50 m apart, at 12 m/s: 3,585 s of flight, 358,487 steps, replanning the
// detection rate every second.
void BM_OneHourMission(benchmark::State& state) {
  const Plan plan = parse_plan(swath::test::lawnmower_plan(90, 50, 400), "lawnmower.plan");
  const SimConfig c = lawnmower_config();
  double flown = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate(plan, c);
    flown = r.flight_time_s;
    benchmark::DoNotOptimize(r.energy_j);
  }
  state.counters["flight_s"] = flown;
}
BENCHMARK(BM_OneHourMission)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// The same without the replanner (parameters fixed).
void BM_OneHourMissionFixed(benchmark::State& state) {
  const Plan plan = parse_plan(swath::test::lawnmower_plan(90, 50, 400), "lawnmower.plan");
  SimConfig c = lawnmower_config();
  c.replan = false;
  for (auto _ : state) benchmark::DoNotOptimize(simulate(plan, c).energy_j);
}
BENCHMARK(BM_OneHourMissionFixed)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// The guidance field at one point (phi and its gradient: five expression evaluations).
void BM_GuidanceStep(benchmark::State& state) {
  const Plan plan = parse_plan(swath::test::lawnmower_plan(2, 50, 400), "lawnmower.plan");
  auto fields = stage_fields(plan, {});
  swath::geometry::Point2 p{10.0, 399.0};
  for (auto _ : state) {
    const auto d = guidance_direction(fields[1], p);
    benchmark::DoNotOptimize(d);
    p.x += 1e-9;
  }
}
BENCHMARK(BM_GuidanceStep);

void BM_KalmanStepStructured(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  KalmanSettings k;
  k.gate_w = 0;
  EnergyEstimator est(fourier_model(order, 40.0, 0.01), k, 150.0);
  double t = 0;
  for (auto _ : state) {
    est.predict();
    est.correct(150.0 + 10.0 * std::sin(t));
    t += 0.01;
  }
}
BENCHMARK(BM_KalmanStepStructured)->Arg(3)->Arg(6)->Arg(12);

// The same predict + correct with dense matrices: A P A^T, K = P C^T / s, Joseph form.
void BM_KalmanStepDense(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const FourierModel m = fourier_model(order, 40.0, 0.01);
  const int n = m.states();
  const std::vector<double> av = transition_matrix(m);
  Eigen::MatrixXd a(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) a(r, c) = av[r * n + c];
  Eigen::RowVectorXd cm = Eigen::RowVectorXd::Zero(n);
  cm(0) = 1.0 / 40.0;
  for (int j = 1; j < n; j += 2) cm(j) = 1.0 / 40.0;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  q(0) = 40.0 * 150.0;
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(n, n) * 640000.0;
  const Eigen::MatrixXd qn = Eigen::MatrixXd::Identity(n, n) * 0.16;
  const Eigen::MatrixXd eye = Eigen::MatrixXd::Identity(n, n);
  double t = 0;
  for (auto _ : state) {
    q = a * q;
    p = a * p * a.transpose() + qn;
    const double s = (cm * p * cm.transpose())(0, 0) + 4.0;
    const Eigen::VectorXd gain = p * cm.transpose() / s;
    q += gain * (150.0 + 10.0 * std::sin(t) - (cm * q)(0));
    const Eigen::MatrixXd l = eye - gain * cm;
    p = l * p * l.transpose() + gain * 4.0 * gain.transpose();
    benchmark::DoNotOptimize(q.data());
    t += 0.01;
  }
}
BENCHMARK(BM_KalmanStepDense)->Arg(3)->Arg(6)->Arg(12);

}  // namespace

BENCHMARK_MAIN();

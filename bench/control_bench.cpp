// The control task's costs (docs/performance.md: one control execution ≤ 3 µs): one execution with
// the complementary estimator and every sensor fresh, the mixer alone, and one simulated second
// of the flight computer under TT400 with 1 kHz samples and the default background work.

#include <benchmark/benchmark.h>

#include "swath/control/control_files.hpp"
#include "swath/control/logistic.hpp"
#include "swath/control/mission.hpp"
#include "swath/control/reactive_scheduler.hpp"
#include "swath/control/simulation.hpp"

#include "swath/control/computer.hpp"
#include "swath/control/control_task.hpp"

namespace swath::control {
namespace {

void ControlExecution(benchmark::State& st) {
  const ControlTask task = *ControlTask::create(ControlTaskConfig{});
  TaskState state = task.initial_state({0, 0, 5});
  TaskInput in;
  in.sensors.imu = {{1e-4, -2e-4, 5e-5}, {0.001, -0.002, 0.0245}, 0.0025};
  in.sensors.mag = {{0.1, 0.5, -0.85}, true};
  in.sensors.baro = {5.01, true};
  in.sensors.fix = {{0.01, -0.02, 5.0}, {0.0, 0.1, 0.0}, true, true};
  in.setpoint.position_m = {1, 0, 5};
  for (auto _ : st) {
    in.time_ns += 2'500'000;
    benchmark::DoNotOptimize(task.execute(state, in));
  }
}
BENCHMARK(ControlExecution);

void Mixer(benchmark::State& st) {
  const MixerRotors layout = standard_layout(vehicle::RotorLayout::hexa_x, 0.275);
  const MixerMatrices m = *mixer_matrices(layout);
  double roll = 0;
  for (auto _ : st) {
    roll = roll > 1 ? 0 : roll + 1e-3;
    benchmark::DoNotOptimize(mix(layout, m, Wrench{23.0, {roll, 0.1, 0.02}}));
  }
}
BENCHMARK(Mixer);

void ComputerSecondTt400(benchmark::State& st) {
  for (auto _ : st) {
    FlightComputer cpu{ComputerSettings{}};
    TimeTriggeredScheduler tt = *TimeTriggeredScheduler::at_rate(400);
    for (SimTime t = 0; t < 1'000'000'000; t += 500'000) {  // 2 kHz of events
      while (cpu.advance(t)) {
      }
      if (t % 1'000'000 == 0) cpu.sample();
      if (t == tt.next_release_ns()) cpu.request_control(tt.take_release());
    }
    benchmark::DoNotOptimize(cpu.stats().busy_ns);
  }
}
BENCHMARK(ComputerSecondTt400)->Unit(benchmark::kMicrosecond);

// docs/performance.md target: 10 minutes of flight at 1 ms steps in ≤ 1 s on one core — the whole
// simulation (plant, sensors, driver, computer model, TT400 control task, carrot, battery,
// metrics), the rows computed but not written. Arg: the environment (0 calm, 1 arch).
void TenMinutesOfFlight(benchmark::State& st) {
  SimulationSettings s;
  s.environment = vehicle::environment_preset(st.range(0) == 0 ? "calm" : "arch");
  s.mission = closed_for_loop(random_mission(RandomSpec{8, 170, 170}, 5, 1));
  s.loop = true;
  s.speed_m_s = 3;
  s.scheduler.run.max_time_s = 600;
  struct Rows : SimulationObserver {
    std::size_t bytes = 0;
    void on_row(const TimeseriesRow& r) override { bytes += timeseries_csv_row(r).size(); }
  } rows;
  for (auto _ : st) {
    const SimulationSummary r = simulate(s, &rows);
    benchmark::DoNotOptimize(r.total_j);
  }
  st.counters["simulated_s_per_s"] =
      benchmark::Counter(600.0 * static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(TenMinutesOfFlight)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(2);

// The same ten minutes in ARCH with reactive execution (30 s boot, then triggers): the target is
// at most twice the time-triggered flight's time.
void TenMinutesOfFlightReactive(benchmark::State& st) {
  SimulationSettings s;
  s.environment = vehicle::environment_preset("arch");
  s.mission = closed_for_loop(random_mission(RandomSpec{8, 170, 170}, 5, 1));
  s.loop = true;
  s.speed_m_s = 3;
  s.scheduler.mode = SchedulerMode::reactive;
  s.scheduler.run.max_time_s = 600;
  for (auto _ : st) benchmark::DoNotOptimize(simulate(s, nullptr).total_j);
}
BENCHMARK(TenMinutesOfFlightReactive)->Unit(benchmark::kMillisecond)->Iterations(2);

// One sample through the reactive scheduler's trigger check (target ≤ 5 ns).
void TriggerCheck(benchmark::State& st) {
  ReactiveSettings r;
  r.boot_s = 0;
  r.initial_models = {{"gyro", -3, 2}};
  ReactiveScheduler sched(r, {{"gyro", 0, 1'000'000}}, 400);
  sched.on_execution_start(0);
  SensorSample sample;
  sample.axes = 3;
  SimTime t = 0;
  for (auto _ : st) {
    sample.time_ns = (t += 1'000'000);
    sample.value[0] = static_cast<double>(t % 3) * 1e-4;  // below x*: no release
    sched.on_sample(sample);
  }
  benchmark::DoNotOptimize(sched.next_release_ns());
}
BENCHMARK(TriggerCheck);

// A refit of 20,000 points (target ≤ 2 ms), each method.
void Refit(benchmark::State& st) {
  auto random = vehicle::SplitMix64::stream(1, "bench");
  std::vector<TriggerPoint> data;
  for (int i = 0; i < 20'000; ++i) {
    const double x = random.uniform(0, 4);
    data.push_back({x, random.uniform() < 1 / (1 + std::exp(3 - 2 * x))});
  }
  const auto method = static_cast<FitMethod>(st.range(0));
  for (auto _ : st) benchmark::DoNotOptimize(fit_logistic(data, method).beta2);
}
BENCHMARK(Refit)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace swath::control
BENCHMARK_MAIN();

// The plant's cost per simulated second (docs/performance.md: 10 min of flight at 1 ms steps in <=
// 2 s on one core with the controller; the plant is most of it): the bare rigid body, the body with
// its ESCs, wind and five sensors on the event clock, in calm air and in ARCH's wind.
#include <benchmark/benchmark.h>

#include "swath/vehicle/flight_model.hpp"

namespace swath::vehicle {
namespace {

void RigidBodyOneSimulatedSecond(benchmark::State& state) {
  const Airframe a;
  MultirotorState s;
  s.position_m = {0, 0, 10};
  MultirotorInputs in;
  s.rotor_rad_s = in.command_rad_s = hover(a).rotor_rad_s;
  for (auto _ : state) {
    const MultirotorState after = integrate(a, s, in, 1.0, 0.001);
    benchmark::DoNotOptimize(after);
  }
  state.SetLabel("1 s at 1 ms steps");
}
BENCHMARK(RigidBodyOneSimulatedSecond)->Unit(benchmark::kMillisecond);

void FlightModelTenSimulatedSeconds(benchmark::State& state, const char* environment) {
  FlightModelSettings settings;
  settings.environment = environment_preset(environment);
  settings.initial.position_m = {0, 0, 10};
  settings.initial.rotor_rad_s = hover(settings.physics.airframe).rotor_rad_s;
  std::size_t samples = 0;
  for (auto _ : state) {
    FlightModel m(settings);
    for (int k = 1; k <= 4000; ++k) {  // a controller's 400 Hz: commands and sample reads
      m.advance_to(static_cast<SimTime>(k) * 2'500'000);
      samples += m.take_samples().size();
      for (std::size_t i = 0; i < 4; ++i) m.command_pwm(i, 1500);
    }
    benchmark::DoNotOptimize(m.state());
  }
  state.counters["samples"] =
      benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kAvgIterations);
  state.SetLabel("10 s simulated, 5 sensors, 490 Hz ESC, 200 Hz wind");
}
BENCHMARK_CAPTURE(FlightModelTenSimulatedSeconds, calm, "calm")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(FlightModelTenSimulatedSeconds, arch, "arch")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace swath::vehicle

BENCHMARK_MAIN();

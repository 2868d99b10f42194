// The fleet schedulers (DESIGN.md §18.12): one decision for 100 drones and 1,000 requests
// (target: simulated annealing p50 ≤ 20 ms, p99 ≤ 50 ms), beside the exact Hungarian and greedy.
#include <benchmark/benchmark.h>

#include "swath/fleet/scheduler.hpp"

namespace swath::fleet {
namespace {

Snapshot instance(std::size_t drones, std::size_t requests) {
  auto rng = vehicle::SplitMix64::stream(7, "bench");
  Snapshot s;
  for (std::size_t d = 0; d < drones; ++d) {
    DroneState x;
    x.position_m = {rng.uniform(0, 3000), rng.uniform(0, 3000), 10};
    s.drones.push_back(x);
  }
  for (std::size_t r = 0; r < requests; ++r) {
    Request q;
    q.location_m = {rng.uniform(0, 3000), rng.uniform(0, 3000), 10};
    q.service_s = 5;
    q.waiting_s = rng.uniform(0, 60);
    s.requests.push_back(q);
  }
  return s;
}

void Decision(benchmark::State& st) {
  const Snapshot s =
      instance(static_cast<std::size_t>(st.range(1)), static_cast<std::size_t>(st.range(2)));
  const char* names[] = {"sa", "hungarian", "greedy"};
  auto scheduler = make_scheduler(names[st.range(0)]);
  auto rng = vehicle::SplitMix64::stream(1, "sa");
  for (auto _ : st) benchmark::DoNotOptimize(scheduler->assign(s, rng));
  st.SetLabel(names[st.range(0)]);
}
BENCHMARK(Decision)
    ->Args({0, 100, 1000})
    ->Args({1, 100, 1000})
    ->Args({2, 100, 1000})
    ->Args({0, 10, 50})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace swath::fleet
BENCHMARK_MAIN();

// The fleet schedulers (docs/swath-fleet.md): one decision for 100 drones and 1,000 requests
// (target: simulated annealing p50 ≤ 20 ms, p99 ≤ 50 ms), beside the exact Hungarian and greedy;
// one GMF forecast over 20 histories of 2,000 nodes (target ≤ 10 ms) beside constant velocity.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "swath/fleet/apps.hpp"
#include "swath/fleet/forecaster.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/fleet/scheduler.hpp"
#include "swath/worlds/worlds.hpp"

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

// SA decisions on 50 different 100 × 1,000 snapshots: the distribution docs/swath-fleet.md bounds
// (p50 ≤ 20 ms, p99 ≤ 50 ms), as counters.
void DecisionPercentiles(benchmark::State& st) {
  std::vector<Snapshot> snapshots;
  for (int i = 0; i < 50; ++i) {
    Snapshot s = instance(100, 1000);
    auto rng = vehicle::SplitMix64::stream(static_cast<std::uint64_t>(i), "shuffle");
    for (auto& r : s.requests) r.waiting_s = rng.uniform(0, 60);
    for (auto& d : s.drones) d.position_m.x += rng.uniform(-100, 100);
    snapshots.push_back(std::move(s));
  }
  auto scheduler = make_scheduler("sa");
  std::vector<double> ms;
  for (auto _ : st) {
    ms.clear();
    for (const Snapshot& s : snapshots) {
      auto rng = vehicle::SplitMix64::stream(1, "sa");
      const auto t0 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(scheduler->assign(s, rng));
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  std::sort(ms.begin(), ms.end());
  st.counters["p50_ms"] = ms[ms.size() / 2];
  st.counters["p99_ms"] = ms[ms.size() * 99 / 100];
}
BENCHMARK(DecisionPercentiles)->Iterations(1)->Unit(benchmark::kMillisecond);

// One whole simulated case study (docs/swath-fleet.md: ≤ 1 s), each bundled world with its app,
// two drones `spacing_m` apart at home. Counters: the events logged and the scheduling rounds
// (each round is one 20,000-move annealing search, most of a case study's time).
void case_study(benchmark::State& st, double spacing_m) {
  static const char* apps[] = {"road", "wifi", "hotspot", "multiplexing", "tracking"};
  const std::string app_name = apps[st.range(0)];
  App app;
  for (App& a : fleet::builtin_apps())
    if (a.name == app_name) app = a;
  std::filesystem::path path = SWATH_SOURCE_DIR;
  path /= "share/worlds";
  path /= fleet::app_world_kind(app_name);
  path += ".yaml";
  const auto world = worlds::read_world(path.string());
  std::vector<DroneSpec> drones(2);
  for (std::size_t i = 0; i < drones.size(); ++i) {
    drones[i].drone.name = std::string(1, static_cast<char>('a' + i));
    drones[i].home_m = {spacing_m * static_cast<double>(i), 0, 0};
  }
  if (app_name == "tracking")
    for (auto& d : drones) d.max_flight_time_s = 60;
  RuntimeSettings settings;
  settings.app_name = app_name;
  std::size_t events = 0;
  int rounds = 0;
  for (auto _ : st) {
    const RunRecord r = run_app(app, *world, drones, settings);
    events =
        static_cast<std::size_t>(std::count(r.events_jsonl.begin(), r.events_jsonl.end(), '\n'));
    rounds = r.schedules;
    benchmark::DoNotOptimize(r.completion_time_s);
  }
  st.SetLabel(app_name);
  st.counters["events"] = static_cast<double>(events);
  st.counters["rounds"] = rounds;
}

// Homes 3 m apart, nearer than the envelope's 5 m separation: one drone climbs at a time and the
// other is offered again at every tick (a scheduling round each) until the climb is clear.
void CaseStudy(benchmark::State& st) {
  case_study(st, 3.0);
}
BENCHMARK(CaseStudy)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
// Homes separation_m + 1 apart, as `swath-fleet run --drones N` places them: no take-off queue.
void CaseStudyApart(benchmark::State& st) {
  case_study(st, LocalEnvelope{}.separation_m + 1);
}
BENCHMARK(CaseStudyApart)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

// The cost of one tick with nothing to schedule (docs/swath-fleet.md: idle tick ≤ 20 µs): an app
// whose main waits 0.1 s of computation 10,000 times beside ten idle drones, so every tick has
// one event and no request; time per tick = run time / 10,000.
void IdleTick(benchmark::State& st) {
  class Empty final : public World {
   public:
    std::string kind() const override { return "empty"; }
    Vec3 start() const override { return {}; }
    double sense_time_s(const std::string&) const override { return 1; }
    Reading sense(const std::string&, const Vec3&, double) const override { return {}; }
  } world;
  App app{"idle", "", [](Ctx& c) -> Co<void> {
            for (int i = 0; i < 10'000; ++i) co_await c.compute([] { return 0; }, 0.1);
          }};
  std::vector<DroneSpec> drones(10);
  for (std::size_t i = 0; i < drones.size(); ++i)
    drones[i].drone.name = std::string(1, static_cast<char>('a' + i));
  RuntimeSettings settings;
  settings.state_period_s = 1e9;  // no drone_state lines: the tick alone
  settings.max_time_s = 1e5;
  for (auto _ : st)
    benchmark::DoNotOptimize(run_app(app, world, drones, settings).completion_time_s);
  st.counters["ticks_per_s"] =
      benchmark::Counter(1e4, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(IdleTick)->Unit(benchmark::kMillisecond);

// A hotspot-shaped history of `iterations` squares (4 corners + 1 sync node each: 5 nodes per
// iteration), the squares walking diagonally at random.
Dtg square_walk(std::uint64_t seed, int iterations) {
  auto rng = vehicle::SplitMix64::stream(seed, "squares");
  Dtg g;
  DtgNode main;
  main.kind = "main";
  g.nodes.push_back(main);
  double x = 0, y = 0;
  std::vector<int> corners;
  for (int i = 0; i < iterations; ++i) {
    for (int c = 0; c < 4; ++c) {
      DtgNode t;
      t.number = static_cast<int>(g.nodes.size());
      t.kind = "corner";
      t.created_s = 20.0 * i;
      t.ended_s = t.created_s + 15;
      t.status = DtgStatus::done;
      t.first_loc_m = Vec3{x + (c == 1 || c == 2 ? 5 : -5), y + (c >= 2 ? 5 : -5), 0};
      corners.push_back(static_cast<int>(g.nodes.size()));
      g.nodes.push_back(t);
    }
    x += rng.uniform() < 0.5 ? 3.5 : -3.5;
    y += rng.uniform() < 0.5 ? 3.5 : -3.5;
  }
  for (int i = 0; i < iterations; ++i) {
    DtgNode s;
    s.type = DtgNodeType::sync;
    s.number = i;
    s.kind = "main";
    s.waiter = 0;
    s.created_s = 20.0 * i;
    const int id = static_cast<int>(g.nodes.size());
    g.nodes.push_back(s);
    for (int c = 0; c < 4; ++c) {
      const int corner = corners[static_cast<std::size_t>(4 * i + c)];
      g.edges.push_back({corner, id, DtgEdgeType::sync});
      g.edges.push_back({i == 0 ? 0 : id - 1, corner, DtgEdgeType::spawn});
    }
  }
  return g;
}

// One forecast of a run half-way (1,000 nodes, 4 running corners) against 20 histories of 2,000
// nodes each (400 iterations).
void Forecast(benchmark::State& st) {
  std::vector<Dtg> histories;
  for (std::uint64_t h = 0; h < 20; ++h) histories.push_back(square_walk(100 + h, 400));
  const Dtg full = square_walk(7, 400);
  const double now_s = 20.0 * 199;
  const Dtg current = full.as_of(now_s);
  auto f = st.range(0) == 0 ? gmf_forecaster(histories) : constant_velocity_forecaster();
  std::size_t n = 0;
  for (auto _ : st) n = f->forecast(current, now_s).size();
  st.counters["forecasts"] = static_cast<double>(n);
  st.counters["history_nodes"] = static_cast<double>(histories.front().nodes.size());
  st.SetLabel(f->name());
}
BENCHMARK(Forecast)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace swath::fleet
BENCHMARK_MAIN();

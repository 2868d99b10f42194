// Dividing a survey among 1..64 equal drones on field-like areas of 10..10,000 vertices:
//   path division (cut the sweep path by length), region division (exact bisection on the area
//   below a cut), and the paper's coarse region search (even heights, then 1/1000-height steps
//   until each band is within 1 % of its area; eq. 7-8) beside it.
//
//   swath_division_bench --balance-table
// instead prints the balance table of issue 18 (docs/swath-plan.md): meadow, vineyard and orchard
// with three equal drones and with three-quads, path and region division, --balance makespan: each
// drone's flight time and the longest over the shortest (as summary.json reports them), and the
// plan's wall time. BM_BalancedPlan times the same plans.
//   swath_division_bench --balance-corpus
// prints the same for region division on split-corpus shapes (tests/support/field_shapes.hpp).
//   swath_division_bench --balance-distribution SEED PER_FAMILY [FAMILY or SHAPE [FLEET]]
// the distribution of max / min over many such shapes with 2, 3, 4 equal drones and three-quads
// (FLEET: only that one, "4 equal", e.g. to profile one plan);
//   swath_division_bench --path-distribution SEED PER_FAMILY [FAMILY or SHAPE [FLEET]]
// the same with path division (the issue's <= 1.005 for path division). With SWATH_BENCH_EXACT
// set, these print each plan's flight times as exact doubles and a hash of its regions and paths.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <string>

#include "division_cases.hpp"
#include "random_polygons.hpp"
#include "region_division.hpp"
#include "swath/base/freed_memory.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/planning/division.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/sweep.hpp"
#include "swath/vehicle/drone.hpp"

namespace {

using namespace swath;

std::vector<geometry::Ring> field(std::size_t n) {
  test::Rng rng(n);
  return {test::random_field_polygon(rng, n, 500)};
}

std::vector<planning::DroneResource> drones(std::size_t n) {
  std::vector<planning::DroneResource> d;
  for (std::size_t i = 0; i < n; ++i) {
    std::string name = "d";  // not "d" + ...: GCC 12 warns -Wrestrict on that
    name += std::to_string(i);
    d.push_back({name, {-700, -700}, 5, std::nullopt, 1});
  }
  return d;
}

constexpr double kAngle = 30;

void BM_PathDivision(benchmark::State& state) {
  const auto rings = field(std::size_t(state.range(0)));
  planning::SweepSettings s;
  s.angle_deg = kAngle;
  s.line_spacing_m = 20;
  s.footprint_width_m = 40;
  const planning::Sweep sweep = planning::plan_sweep(geometry::Polygon{rings[0], {}}, s);
  const planning::SurveyPath path =
      planning::survey_path(planning::zigzag(sweep, false, false), std::nullopt);
  const auto fleet = drones(std::size_t(state.range(1)));
  for (auto _ : state)
    benchmark::DoNotOptimize(planning::divide_path(path, fleet, planning::Balance::capability));
}

void BM_RegionDivisionExact(benchmark::State& state) {
  const auto rings = field(std::size_t(state.range(0)));
  const auto fleet = drones(std::size_t(state.range(1)));
  const planning::BandSweep none = [](const std::vector<geometry::Ring>&,
                                      const planning::DroneResource&) {
    return planning::SurveyPath{};
  };
  for (auto _ : state)
    benchmark::DoNotOptimize(planning::divide_region(rings, kAngle, fleet, none));
}

void BM_RegionCutsPaper(benchmark::State& state) {
  const auto rings = field(std::size_t(state.range(0)));
  const std::vector<double> fractions(std::size_t(state.range(1)), 1.0 / double(state.range(1)));
  std::size_t evaluations = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(
        reference::paper_region_cuts(rings, kAngle, fractions, 0.01, evaluations));
  state.counters["area_evaluations"] =
      benchmark::Counter(double(evaluations), benchmark::Counter::kAvgIterations);
}

std::vector<test::DivisionCase> balance_cases() {
  std::vector<test::DivisionCase> all;
  for (const auto mode : {planning::DivisionMode::path, planning::DivisionMode::region})
    for (test::DivisionCase& c :
         test::division_cases(SWATH_SOURCE_DIR, mode, planning::Balance::makespan))
      all.push_back(std::move(c));
  return all;
}

void BM_BalancedPlan(benchmark::State& state) {
  const test::DivisionCase c = balance_cases()[std::size_t(state.range(0))];
  state.SetLabel(c.field + " " + c.fleet + " " +
                 (c.request.division == planning::DivisionMode::path ? "path" : "region"));
  for (auto _ : state) benchmark::DoNotOptimize(planning::plan_survey(c.request));
}

// The vineyard's region division by makespan with six drones at six homes: three-quads and a
// copy of each 55 m further north (and 53 m east) per copy. Above four drones the division
// balances the homes' order, the fleet's and pairwise swaps of the best rather than all 720
// orders (which took tens of seconds on such split areas).
test::DivisionCase six_drone_case() {
  test::DivisionCase c = balance_cases()[9];  // vineyard, three-quads, region
  vehicle::Fleet& fleet = *c.request.fleet;
  const std::size_t n = fleet.drones.size();
  for (std::size_t i = 0; i < n; ++i) {
    vehicle::Drone d = fleet.drones[i];
    d.name += "-2";
    const geometry::GeoPoint from = d.home.value_or(fleet.home);
    const double k = double(i + 1);
    d.home = geometry::GeoPoint{from.lat_deg + 0.0005 * k, from.lon_deg + 0.0007 * k, 0};
    fleet.drones.push_back(std::move(d));
  }
  c.fleet = "six at six homes";
  return c;
}

void BM_SixDronePlan(benchmark::State& state) {
  const test::DivisionCase c = six_drone_case();
  state.SetLabel(c.field + " " + c.fleet + " region");
  double ratio = 0;
  for (auto _ : state) {
    const planning::SurveyPlan plan = planning::plan_survey(c.request);
    ratio = test::max_over_min_flight(plan);
    benchmark::DoNotOptimize(ratio);
  }
  state.counters["max_over_min"] = ratio;
}

// With SWATH_BENCH_EXACT set, each plan's flight times as the doubles they are (%a) and a hash of
// its regions' and paths' coordinates' bits: a change meant to keep the plans can be checked bit
// for bit, where the tables round.
void print_exact(const planning::SurveyPlan& plan) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a over the doubles' bits
  auto mix = [&h](double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 8; ++i) h = (h ^ ((bits >> (8 * i)) & 0xff)) * 0x100000001b3ull;
  };
  std::printf("  exact:");
  for (const planning::DronePlan& d : plan.drones) {
    std::printf(" %a", d.mission.flight_time_s);
    for (const geometry::Ring& ring : d.work.region) {
      mix(double(ring.size()));
      for (const geometry::Point2& p : ring) {
        mix(p.x);
        mix(p.y);
      }
    }
    mix(double(d.work.path.points.size()));
    for (const geometry::Point2& p : d.work.path.points) {
      mix(p.x);
      mix(p.y);
    }
  }
  std::printf(" makespan %a hash %016llx\n", plan.division.makespan_s,
              static_cast<unsigned long long>(h));
}

// One plan, its wall time and its drones' flight times as text ("526, 515, 515").
struct TimedPlan {
  planning::SurveyPlan plan;
  double ms;
  std::string times;
};

TimedPlan timed_plan(const planning::SurveyRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  TimedPlan t{planning::plan_survey(request), 0, ""};
  t.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (const planning::DronePlan& d : t.plan.drones)
    t.times += (t.times.empty() ? "" : ", ") + std::to_string(std::lround(d.mission.flight_time_s));
  if (std::getenv("SWATH_BENCH_EXACT")) print_exact(t.plan);
  return t;
}

int balance_table() {
  std::printf("| field | drones | division | flight times, s | max / min | plan |\n");
  std::printf("|---|---|---|---|---:|---:|\n");
  for (const test::DivisionCase& c : balance_cases()) {
    const TimedPlan t = timed_plan(c.request);
    const planning::SurveyPlan& plan = t.plan;
    const double ms = t.ms;
    const std::string& times = t.times;
    std::printf("| %s | %s | %s | %s | %.4f | %.0f ms |\n", c.field.c_str(), c.fleet.c_str(),
                c.request.division == planning::DivisionMode::path ? "path" : "region",
                times.c_str(), test::max_over_min_flight(plan), ms);
  }
  return 0;
}

// The same on split-corpus shapes (seed 18, two of each family), region division by makespan:
// one row per shape and fleet, then the mean and the worst max / min per fleet.
int balance_corpus() {
  std::printf("| shape | drones | flight times, s | max / min | plan |\n");
  std::printf("|---|---|---|---:|---:|\n");
  std::map<std::string, std::pair<double, double>> sum_worst;
  std::map<std::string, int> count;
  for (const test::DivisionCase& c : test::corpus_division_cases(
           SWATH_SOURCE_DIR, 18, 2, planning::DivisionMode::region, planning::Balance::makespan)) {
    const TimedPlan t = timed_plan(c.request);
    const planning::SurveyPlan& plan = t.plan;
    const double ms = t.ms;
    const std::string& times = t.times;
    const double ratio = test::max_over_min_flight(plan);
    std::printf("| %s | %s | %s | %.4f | %.0f ms |\n", c.field.c_str(), c.fleet.c_str(),
                times.c_str(), ratio, ms);
    auto& [sum, worst] = sum_worst[c.fleet];
    sum += ratio;
    worst = std::max(worst, ratio);
    ++count[c.fleet];
  }
  for (const auto& [fleet, sw] : sum_worst)
    std::printf("%s: mean %.4f, worst %.4f over %d shapes\n", fleet.c_str(),
                sw.first / count[fleet], sw.second, count[fleet]);
  return 0;
}

// Issue 18's distribution: region (or path) division by makespan on `per_family` split-corpus
// shapes of each family from `seed` (`family`: one family or one shape, "comb 0", only; "" all),
// with 2, 3 and 4 equal drones and three-quads (`only_fleet`: that one only; "" all). One row per
// plan (max / min, makespan, the regions' areas over the area), then per fleet the mean, p90 and
// worst max / min and how many exceed 1.02.
int balance_distribution(std::uint64_t seed, int per_family, const std::string& family,
                         const std::string& only_fleet, planning::DivisionMode division) {
  std::map<std::string, std::vector<double>> ratios;
  double worst_tiling = 0;
  for (const test::DivisionCase& base : test::corpus_division_cases(
           SWATH_SOURCE_DIR, seed, per_family, division, planning::Balance::makespan)) {
    if (!family.empty() && base.field != family && !base.field.starts_with(family + " ")) continue;
    std::vector<std::pair<std::string, planning::SurveyRequest>> requests;
    if (base.fleet == "3 equal") {
      for (const int n : {2, 3, 4}) {
        planning::SurveyRequest r = base.request;
        r.fleet = vehicle::equal_fleet(n, {});
        r.fleet->home = geometry::GeoPoint{std::numeric_limits<double>::quiet_NaN(), 0, 0};
        requests.push_back({std::to_string(n) + " equal", std::move(r)});
      }
    } else {
      requests.push_back({base.fleet, base.request});
    }
    for (const auto& [fleet, request] : requests) {
      if (!only_fleet.empty() && fleet != only_fleet) continue;
      const TimedPlan t = timed_plan(request);
      const double ratio = test::max_over_min_flight(t.plan);
      double area = 0, regions = 0;
      for (const geometry::Ring& ring : geometry::rings_of(t.plan.area))
        area += geometry::signed_area(ring);
      for (const planning::DronePlan& d : t.plan.drones)
        for (const geometry::Ring& piece : d.work.region) regions += geometry::signed_area(piece);
      worst_tiling = std::max(worst_tiling, std::abs(regions / area - 1));
      std::printf("| %s | %s | %s | %.4f | %.1f | %.6f | %.0f ms |\n", base.field.c_str(),
                  fleet.c_str(), t.times.c_str(), ratio, t.plan.division.makespan_s, regions / area,
                  t.ms);
      std::fflush(stdout);
      ratios[fleet].push_back(ratio);
    }
  }
  for (auto& [fleet, r] : ratios) {
    std::sort(r.begin(), r.end());
    const double mean = std::accumulate(r.begin(), r.end(), 0.0) / double(r.size());
    const double p90 =
        r[std::min(r.size() - 1, std::size_t(std::ceil(0.9 * double(r.size())) - 1))];
    const auto over = std::count_if(r.begin(), r.end(), [](double v) { return v > 1.02; });
    std::printf("%s: %zu plans, mean %.4f, p90 %.4f, worst %.4f, %td over 1.02\n", fleet.c_str(),
                r.size(), mean, p90, r.back(), over);
  }
  if (division == planning::DivisionMode::region)
    std::printf("regions' areas over the area: worst |sum / area - 1| %.2e\n", worst_tiling);
  return 0;
}

void Cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"vertices", "drones"})->Unit(benchmark::kMillisecond);
  for (int n : {10, 1000, 10000})
    for (int d : {1, 4, 16, 64}) b->Args({n, d});
}

}  // namespace

BENCHMARK(BM_PathDivision)->Apply(Cases);
BENCHMARK(BM_RegionDivisionExact)->Apply(Cases);
BENCHMARK(BM_RegionCutsPaper)->Apply(Cases);

BENCHMARK(BM_BalancedPlan)->DenseRange(0, 11)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SixDronePlan)->Unit(benchmark::kMillisecond)->Iterations(1);

int main(int argc, char** argv) {
  swath::base::keep_freed_memory();  // as the swath programs run
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--balance-table") == 0)
      return balance_table();
    else if (std::strcmp(argv[i], "--balance-corpus") == 0)
      return balance_corpus();
    else if ((std::strcmp(argv[i], "--balance-distribution") == 0 ||
              std::strcmp(argv[i], "--path-distribution") == 0) &&
             i + 2 < argc)
      return balance_distribution(
          std::stoull(argv[i + 1]), std::stoi(argv[i + 2]), i + 3 < argc ? argv[i + 3] : "",
          i + 4 < argc ? argv[i + 4] : "",
          argv[i][2] == 'p' ? planning::DivisionMode::path : planning::DivisionMode::region);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

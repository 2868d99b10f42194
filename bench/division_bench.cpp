// Dividing a survey among 1..64 equal drones on field-like areas of 10..10,000 vertices:
//   path division (cut the sweep path by length), region division (exact bisection on the area
//   below a cut), and the paper's coarse region search (even heights, then 1/1000-height steps
//   until each band is within 1 % of its area; eq. 7-8) beside it.
#include <benchmark/benchmark.h>

#include <numeric>

#include "random_polygons.hpp"
#include "region_division.hpp"
#include "swath/planning/division.hpp"
#include "swath/planning/sweep.hpp"

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
                                      const planning::DroneResource&,
                                      bool) { return planning::SurveyPath{}; };
  for (auto _ : state)
    benchmark::DoNotOptimize(
        planning::divide_region(rings, kAngle, fleet, planning::Balance::capability, none));
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

void Cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"vertices", "drones"})->Unit(benchmark::kMillisecond);
  for (int n : {10, 1000, 10000})
    for (int d : {1, 4, 16, 64}) b->Args({n, d});
}

}  // namespace

BENCHMARK(BM_PathDivision)->Apply(Cases);
BENCHMARK(BM_RegionDivisionExact)->Apply(Cases);
BENCHMARK(BM_RegionCutsPaper)->Apply(Cases);

BENCHMARK_MAIN();

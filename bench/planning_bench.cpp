// The whole planning pipeline, swath's against the paper's, on field-like areas of 10 to 100,000
// vertices (GeoJSON text in memory; the files are produced as text, not written to disk), both
// flying the convex hull of these slightly concave areas (split: split_bench.cpp):
//   swath: read -> O(n log n) classify -> exact min height -> centered sweep -> mission -> files
//   paper: read -> O(n²) TypeDetection -> 0.1° scan -> Algorithm 2 placement -> mission -> files
#include <benchmark/benchmark.h>

#include <cstdio>
#include <numbers>

#include "random_polygons.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/survey_files.hpp"
#include "type_detection.hpp"

namespace {

using namespace swath;

// A ~1 km field near 47°N as GeoJSON text.
std::string field_geojson(std::size_t n) {
  test::Rng rng(n);
  const geometry::Ring ring = test::random_field_polygon(rng, n, 500);
  std::string s = R"({"type":"Polygon","coordinates":[[)";
  char buffer[64];
  for (const geometry::Point2& p : ring) {
    std::snprintf(buffer, sizeof buffer, "[%.9f,%.9f],",
                  8.54 + p.x / (111320 * std::cos(47.4 * std::numbers::pi / 180)),
                  47.4 + p.y / 111320);
    s += buffer;
  }
  s.pop_back();
  return s + "]]}";
}

planning::SurveyRequest request(bool paper) {
  planning::SurveyRequest r;
  r.camera = {"Sony ILCE-QX1", 23.2, 15.4, 16, 5456, 3632, std::nullopt};
  planning::PhotogrammetryMode m;
  m.altitude_m = 100;
  r.mode = m;
  r.angle_search = paper ? planning::AngleSearch::scan : planning::AngleSearch::exact;
  r.placement = paper ? planning::LinePlacement::paper : planning::LinePlacement::centered;
  // Like for like with the paper: both fly the convex hull (split has its own bench).
  r.concave = planning::ConcaveMode::hull;
  return r;
}

void BM_SwathPipeline(benchmark::State& state) {
  const std::string text = field_geojson(std::size_t(state.range(0)));
  planning::SurveyRequest r = request(false);
  for (auto _ : state) {
    r.field = geometry::parse_field(text, geometry::FieldFormat::geojson, "bench");
    const planning::SurveyPlan plan = planning::plan_survey(r);
    benchmark::DoNotOptimize(planning::survey_files(plan));
  }
}

void BM_PaperPipeline(benchmark::State& state) {
  const std::string text = field_geojson(std::size_t(state.range(0)));
  planning::SurveyRequest r = request(true);
  for (auto _ : state) {
    r.field = geometry::parse_field(text, geometry::FieldFormat::geojson, "bench");
    benchmark::DoNotOptimize(reference::type_detection_quadratic(r.field.polygon));
    const planning::SurveyPlan plan = planning::plan_survey(r);
    benchmark::DoNotOptimize(planning::survey_files(plan));
  }
}

// The parts of the swath pipeline, to see where the time goes.
void BM_StageRead(benchmark::State& state) {
  const std::string text = field_geojson(std::size_t(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(geometry::parse_field(text, geometry::FieldFormat::geojson, "bench"));
}

// docs/performance.md target set: classify + exact min height + sweep (+ mission) on a field
// already read.
void BM_StageGeometry(benchmark::State& state) {
  const geometry::Field field = geometry::parse_field(field_geojson(std::size_t(state.range(0))),
                                                      geometry::FieldFormat::geojson, "bench");
  for (auto _ : state) {
    const geometry::Classification c = geometry::classify(field.polygon);
    const geometry::SweepDirection d = geometry::min_height_rotation(field.polygon.outer);
    planning::SweepSettings s;
    s.angle_deg = d.angle_deg;
    s.line_spacing_m = 43.5;
    s.footprint_width_m = 145;
    const planning::Sweep sweep = planning::plan_sweep(field.polygon, s);
    benchmark::DoNotOptimize(c);
    benchmark::DoNotOptimize(planning::order_lines(sweep, planning::StartCorner::sw));
  }
}

void BM_StageFiles(benchmark::State& state) {
  planning::SurveyRequest r = request(false);
  r.field = geometry::parse_field(field_geojson(std::size_t(state.range(0))),
                                  geometry::FieldFormat::geojson, "bench");
  const planning::SurveyPlan plan = planning::plan_survey(r);
  for (auto _ : state) benchmark::DoNotOptimize(planning::survey_files(plan));
}

void BM_StageCoverage(benchmark::State& state) {
  planning::SurveyRequest r = request(false);
  r.field = geometry::parse_field(field_geojson(std::size_t(state.range(0))),
                                  geometry::FieldFormat::geojson, "bench");
  const planning::SurveyPlan plan = planning::plan_survey(r);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        planning::measure_coverage(plan.request.field.polygon, plan.drones[0].mission.lines,
                                   plan.sweep.angle_deg, plan.imaging.footprint_across_m));
}

}  // namespace

BENCHMARK(BM_SwathPipeline)
    ->ArgName("vertices")
    ->RangeMultiplier(10)
    ->Range(10, 100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PaperPipeline)
    ->ArgName("vertices")
    ->RangeMultiplier(10)
    ->Range(10, 10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StageRead)
    ->ArgName("vertices")
    ->RangeMultiplier(10)
    ->Range(10, 100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StageGeometry)
    ->ArgName("vertices")
    ->RangeMultiplier(10)
    ->Range(10, 100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StageFiles)
    ->ArgName("vertices")
    ->RangeMultiplier(10)
    ->Range(10, 100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StageCoverage)
    ->ArgName("vertices")
    ->RangeMultiplier(10)
    ->Range(10, 100000)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

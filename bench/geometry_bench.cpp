// Geometry stages against the paper's methods (paper 001 §V-A/B):
//   exact minimum height (rotating calipers)  vs  0.1° angle scan
//   O(n log n) sweep classification           vs  O(n²) TypeDetection (drop-one-vertex)
// on fixed-seed polygons of 10 to 10,000 vertices: field-like boundaries (argument 0) and jagged
// star polygons (argument 1, many edges on one sweep line: the sweep's hard case).
#include <benchmark/benchmark.h>

#include "random_polygons.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/geometry/min_height.hpp"
#include "type_detection.hpp"

namespace {

using namespace swath;

geometry::Polygon field(const benchmark::State& state) {
  const auto n = std::size_t(state.range(0));
  test::Rng rng(n);
  if (state.range(1) == 0) return {test::random_field_polygon(rng, n, 500), {}};
  return {test::random_star_polygon(rng, n, 400, 500), {}};
}

void BM_MinHeightExact(benchmark::State& state) {
  const geometry::Polygon p = field(state);
  for (auto _ : state) benchmark::DoNotOptimize(geometry::min_height_rotation(p.outer));
}

// The same for a simple polygon's ring: Melkman's hull, no sort (what swath plan uses).
void BM_MinHeightSimpleRing(benchmark::State& state) {
  const geometry::Polygon p = field(state);
  for (auto _ : state) benchmark::DoNotOptimize(geometry::min_height_of_simple_ring(p.outer));
}

void BM_MinHeightScan0p1(benchmark::State& state) {
  const geometry::Polygon p = field(state);
  for (auto _ : state) benchmark::DoNotOptimize(geometry::min_height_scan(p.outer, 0.1));
}

void BM_ClassifySweep(benchmark::State& state) {
  const geometry::Polygon p = field(state);
  for (auto _ : state) benchmark::DoNotOptimize(geometry::classify(p));
}

void BM_ClassifyPaperQuadratic(benchmark::State& state) {
  const geometry::Polygon p = field(state);
  for (auto _ : state) benchmark::DoNotOptimize(reference::type_detection_quadratic(p));
}

}  // namespace

void Sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"vertices", "jagged"})->Unit(benchmark::kMicrosecond);
  for (int jagged : {0, 1})
    for (int n : {10, 100, 1000, 10000}) b->Args({n, jagged});
}

BENCHMARK(BM_MinHeightExact)->Apply(Sizes);
BENCHMARK(BM_MinHeightSimpleRing)->Apply(Sizes);
BENCHMARK(BM_MinHeightScan0p1)->Apply(Sizes);
BENCHMARK(BM_ClassifySweep)->Apply(Sizes);
BENCHMARK(BM_ClassifyPaperQuadratic)->Apply(Sizes);

BENCHMARK_MAIN();

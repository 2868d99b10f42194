// --concave split on field-like areas of 10 to 10,000 vertices with 0 to 50 rectangular no-fly
// holes: the decomposition alone, and the whole split plan (direction search over ~100
// directions, runs from the lanes and cells, their order, transits routed inside the area),
// beside the first method alone (cells only). The allocator keeps freed memory as the swath
// programs' does (base::keep_freed_memory()); --default_allocator times glibc's defaults.
#include <benchmark/benchmark.h>

#include <cstring>

#include "random_polygons.hpp"
#include "swath/base/freed_memory.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/planning/split.hpp"

namespace {

using namespace swath;

std::vector<geometry::Ring> area(const benchmark::State& state) {
  const auto n = std::size_t(state.range(0));
  const auto holes = int(state.range(1));
  test::Rng rng(n);
  std::vector<geometry::Ring> rings{test::random_field_polygon(rng, n, 500)};
  for (int h = 0; h < holes; ++h) {  // 25 x 20 m holes on an 8 x 8 grid inside the field
    const double x = -300 + 75.0 * (h % 8), y = -300 + 75.0 * (h / 8);
    rings.push_back({{x, y}, {x, y + 20}, {x + 25, y + 20}, {x + 25, y}});
  }
  return rings;
}

void BM_Decomposition(benchmark::State& state) {
  const auto rings = area(state);
  std::size_t cells = 0;
  for (auto _ : state) cells = geometry::boustrophedon_decomposition(rings, 30.0).cell_rings.size();
  state.counters["cells"] = double(cells);
}

void split_plan(benchmark::State& state, planning::SplitCells method) {
  const auto rings = area(state);
  planning::SplitSettings s;
  s.line_spacing_m = 43.5;  // QX1 at 100 m, 70 % side overlap
  s.footprint_width_m = 145;
  s.cells = method;
  std::size_t cells = 0;
  double path_m = 0;
  for (auto _ : state) {
    const geometry::VisibilityRouter router(rings);
    const planning::SplitPlan plan = planning::plan_split(rings, {-600, -600}, s, router);
    cells = plan.cells.size();
    path_m = plan.path_length_m;
  }
  state.counters["cells"] = double(cells);
  state.counters["path_m"] = path_m;
}
// The default: runs from the lanes and boustrophedon cells, per direction the shorter.
void BM_SplitPlan(benchmark::State& state) {
  split_plan(state, planning::SplitCells::best);
}
// The first method alone (the baseline of issue 18): boustrophedon cells only.
void BM_SplitPlanCells(benchmark::State& state) {
  split_plan(state, planning::SplitCells::boustrophedon);
}

void Areas(benchmark::internal::Benchmark* b) {
  b->ArgNames({"vertices", "holes"})->Unit(benchmark::kMillisecond);
  for (int n : {10, 100, 1000, 10000})
    for (int holes : {0, 5, 10, 50}) b->Args({n, holes});
}

}  // namespace

BENCHMARK(BM_Decomposition)->Apply(Areas);
BENCHMARK(BM_SplitPlan)->Apply(Areas)->Iterations(1);
BENCHMARK(BM_SplitPlanCells)->Apply(Areas)->Iterations(1);

int main(int argc, char** argv) {
  bool default_allocator = false;
  int kept = 1;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--default_allocator") == 0)
      default_allocator = true;
    else
      argv[kept++] = argv[i];
  argc = kept;
  if (!default_allocator) swath::base::keep_freed_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

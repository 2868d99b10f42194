// Process-level benchmark (issue 17): whole program runs as a user starts them, each timed from
// spawn to exit. `swath --version` is the floor (process start alone); the meadow plan without
// --render must stay near it because the drawing stack is only loaded to draw. A long outline
// (10,000 vertices, a field drawn from a detailed survey) times the whole plan of a large input.
// Usage: swath_startup_bench [benchmark flags]; SWATH_BENCH_BINARY=/other/swath for a baseline.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "random_polygons.hpp"

extern char** environ;

namespace {

void run(benchmark::State& state, std::vector<std::string> args) {
  const std::string out = (std::filesystem::temp_directory_path() / "swath-startup-bench").string();
  for (std::string& a : args)
    if (a == "OUT") a = out;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t io;
  posix_spawn_file_actions_init(&io);
  posix_spawn_file_actions_addopen(&io, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&io, 2, "/dev/null", O_WRONLY, 0);
  for (auto _ : state) {
    pid_t pid = 0;
    if (posix_spawn(&pid, argv[0], &io, nullptr, argv.data(), environ) != 0) {
      state.SkipWithError("cannot start the program");
      break;
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      state.SkipWithError("the program failed");
      break;
    }
  }
  posix_spawn_file_actions_destroy(&io);
}

// $SWATH_BENCH_BINARY runs another build (e.g. a baseline) through the same benchmarks.
const std::string kSwath =
    std::getenv("SWATH_BENCH_BINARY") ? std::getenv("SWATH_BENCH_BINARY") : SWATH_BINARY;
const std::string kMeadow = std::string(SWATH_SOURCE_DIR) + "/share/fields/meadow.geojson";

// test::random_field_polygon (10,000 vertices, 500 m across, fixed seed) placed near Zurich, as
// GeoJSON in a temporary file.
std::string long_outline() {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("swath-bench-long-outline-" + std::to_string(getpid()) + ".geojson"))
                               .string();
  swath::test::Rng rng(10000);
  const swath::geometry::Ring ring = swath::test::random_field_polygon(rng, 10000, 500);
  const double lat0 = 47.39, lon0 = 8.54, m_per_deg = 111319.49;
  std::ofstream out(path);
  out << R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[)";
  char text[64];
  for (std::size_t i = 0; i <= ring.size(); ++i) {
    const auto& p = ring[i % ring.size()];
    std::snprintf(text, sizeof text, "%s[%.9f,%.9f]", i ? "," : "",
                  lon0 + p.x / (m_per_deg * std::cos(lat0 * 3.141592653589793 / 180)),
                  lat0 + p.y / m_per_deg);
    out << text;
  }
  out << "]]}}\n";
  return path;
}

void BM_SwathVersion(benchmark::State& s) {
  run(s, {kSwath, "--version"});
}
void BM_PlanMeadow(benchmark::State& s) {
  run(s, {kSwath, "plan", kMeadow, "--camera", "sony-ilce-qx1", "--altitude", "60", "-o", "OUT"});
}
void BM_PlanMeadowRender(benchmark::State& s) {
  run(s, {kSwath, "plan", kMeadow, "--camera", "sony-ilce-qx1", "--altitude", "60", "--render",
          "-o", "OUT"});
}

void BM_PlanLongOutline(benchmark::State& s) {
  static const std::string field = long_outline();
  run(s, {kSwath, "plan", field, "--camera", "sony-ilce-qx1", "--altitude", "100", "-o", "OUT"});
}

BENCHMARK(BM_SwathVersion)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlanMeadow)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlanMeadowRender)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);
BENCHMARK(BM_PlanLongOutline)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();

// Process-level benchmark (issue 17): whole program runs as a user starts them, each timed from
// spawn to exit. `swath --version` is the floor (process start alone); the meadow plan without
// --render must stay near it because the drawing stack is only loaded to draw.
// Usage: swath_startup_bench [benchmark flags]; SWATH_BENCH_BINARY=/other/swath for a baseline.
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

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

BENCHMARK(BM_SwathVersion)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlanMeadow)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PlanMeadowRender)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);

}  // namespace

BENCHMARK_MAIN();

// `swath batch` plans its areas in a few worker processes, each planning area after area
// (apps/swath/batch_workers.hpp). What a user must not see from that: an area's row carrying
// another area's words, an area planned differently after others than alone, an area lost when a
// worker is replaced or dies.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "swath/base/number_text.hpp"

namespace swath::test {
namespace {

namespace fs = std::filesystem;

const char* const kOptions = " --camera sony-ilce-qx1 --altitude 60";

// An axis-aligned rectangle of `w` x `h` degrees at (lon, lat) as a GeoJSON Feature named `name`;
// `crossed`: its second and third corners swapped, a bow tie that `swath plan` refuses.
std::string rectangle(double lon, double lat, double w, double h, const std::string& name,
                      bool crossed = false) {
  std::vector<std::pair<double, double>> ring{
      {lon, lat}, {lon + w, lat}, {lon + w, lat + h}, {lon, lat + h}};
  if (crossed) std::swap(ring[1], ring[2]);
  ring.push_back(ring.front());
  std::string coords;
  for (const auto& [x, y] : ring)
    coords += std::string(coords.empty() ? "" : ", ") + "[" + base::shortest_text(x) + ", " +
              base::shortest_text(y) + "]";
  return R"({"type": "Feature", "properties": {"name": ")" + name +
         R"("}, "geometry": {"type": "Polygon", "coordinates": [[)" + coords + "]]}}";
}

// The plot of 0.5 km² whose plan takes more than a battery (a warning on stderr, still planned:
// exit 0) and writes a photos.geojson of about 300 kB; the small plots write at most 8 kB a file.
std::string large_plot(int i) {
  return rectangle(8.42, 47.3 + 0.01 * i, 0.01, 0.006, "large");
}
std::string small_plot(int i) {
  return rectangle(8.40 + 0.002 * (i % 8), 47.29 - 0.0012 * (i / 8), 0.0015, 0.001,
                   "small " + std::to_string(i));
}

// A star of 12 points, 220 m across, at row `i` (a concave area split into cells: a few tens of
// ms of CPU to plan, several times a small plot's).
std::string star_plot(int i) {
  std::string coords;
  for (int k = 0; k <= 24; ++k) {
    const double a = std::numbers::pi * (k % 24) / 12, r = k % 2 ? 0.0005 : 0.001;
    coords +=
        std::string(k ? ", " : "") + "[" +
        base::shortest_text(8.41 + r * std::cos(a) / std::cos(47.29 * std::numbers::pi / 180)) +
        ", " + base::shortest_text(47.29 - 0.004 * i + r * std::sin(a)) + "]";
  }
  return R"({"type": "Feature", "properties": {"name": "star )" + std::to_string(i) +
         R"("}, "geometry": {"type": "Polygon", "coordinates": [[)" + coords + "]]}}";
}

std::string areas_of(const std::vector<std::string>& features) {
  std::string out = R"({"type": "FeatureCollection", "features": [)";
  for (std::size_t i = 0; i < features.size(); ++i) out += (i ? ",\n" : "\n") + features[i];
  return out + "\n]}\n";
}

// batch.csv's rows without the header, split at commas (the messages hold commas too: they are
// read from the whole line).
std::vector<std::vector<std::string>> batch_rows(const std::string& dir) {
  auto rows = csv_rows(read_text(dir + "/batch.csv"));
  if (!rows.empty()) rows.erase(rows.begin());
  return rows;
}
std::vector<std::string> batch_lines(const std::string& dir) {
  std::vector<std::string> lines;
  std::istringstream text(read_text(dir + "/batch.csv"));
  std::string line;
  std::getline(text, line);  // the header
  while (std::getline(text, line)) lines.push_back(line);
  return lines;
}

// Whether area `index` of `areas` planned alone writes the same summary.json as in `batch_dir`.
bool planned_as_alone(const std::string& areas, std::size_t index, const std::string& batch_dir,
                      const std::string& sub, const std::string& scratch) {
  const std::string alone = scratch + "/alone-" + std::to_string(index);
  const CliRun run = run_swath("plan " + areas + " --feature " + std::to_string(index) + kOptions +
                               " -o " + alone);
  return run.exit_code == 0 &&
         read_text(alone + "/summary.json") == read_text(batch_dir + "/" + sub + "/summary.json");
}

// One worker plans them all (--jobs 1): a refused area after one that warned says its own
// refusal, not the warning the worker's log held from the area before.
TEST(BatchWorkers, EachAreasMessageIsItsOwnInAWorkerThatPlansSeveral) {
  const std::string dir = fresh_dir("batch-workers-log");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::ofstream(areas) << areas_of({large_plot(0),
                                    rectangle(8.41, 47.31, 0.0015, 0.001, "bow", true),
                                    small_plot(0), large_plot(1)});
  const CliRun run = run_swath("batch " + areas + " -o " + dir + "/out --jobs 1" + kOptions);
  ASSERT_EQ(run.exit_code, 3) << run.err;
  const auto rows = batch_rows(dir + "/out");
  const auto lines = batch_lines(dir + "/out");
  ASSERT_EQ(rows.size(), 4u);
  ASSERT_EQ(lines.size(), 4u);
  for (const std::size_t planned : {0u, 2u, 3u}) {
    EXPECT_EQ(rows[planned][4], "planned") << planned;
    EXPECT_EQ(lines[planned].back(), ',') << lines[planned];  // no message: not the warning
  }
  EXPECT_EQ(rows[1][4], "refused");
  EXPECT_NE(lines[1].find(",\"swath plan: "), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("crosses itself"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[1].find("warning"), std::string::npos) << lines[1];
  // The plan after the refusal, by the same worker, is the plan alone.
  EXPECT_TRUE(planned_as_alone(areas, 2, dir + "/out", rows[2][3], dir));
  EXPECT_TRUE(planned_as_alone(areas, 3, dir + "/out", rows[3][3], dir));
}

// More areas than a worker plans before a fresh one takes over (64), on two workers: every area
// is planned, each as alone, around the hand-overs too.
TEST(BatchWorkers, EveryAreaIsPlannedAcrossTheWorkersHandOvers) {
  const std::string dir = fresh_dir("batch-workers-many");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::vector<std::string> plots;
  for (int i = 0; i < 140; ++i) plots.push_back(small_plot(i));
  std::ofstream(areas) << areas_of(plots);
  const CliRun run = run_swath("batch " + areas + " -o " + dir + "/out --jobs 2" + kOptions);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = batch_rows(dir + "/out");
  ASSERT_EQ(rows.size(), plots.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][0], "small " + std::to_string(i));
    EXPECT_EQ(rows[i][4], "planned") << i;
    EXPECT_TRUE(fs::is_regular_file(dir + "/out/" + rows[i][3] + "/drone-1.plan")) << i;
  }
  for (const std::size_t i : {0u, 63u, 64u, 65u, 128u, 139u})
    EXPECT_TRUE(planned_as_alone(areas, i, dir + "/out", rows[i][3], dir)) << i;
}

// A worker killed while planning (here by the file size limit, SIGXFSZ, on the large plot's
// photos) fails that area alone, with the signal in its row and no directory of it left; the
// areas after it are planned by a fresh worker, as alone.
TEST(BatchWorkers, AWorkerThatDiesFailsOnlyItsArea) {
  const std::string dir = fresh_dir("batch-workers-death");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::ofstream(areas) << areas_of({small_plot(0), large_plot(0), small_plot(1), small_plot(2)});
  // 100 blocks: 50 kB in dash's units, 100 kB in bash's; both between the two plots' files.
  const CliRun run =
      run_program("sh", "-c 'ulimit -f 100; exec " + std::string(SWATH_BINARY) + " batch " + areas +
                            " -o " + dir + "/out --jobs 1" + kOptions + "'");
  ASSERT_EQ(run.exit_code, 3) << run.err;
  const auto rows = batch_rows(dir + "/out");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[1][4], "failed");  // not refused: nothing was wrong with the area
  EXPECT_EQ(rows[1][5], "153");     // 128 + SIGXFSZ
  EXPECT_NE(batch_lines(dir + "/out")[1].find("ended by signal 25"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(dir + "/out/" + rows[1][3]));
  for (const std::size_t i : {0u, 2u, 3u}) {
    EXPECT_EQ(rows[i][4], "planned") << i;
    EXPECT_TRUE(planned_as_alone(areas, i, dir + "/out", rows[i][3], dir)) << i;
  }
}

// Shell lines that set w to the first child of the process $b (the batch's worker), from
// /proc/$b/task/$b/children, else from every process's parent in /proc/PID/stat (builtins only),
// looking every 5 ms (a sanitized batch forks its first worker only after some hundreds of ms);
// exit 97 when none is found in 12,000 looks (a minute or more).
const char* const kFindWorker =
    "w=; n=0; while [ -z \"$w\" ] && [ $n -lt 12000 ]; do n=$((n+1)); "
    "if [ -e /proc/$b/task/$b/children ]; then read -r w rest 2>/dev/null "
    "< /proc/$b/task/$b/children; else for s in /proc/[0-9]*/stat; do "
    "read -r line 2>/dev/null < $s && set -- $line x x x x && [ \"$4\" = \"$b\" ] && w=$1; "
    "done; fi; [ -n \"$w\" ] || sleep 0.005; done; [ -n \"$w\" ] || { kill $b; exit 97; }; ";

// A worker that stops answering (here stopped with SIGSTOP as soon as it starts; in the field a
// hung network mount) fails the area it holds once --timeout-s has passed, that area alone: a
// fresh worker plans the others, each as alone, and nothing of the stopped one is left behind.
TEST(BatchWorkers, AnAreaPastTheTimeoutFailsAloneTheBatchGoesOn) {
  const std::string dir = fresh_dir("batch-workers-timeout");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::vector<std::string> plots;
  for (int i = 0; i < 120; ++i) plots.push_back(small_plot(i));
  std::ofstream(areas) << areas_of(plots);
  // The batch in the background, its worker stopped as soon as it is found, the batch waited for.
  const std::string script = std::string(SWATH_BINARY) + " batch " + areas + " -o " + dir +
                             "/out --jobs 1 --timeout-s 3" + kOptions + " & b=$!; " + kFindWorker +
                             "kill -STOP $w; wait $b";
  const CliRun run = run_program("sh", "-c '" + script + "'");
  ASSERT_EQ(run.exit_code, 3) << run.err << run.out;
  const auto rows = batch_rows(dir + "/out");
  const auto lines = batch_lines(dir + "/out");
  ASSERT_EQ(rows.size(), plots.size());
  std::size_t timed_out = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i][4] == "planned") {
      if (i % 10 == 0) EXPECT_TRUE(planned_as_alone(areas, i, dir + "/out", rows[i][3], dir)) << i;
      continue;
    }
    ++timed_out;
    EXPECT_EQ(rows[i][4], "timed-out") << lines[i];
    EXPECT_EQ(rows[i][5], "1") << lines[i];
    EXPECT_NE(lines[i].find("planning took longer than --timeout-s 3 s; its process was ended"),
              std::string::npos)
        << lines[i];
  }
  EXPECT_EQ(timed_out, 1u);
  for (const auto& e : fs::recursive_directory_iterator(dir + "/out"))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  EXPECT_EQ(run_swath("batch " + areas + " -o " + dir + "/no --timeout-s -1" + kOptions).exit_code,
            2);
}

// The batch itself stopped for 4 s under --timeout-s 2 (its worker plans on and answers): no area
// is failed. Nor with the worker stopped in an area, then the batch (as Ctrl-Z stops the whole
// job): the time stopped is not counted against the area (this second case fails without that).
TEST(BatchWorkers, ABatchStoppedAWhileFailsNoAreaForTheTimeout) {
  const std::string dir = fresh_dir("batch-workers-stopped");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::vector<std::string> plots;
  for (int i = 0; i < 40; ++i) plots.push_back(small_plot(i));
  std::ofstream(areas) << areas_of(plots);
  for (const std::string stopped : {"$b", "$w; sleep 0.2; kill -STOP $b"}) {
    const std::string out = dir + "/out-" + std::to_string(stopped.size());
    const std::string script = std::string(SWATH_BINARY) + " batch " + areas + " -o " + out +
                               " --jobs 1 --timeout-s 2" + kOptions + " & b=$!; " + kFindWorker +
                               "kill -STOP " + stopped + "; sleep 4; kill -CONT $w $b; wait $b";
    const CliRun run = run_program("sh", "-c '" + script + "'");
    EXPECT_EQ(run.exit_code, 0) << stopped << ": " << read_text(out + "/batch.csv");
    const auto rows = batch_rows(out);
    ASSERT_EQ(rows.size(), plots.size());
    for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i][4], "planned") << i;
  }
}

// A batch ended by SIGTERM while its worker is stopped ends that worker too (without the batch's
// SIGCONT the worker's SIGTERM from PR_SET_PDEATHSIG stays pending, and it stays stopped for
// good, an orphan); and it leaves no temporary of the area it held.
TEST(BatchWorkers, ABatchEndedBySignalEndsItsStoppedWorker) {
  const std::string dir = fresh_dir("batch-workers-ended");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::vector<std::string> plots;
  for (int i = 0; i < 40; ++i) plots.push_back(small_plot(i));
  std::ofstream(areas) << areas_of(plots);
  // The worker's state once the batch is gone: "ended" (no process, or a zombie init reaps) or
  // its state letter (then killed, so that no test leaves it behind).
  const std::string script =
      std::string(SWATH_BINARY) + " batch " + areas + " -o " + dir + "/out --jobs 1" + kOptions +
      " & b=$!; " + kFindWorker +
      "kill -STOP $w; sleep 0.2; kill -TERM $b; wait $b; n=0; s=ended; "
      "while [ $n -lt 500 ]; do s=ended; read -r l 2>/dev/null < /proc/$w/stat || break; "
      "set -- $l; [ \"$3\" = Z ] && break; s=$3; n=$((n+1)); sleep 0.01; done; "
      "echo worker: $s; [ $s = ended ] || kill -KILL $w";
  const CliRun run = run_program("sh", "-c '" + script + "'");
  EXPECT_NE(run.out.find("worker: ended"), std::string::npos) << run.out << run.err;
  if (fs::exists(dir + "/out"))
    for (const auto& e : fs::recursive_directory_iterator(dir + "/out"))
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

// A comb of four teeth (concave): split, its direction search on threads. Its plan is the same
// bytes on one thread or three; a batch gives its workers' plans a share of the machine's threads
// (--threads), unless the plan options name it themselves (given twice, `swath plan` refuses).
TEST(BatchWorkers, TheThreadsChangeNoFile) {
  const std::string dir = fresh_dir("batch-workers-threads");
  fs::create_directories(dir + "/areas");
  // The base from 47.300 to 47.302, teeth 0.002 deg wide and 0.001 apart up to 47.308.
  std::string ring = "[8.4, 47.3], [8.411, 47.3]";
  for (int t = 3; t >= 0; --t) {
    const std::string right = base::shortest_text(8.4 + 0.003 * t + 0.002),
                      left = base::shortest_text(8.4 + 0.003 * t);
    ring += ", [" + right + ", 47.308], [" + left + ", 47.308]";
    if (t > 0)
      ring += ", [" + left + ", 47.302], [" + base::shortest_text(8.4 + 0.003 * t - 0.001) +
              ", 47.302]";
  }
  ring += ", [8.4, 47.3]";
  std::ofstream(dir + "/areas/comb.geojson")
      << R"({"type": "Polygon", "coordinates": [[)" << ring << "]]}\n";
  std::ofstream(dir + "/areas/plots.geojson") << areas_of({small_plot(0), small_plot(1)});
  const std::string comb = dir + "/areas/comb.geojson";
  ASSERT_EQ(run_swath("plan " + comb + kOptions + " -o " + dir + "/all").exit_code, 0);
  const auto all = directory_files(dir + "/all");
  EXPECT_NE(all.at("summary.json").find("\"split\""), std::string::npos);
  for (const char* threads : {"1", "3"}) {
    const std::string out = dir + "/threads-" + threads;
    ASSERT_EQ(
        run_swath("plan " + comb + kOptions + " --threads " + threads + " -o " + out).exit_code, 0);
    EXPECT_EQ(directory_files(out), all) << threads;
  }
  EXPECT_EQ(run_swath("plan " + comb + kOptions + " --threads -1 -o " + dir + "/no").exit_code, 2);
  const CliRun shared =
      run_swath("batch " + dir + "/areas -o " + dir + "/shared --jobs 2" + kOptions);
  ASSERT_EQ(shared.exit_code, 0) << shared.err;
  EXPECT_EQ(directory_files(dir + "/shared/comb"), all);
  for (const std::string given : {" --jobs 2 --threads=1", " --jobs 1 --threads 2"}) {
    const std::string out = dir + "/given-" + std::to_string(given.size());
    const CliRun run = run_swath("batch " + dir + "/areas -o " + out + given + kOptions);
    ASSERT_EQ(run.exit_code, 0) << given << ": " << read_text(out + "/batch.csv");
    EXPECT_EQ(directory_files(out), directory_files(dir + "/shared")) << given;
  }
}

// A CPU time limit (ulimit -t) is a process's: `swath plan` alone has the whole of it for its area,
// and so does each area of a batch under it, not what the worker's earlier areas left of it (60
// stars of about 60 ms each on one thread: 3.6 s for all of them in one worker; 2 s leaves a
// sanitized build's 0.6-0.7 s a star three times over, where 1 s at times did not).
TEST(BatchWorkers, ACpuTimeLimitIsEachAreasAsAlone) {
  const std::string dir = fresh_dir("batch-workers-cpu");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  std::vector<std::string> plots;
  for (int i = 0; i < 60; ++i) plots.push_back(star_plot(i));
  std::ofstream(areas) << areas_of(plots);
  const CliRun run =
      run_program("sh", "-c 'ulimit -t 2; exec " + std::string(SWATH_BINARY) + " batch " + areas +
                            " -o " + dir + "/out --jobs 1 --threads 1" + kOptions + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const auto rows = batch_rows(dir + "/out");
  ASSERT_EQ(rows.size(), plots.size());
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i][4], "planned") << i;
  EXPECT_TRUE(planned_as_alone(areas, 59, dir + "/out", rows[59][3], dir));
}

// A worker that ends between two areas (here killed while the batch is stopped, after it has
// planned one) was planning none: the next area goes to a fresh worker, not into a row of a
// signal it never met (nor the message the dead worker's log held from the area before).
TEST(BatchWorkers, AWorkerThatDiesBetweenAreasFailsNone) {
  const std::string dir = fresh_dir("batch-workers-idle");
  fs::create_directories(dir);
  const std::string areas = dir + "/areas.geojson";
  // Large plots after the first area: the batch is still at work when the script stops it.
  std::vector<std::string> plots{small_plot(0)};
  for (int i = 0; i < 12; ++i) plots.push_back(large_plot(i));
  std::ofstream(areas) << areas_of(plots);
  // The batch stopped once the first area is written; its worker then finishes what it has and
  // waits for the next area, and is killed there; the batch goes on once it is dead (a zombie).
  // Exit 90 or 91: the script did not get there (no worker, or it did not die).
  const std::string script = std::string(SWATH_BINARY) + " batch " + areas + " -o " + dir +
                             "/out --jobs 1" + kOptions + R"( & b=$!
    until [ -e )" + dir + R"(/out/small_0/summary.json ]; do sleep 0.01; done
    kill -STOP $b; sleep 1; w=
    for s in /proc/[0-9]*/status; do
      grep -q "^PPid:[[:space:]]*$b\$" $s 2>/dev/null && w=${s#/proc/} && w=${w%/status}
    done
    [ -n "$w" ] || { kill -KILL $b; exit 90; }
    kill -KILL $w; n=0
    until grep -q "^State:[[:space:]]*Z" /proc/$w/status; do
      n=$((n + 1)); [ $n -lt 500 ] || { kill -KILL $b; exit 91; }; sleep 0.01
    done
    kill -CONT $b; wait $b)";
  const CliRun run = run_program("sh", "-c '" + script + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const auto rows = batch_rows(dir + "/out");
  ASSERT_EQ(rows.size(), plots.size());
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i][4], "planned") << i;
  for (const std::size_t i : {0u, 1u, 2u, 3u})
    EXPECT_TRUE(planned_as_alone(areas, i, dir + "/out", rows[i][3], dir)) << i;
}

}  // namespace
}  // namespace swath::test

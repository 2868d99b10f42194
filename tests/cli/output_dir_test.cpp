// The output side of issue 16 (docs/swath-plan.md), as a user and an attacker meet
// it: concurrent runs into one directory, signals at random moments, re-plans that leave fewer
// files, other programs writing into a plan's directory, names that collide, bytes that are not
// UTF-8, and the worst inputs refused within bounded time and memory.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/survey.hpp"

extern char** environ;

namespace swath::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Starts `swath args...` from the source tree with stdout/stderr to /dev/null; returns its pid.
pid_t start_swath(const std::vector<std::string>& args) {
  std::vector<std::string> all{SWATH_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t io;
  posix_spawn_file_actions_init(&io);
  posix_spawn_file_actions_addopen(&io, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&io, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addchdir_np(&io, SWATH_SOURCE_DIR);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, SWATH_BINARY, &io, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&io);
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::vector<std::string> plan_args(int altitude_m, const std::string& out) {
  return {"plan",       "share/fields/meadow.geojson", "--camera", "sony-ilce-qx1",
          "--altitude", std::to_string(altitude_m),    "-o",       out};
}

// The directory holds exactly one complete plan: summary.json lists the set, every listed file
// is there and parses as that plan (the .plan's altitude is summary's), nothing else of ours and
// no temporaries. Returns the altitude of the set, or -1 when the directory holds no plan.
double one_complete_set(const std::string& dir) {
  if (!fs::exists(dir + "/summary.json")) {
    for (const auto& e : fs::directory_iterator(dir))
      ADD_FAILURE() << "no summary.json but " << e.path().filename();
    return -1;
  }
  const json summary = json::parse(read_text(dir + "/summary.json"));
  std::set<std::string> listed;
  for (const auto& f : summary.at("files")) listed.insert(f.get<std::string>());
  std::set<std::string> present;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(".swath-", 0) == 0) continue;  // the set's manifest
    present.insert(name);
  }
  EXPECT_EQ(present, listed) << "files of another set, or temporaries, in " << dir;
  const double altitude = summary.at("camera").at("altitude_m").get<double>();
  const json plan = json::parse(read_text(dir + "/drone-1.plan"));
  double item_altitude = -1;
  for (const auto& item : plan.at("mission").at("items"))
    if (item.at("command") == 16) item_altitude = item.at("params")[6].get<double>();
  EXPECT_DOUBLE_EQ(item_altitude, altitude) << "drone-1.plan from another run than summary.json";
  EXPECT_NE(read_text(dir + "/mission.kml").find("</kml>"), std::string::npos);
  return altitude;
}

TEST(OutputDir, TwentyConcurrentRunsLeaveOneCompleteSet) {
  const std::string out = fresh_dir("concurrent");
  std::vector<pid_t> runs;
  for (int k = 0; k < 20; ++k) runs.push_back(start_swath(plan_args(40 + k, out)));
  int succeeded = 0;
  for (const pid_t pid : runs) succeeded += wait_exit(pid) == 0;
  EXPECT_EQ(succeeded, 20) << "each waits for the lock (10 s) and then writes its set";
  const double altitude = one_complete_set(out);
  EXPECT_GE(altitude, 40);
  EXPECT_LE(altitude, 59);
}

TEST(OutputDir, SigtermAtRandomMomentsLeavesTheOldOrTheNewSet) {
  const std::string out = fresh_dir("sigterm");
  ASSERT_EQ(
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + out)
          .exit_code,
      0);
  std::mt19937 random(20261124);
  std::uniform_int_distribution<int> delay_us(0, 40000);
  int killed = 0;
  for (int k = 0; k < 50; ++k) {
    const int altitude = 61 + k % 30;
    std::vector<std::string> args = plan_args(altitude, out);
    if (k % 5 == 0) args.push_back("--render");  // a long write: the signal lands mid-set
    const pid_t pid = start_swath(args);
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(random)));
    kill(pid, SIGTERM);
    const int code = wait_exit(pid);
    killed += code == 128 + SIGTERM;
    EXPECT_TRUE(code == 0 || code == 128 + SIGTERM) << "exit " << code;
    one_complete_set(out);
  }
  EXPECT_GT(killed, 10) << "the signals should land while the runs are at work";
}

TEST(OutputDir, AReplanRemovesTheStaleFilesOfTheOldPlanOnly) {
  const std::string out = fresh_dir("stale");
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
                      "--drones 3 -o " +
                      out)
                .exit_code,
            0);
  ASSERT_TRUE(fs::exists(out + "/drone-3.plan"));
  { std::ofstream(out + "/pilot-notes.txt") << "mine"; }
  ASSERT_EQ(
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + out)
          .exit_code,
      0);
  EXPECT_FALSE(fs::exists(out + "/drone-2.plan"));
  EXPECT_FALSE(fs::exists(out + "/drone-3.waypoints"));
  EXPECT_EQ(read_text(out + "/pilot-notes.txt"), "mine") << "swath removes only what it wrote";
}

// A file no swath run wrote (listed in no manifest here: the user's, or an older swath's that
// wrote none) is never replaced: the plan is refused naming it, exit 2, nothing written. A file
// the plan before wrote is replaced as ever.
TEST(OutputDir, AFileSwathDidNotWriteIsNeverReplaced) {
  for (const std::string name : {"photos.csv", "summary.json"}) {
    const std::string out = fresh_dir("unlisted-" + name);
    fs::create_directories(out);
    const std::string mine = "MY OWN NOTES\n";
    std::ofstream(out + "/" + name) << mine;
    const CliRun r = run_swath(
        "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + out);
    EXPECT_EQ(r.exit_code, 2) << name;
    EXPECT_EQ(r.err, "swath plan: " + out + "/" + name +
                         ": a file swath did not write (no .swath-plan.files here lists it) "
                         "would be replaced; move it, or choose another -o\n");
    EXPECT_EQ(read_text(out + "/" + name), mine);
    EXPECT_EQ(directory_files(out).size(), 1u) << name;
    fs::remove(out + "/" + name);
    ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
                        "-o " +
                        out)
                  .exit_code,
              0);
    EXPECT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 70 "
                        "-o " +
                        out)
                  .exit_code,
              0)
        << "the plan before's files are replaced";
  }
}

// The programs whose work takes long (runs over many seeds) refuse a file of the user's in the
// way before that work, not after it: swath-fleet compare and forecasts print their tables to
// stdout as they finish the runs, so nothing on stdout shows no run was made.
TEST(OutputDir, AFileInTheWayIsRefusedBeforeTheRuns) {
  const std::string mine = "MY OWN TABLE\n";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"compare road --world road --drones 2 --seeds 2 --schedulers reactive,greedy",
       "compare.csv"},
      {"forecasts road --world road --seeds 2", "forecasts.csv"}};
  for (const auto& [command, name] : cases) {
    const std::string out = fresh_dir("in-the-way-" + name);
    fs::create_directories(out);
    std::ofstream(out + "/" + name) << mine;
    const CliRun r = run_swath_fleet(command + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find(out + "/" + name + ": a file swath did not write"), std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "") << command << ": runs were made before the refusal";
    EXPECT_EQ(read_text(out + "/" + name), mine);
    EXPECT_EQ(directory_files(out).size(), 1u) << command;
  }
}

TEST(OutputDir, OtherProgramsAndExtraNamesNeverReplaceThePlan) {
  const std::string out = fresh_dir("foreign");
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
                      "--drones 2 -o " +
                      out)
                .exit_code,
            0);
  const std::string summary = read_text(out + "/summary.json");
  const std::string drone_1 = read_text(out + "/drone-1.plan");
  // swath-energy run into the plan's directory would replace summary.json: refused.
  const CliRun energy =
      run_swath_energy("run plans/survey.stages --config plans/survey-sim.yaml -o " + out);
  EXPECT_EQ(energy.exit_code, 2);
  EXPECT_NE(energy.err.find("summary.json belongs to the files of a swath plan"), std::string::npos)
      << energy.err;
  EXPECT_FALSE(fs::exists(out + "/energy.csv"));
  // An energy plan named like a file of the set: refused before anything is written.
  // One drone keeps the name (summary.json); with a fleet drone.plan becomes drone-1.plan, ...
  for (const std::string options :
       {"--energy-plan summary.json", "--drones 2 --energy-plan drone.plan"}) {
    const CliRun collide =
        run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 70 " +
                  options + " -o " + out);
    const std::string& name = options;
    EXPECT_EQ(collide.exit_code, 2) << name;
    EXPECT_NE(collide.err.find("a file of the mission set itself"), std::string::npos)
        << collide.err;
  }
  EXPECT_EQ(read_text(out + "/summary.json"), summary);
  EXPECT_EQ(read_text(out + "/drone-1.plan"), drone_1);
  // render into the plan's own directory joins the plan's set (no refusal).
  EXPECT_EQ(run_swath("render " + out).exit_code, 0);
  EXPECT_TRUE(fs::exists(out + "/coverage.png"));
}

TEST(OutputDir, BytesThatAreNotUtf8AreReplacedNotFatal) {
  const std::string dir = fresh_dir("latin1");
  fs::create_directories(dir);
  const std::string field = dir + "/Wiese-\xE9t\xE9.geojson";  // Latin-1 é in the file name
  fs::copy_file(source_path("share/fields/meadow.geojson"), field);
  {
    std::ofstream fleet(dir + "/fleet.yaml");
    fleet << "home: {lat: 47.397, lon: 8.540}\ndrones:\n  - {name: \"h\xE9l\xE8ne\", capability: "
             "0.5}\n  - {name: bravo, capability: 0.5}\n";
  }
  const std::string out = dir + "/out";
  const CliRun run =
      run_swath("plan '" + field + "' --camera sony-ilce-qx1 --altitude 60 --fleet " + dir +
                "/fleet.yaml -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(read_text(out + "/summary.json"));  // valid UTF-8 throughout
  EXPECT_EQ(summary.at("drones")[0].at("name").get<std::string>(), "h\uFFFDl\uFFFDne");
  EXPECT_NE(summary.at("field").get<std::string>().find("Wiese-\uFFFDt\uFFFD"), std::string::npos);
}

// Runs `command` (through /bin/sh, from the source tree) under swath_rusage_probe, and returns
// (exit code, CPU seconds, peak RSS in MB) of that command alone (the probe says why not directly).
struct Usage {
  int exit_code;
  double cpu_s, rss_mb;
};
Usage measured(const std::string& command) {
  int pipe_fds[2];
  EXPECT_EQ(pipe(pipe_fds), 0);
  const std::string full =
      "cd '" + std::string(SWATH_SOURCE_DIR) + "' && " + command + " >/dev/null 2>&1";
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_fds[0]);
    dup2(pipe_fds[1], STDOUT_FILENO);
    execl(SWATH_RUSAGE_PROBE, SWATH_RUSAGE_PROBE, full.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string text;
  char buffer[256];
  for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<std::size_t>(n));
  close(pipe_fds[0]);
  waitpid(child, nullptr, 0);
  Usage u{-1, 0, 0};
  long rss_kb = 0;
  EXPECT_EQ(std::sscanf(text.c_str(), "%d %lf %ld", &u.exit_code, &u.cpu_s, &rss_kb), 3) << text;
  u.rss_mb = static_cast<double>(rss_kb) / 1024.0;
  return u;
}

// The inputs that once ran for minutes or grew to gigabytes are refused at once: exit 2 within a
// second of CPU and 200 MB (generous bounds for what takes milliseconds and ~10 MB; the point is
// that nothing grows with the absurd number). Under the sanitizers everything runs 5–15× slower
// (the YAML alias bomb: 0.09 s plain, 1.3 s instrumented), so the CPU bound there is 10 s — still
// a tenth of what the worst input took before it was bounded.
#ifdef SWATH_SANITIZED
constexpr double kWorstInputCpuS = 10.0;
#else
constexpr double kWorstInputCpuS = 1.0;
#endif
TEST(OutputDir, TheWorstInputsAreRefusedInBoundedTimeAndMemory) {
  const std::string dir = fresh_dir("worst");
  fs::create_directories(dir);
  {
    // 3,000 tiny holes (98 s and 5.6 GB before).
    std::ofstream csv(dir + "/holes.csv");
    csv.precision(10);
    csv << "lon,lat,ring\n8.5,47.4,0\n8.53,47.4,0\n8.53,47.42,0\n8.5,47.42,0\n";
    int ring = 0;
    for (int i = 0; i < 60; ++i)
      for (int j = 0; j < 50; ++j) {
        const double x = 8.5 + 0.03 * (i + 0.5) / 60, y = 47.4 + 0.02 * (j + 0.5) / 50;
        ++ring;
        for (const auto& [dx, dy] : {std::pair{-1, -1}, {-1, 1}, {1, 1}, {1, -1}})
          csv << x + dx * 0.00005 << ',' << y + dy * 0.00005 << ',' << ring << '\n';
      }
  }
  {
    // A 2,000-vertex star whose lines cross dozens of spikes each: 20,663 lines, over the limit
    // (145 s and out of memory before, laying and ordering them at every direction).
    std::ofstream csv(dir + "/star.csv");
    csv.precision(10);
    csv << "x,y\n";
    for (int i = 0; i < 2000; ++i) {
      const double a = 6.283185307179586 * i / 2000, r = i % 2 ? 150 : 1000;
      csv << r * std::cos(a) << ',' << r * std::sin(a) << '\n';
    }
  }
  const std::string swath = std::string("'") + SWATH_BINARY + "' ";
  const std::string meadow = "plan share/fields/meadow.geojson ";
  for (const std::string& command :
       {swath + meadow + "--camera tests/bad-input/camera-overflow.yaml --altitude 60 -o " + dir +
            "/o",
        swath + meadow + "--camera sony-ilce-qx1 --gsd 1e308 -o " + dir + "/o",
        swath + meadow +
            "--camera sony-ilce-qx1 --altitude 60 --angle-search scan --angle-step "
            "1e-7 -o " +
            dir + "/o",
        swath + meadow + "--camera sony-ilce-qx1 --altitude 60 --drones 10000 -o " + dir + "/o",
        swath + meadow + "--camera sony-ilce-qx1 --altitude 60 --fleet /dev/zero -o " + dir + "/o",
        swath + "plan " + dir + "/holes.csv --camera sony-ilce-qx1 --altitude 100 -o " + dir + "/o",
        swath + "plan " + dir +
            "/star.csv --local --origin 47.4,8.5 --camera dji-phantom-4-pro --altitude 58 -o " +
            dir + "/o",
        std::string("'") + SWATH_ENERGY_BINARY +
            "' run tests/bad-input/plan-alias-bomb.yaml --config plans/survey-sim.yaml -o " + dir +
            "/o"}) {
    const Usage u = measured(command);
    EXPECT_EQ(u.exit_code, 2) << command;
    EXPECT_LT(u.cpu_s, kWorstInputCpuS) << command;
    EXPECT_LT(u.rss_mb, 200.0) << command;
    EXPECT_FALSE(fs::exists(dir + "/o")) << command;
  }
}

// The documented limits bound the work (survey.hpp kMaxWaypoints, kMaxPhotos; docs/reliability.md):
// a plan just inside each stays under 1 GB and a minute of CPU, files written and read back by the
// preflight check included; one just over it is refused before any file is made. Squares at 5 m
// with the QX1: 800 m takes ~202,000 photos, 1,000 m ~316,000 (over 250,000); the meadow with a
// waypoint every 0.5 m ~93,000 items (under 100,000). The accepted ones are left out under the
// sanitizers, whose memory and time are several times the program's own.
TEST(OutputDir, PlansAtTheWaypointAndPhotoLimitsStayUnderAGigabyteAndAMinute) {
  const std::string dir = fresh_dir("limits");
  fs::create_directories(dir);
  auto square = [&](int side_m) {
    const std::string file = dir + "/square" + std::to_string(side_m) + ".csv";
    std::ofstream csv(file);
    csv << "x,y\n0,0\n" << side_m << ",0\n" << side_m << ',' << side_m << "\n0," << side_m << '\n';
    return file;
  };
  const std::string swath = std::string("'") + SWATH_BINARY + "' plan ";
  const std::string local = " --local --origin 47.4,8.5 --camera sony-ilce-qx1 --altitude 5 -o ";
  const CliRun over = run_swath("plan " + square(1000) + local + dir + "/over");
  EXPECT_EQ(over.exit_code, 2) << over.err;
  EXPECT_NE(over.err.find(" photos, more than swath's limit of 250000; fly higher"),
            std::string::npos)
      << over.err;
  EXPECT_FALSE(fs::exists(dir + "/over"));
#ifndef SWATH_SANITIZED
  const std::string photos = swath + square(800) + local + dir + "/photos";
  const std::string items = swath +
                            "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 5 "
                            "--waypoint-spacing 0.5 -o " +
                            dir + "/items";
  for (const std::string& command : {photos, items}) {
    const Usage u = measured(command);
    EXPECT_EQ(u.exit_code, 0) << command;
    EXPECT_LT(u.cpu_s, 60.0) << command;
    EXPECT_LT(u.rss_mb, 1024.0) << command;
  }
  const json p = json::parse(read_text(dir + "/photos/summary.json"));
  const json i = json::parse(read_text(dir + "/items/summary.json"));
  // Near the limits, or the test proves little: within 25 % of each.
  EXPECT_GT(p.at("drones")[0].at("photos").get<double>(), 0.75 * planning::kMaxPhotos);
  EXPECT_LE(p.at("drones")[0].at("photos").get<double>(), planning::kMaxPhotos);
  EXPECT_GT(i.at("drones")[0].at("waypoints").get<double>(), 0.75 * planning::kMaxWaypoints);
#endif
}

// The vertex limit (field.hpp kMaxFieldVertices, docs/reliability.md) on a GPX track, the format
// that took 113 s and 2.7 GB at 1,000,000 points: a closed track of one point more than the limit
// is refused from its bytes (exit 2, little memory, nothing written); one at the limit plans under
// a gigabyte and a minute of CPU and exits 0. The one at the limit is the worst shape measured: an
// 800 m square traced with every point nudged up to 0.3 m off its edge (fixed seed), so about
// half the vertices are reflex and all of them feed the transit router, which is super-linear in
// them (a convex circle, or a square of collinear points, costs far less).
std::string gpx_header() {
  return "<?xml version=\"1.0\"?>\n<gpx version=\"1.1\" creator=\"swath-test\" "
         "xmlns=\"http://www.topografix.com/GPX/1/1\"><trk><name>outline</name><trkseg>\n";
}

void gpx_point(std::ofstream& f, double east_m, double north_m) {
  char row[96];
  std::snprintf(row, sizeof row, "<trkpt lat=\"%.9f\" lon=\"%.9f\"/>\n",
                47.3986 + north_m / 111'320.0, 8.5424 + east_m / (111'320.0 * 0.67696));
  f << row;
}

std::string gpx_circle(const std::string& dir, std::size_t points) {
  const std::string file = dir + "/circle" + std::to_string(points) + ".gpx";
  std::ofstream f(file);
  f << gpx_header();
  for (std::size_t i = 0; i < points; ++i) {  // the last point is the first: closed
    const double a = i + 1 == points ? 0.0 : 6.283185307179586 * double(i) / double(points - 1);
    gpx_point(f, 500.0 * std::cos(a), 500.0 * std::sin(a));
  }
  f << "</trkseg></trk></gpx>\n";
  return file;
}

// An 800 m square traced by `points` track points (the last is the first), evenly spaced along the
// perimeter, each but the corners' neighbours moved across its edge by up to 0.3 m.
[[maybe_unused]] std::string gpx_jittered_square(const std::string& dir, std::size_t points) {
  const std::string file = dir + "/jittered" + std::to_string(points) + ".gpx";
  std::ofstream f(file);
  f << gpx_header();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> nudge_m(-0.3, 0.3);
  const double side_m = 800.0;
  const std::size_t open = points - 1;
  for (std::size_t i = 0; i <= open; ++i) {
    const double s_m = 4.0 * side_m * double(i % open) / double(open);
    const int edge = int(s_m / side_m);
    const double t_m = s_m - edge * side_m;
    const double d_m = t_m > 1.0 && i < open ? nudge_m(rng) : 0.0;
    switch (edge) {
      case 0:
        gpx_point(f, t_m, d_m);
        break;
      case 1:
        gpx_point(f, side_m + d_m, t_m);
        break;
      case 2:
        gpx_point(f, side_m - t_m, side_m + d_m);
        break;
      default:
        gpx_point(f, d_m, side_m - t_m);
        break;
    }
  }
  f << "</trkseg></trk></gpx>\n";
  return file;
}

TEST(OutputDir, AGpxTrackOverTheVertexLimitIsRefusedAtOnceAndOneAtItPlans) {
  const std::string dir = fresh_dir("gpx-limit");
  fs::create_directories(dir);
  const std::string swath = std::string("'") + SWATH_BINARY + "' plan ";
  const std::string options = " --camera sony-ilce-qx1 --altitude 100 --litchi -o ";
  const std::string over = gpx_circle(dir, geometry::kMaxFieldVertices + 1);
  const CliRun refused = run_swath("plan " + over + options + dir + "/over");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(
      refused.err.find("has more than " + std::to_string(geometry::kMaxFieldVertices) +
                       " points (line " + std::to_string(geometry::kMaxFieldVertices + 3) + ")"),
      std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir + "/over"));
  const Usage u = measured(swath + over + options + dir + "/over");
  EXPECT_EQ(u.exit_code, 2);
  EXPECT_LT(u.rss_mb, 200.0);  // counted in the bytes: no geometry built
  EXPECT_LT(u.cpu_s, kWorstInputCpuS);
#ifndef SWATH_SANITIZED
  const Usage at = measured(swath + gpx_jittered_square(dir, geometry::kMaxFieldVertices) +
                            options + dir + "/at");
  EXPECT_EQ(at.exit_code, 0);
  EXPECT_LT(at.cpu_s, 60.0);
  EXPECT_LT(at.rss_mb, 1024.0);
  EXPECT_TRUE(fs::exists(dir + "/at/drone-1-litchi.csv"));
#endif
}

}  // namespace
}  // namespace swath::test

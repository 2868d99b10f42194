// swath-fleet as a user runs it: the bundled case studies give these outputs — the multiplexing
// case never faster than the brute-force optimal order of its own world, the same bytes for the
// same seed (also from four processes at once), exit 4 with the files when the app cannot finish,
// tracks that start at the drones' homes, and compare's intervals recomputed from its own rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "fleet_images.hpp"
#include "swath/base/file_text.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/render/image.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

TEST(FleetCli, MultiplexingCompletesNoFasterThanTheOptimalOrderOfItsWorld) {
  const std::string out = fresh_dir("fleet-multiplexing");
  const CliRun run = run_swath_fleet("run multiplexing --world sites -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("multiplexing completed in"), std::string::npos) << run.out;
  const json summary = json::parse(read_text(out + "/summary.json"));
  EXPECT_TRUE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["tasks"]["done"], 5);  // main, delivery, two photos, video
  const auto world = worlds::read_world(source_path("share/worlds/sites.yaml"));
  const double optimum = fleet::multiplexing_optimum_s(
      dynamic_cast<const worlds::SitesWorld&>(*world), {0, 0, 0}, fleet::Kinematics{}, 20);
  EXPECT_GE(summary["completion_time_s"].get<double>(), optimum);
  EXPECT_LE(summary["completion_time_s"].get<double>(), 1.5 * optimum);
  // Every event line is JSON with a time; the times never go back.
  std::istringstream events(read_text(out + "/events.jsonl"));
  double last = 0;
  int lines = 0;
  for (std::string line; std::getline(events, line); ++lines) {
    const json e = json::parse(line);
    ASSERT_GE(e["t_s"].get<double>(), last) << line;
    last = e["t_s"].get<double>();
  }
  EXPECT_GT(lines, 20);
}

TEST(FleetCli, SameSeedSameBytesFromOneOrFourProcesses) {
  const std::string base = fresh_dir("fleet-determinism");
  const std::string args = "run hotspot --world hotspot --drones 2 --seed 4 -o ";
  ASSERT_EQ(run_swath_fleet(args + base + "/one").exit_code, 0);
  std::string four = "-c '";
  for (int i = 0; i < 4; ++i)
    four += std::string(SWATH_FLEET_BINARY) + " " + args + base + "/p" + std::to_string(i) + " & ";
  four += "wait'";
  ASSERT_EQ(run_program("sh", four).exit_code, 0);
  for (const char* file : {"events.jsonl", "summary.json", "dtg.json", "tracks.geojson"}) {
    const std::string one = read_text(base + "/one/" + file);
    ASSERT_FALSE(one.empty()) << file;
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(read_text(base + "/p" + std::to_string(i) + "/" + file), one) << file << " " << i;
  }
  // Another seed: another schedule (the scheduler's random numbers), same world.
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 2 --seed 5 -o " + base + "/other")
                .exit_code,
            0);
  EXPECT_NE(read_text(base + "/other/summary.json"), read_text(base + "/one/summary.json"));
}

// Scale-out (docs/swath-fleet.md): sweep prints one line per run, GNU parallel runs them (two at a
// time), each run's files equal a direct run's, and collect's table holds each run's own figures;
// runs of another configuration, another version or a repeated (scheduler, seed) are refused.
TEST(FleetCli, SweepLinesRunUnderGnuParallelAndCollectMergesThem) {
  const std::string dir = fresh_dir("fleet-sweep");
  fs::create_directories(dir);
  std::ofstream(dir + "/spec.yaml") << "app: hotspot\nworld: hotspot\ndrones: 2\n"
                                    << "schedulers: [sa, greedy]\nseeds: {from: 4, to: 6}\n"
                                    << "wind: \"2,1\"\n";
  const CliRun sweep = run_swath_fleet("sweep " + dir + "/spec.yaml --runs " + dir + "/runs");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  std::vector<std::string> lines;
  std::istringstream in(sweep.out);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 6u);
  const std::string program = fs::canonical(SWATH_FLEET_BINARY).string();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].rfind(program + " run hotspot ", 0), 0u) << lines[i];
    const std::string scheduler = i < 3 ? "sa" : "greedy";
    EXPECT_NE(lines[i].find("--scheduler " + scheduler + " --seed " + std::to_string(4 + i % 3)),
              std::string::npos)
        << lines[i];
  }
  std::ofstream(dir + "/jobs.txt") << sweep.out;
  const CliRun parallel = run_program(
      "parallel", "-j2 --will-cite --joblog " + dir + "/joblog -a " + dir + "/jobs.txt");
  ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 2 --scheduler greedy --seed 5 "
                            "--world-seed 5 --wind 2,1 -o " +
                            dir + "/direct")
                .exit_code,
            0);
  EXPECT_EQ(read_text(dir + "/direct/summary.json"),
            read_text(dir + "/runs/hotspot-greedy-seed5/summary.json"));
  EXPECT_EQ(read_text(dir + "/direct/events.jsonl"),
            read_text(dir + "/runs/hotspot-greedy-seed5/events.jsonl"));

  const CliRun collect = run_swath_fleet("collect " + dir + "/runs/* -o " + dir + "/table");
  ASSERT_EQ(collect.exit_code, 0) << collect.err;
  std::istringstream csv(read_text(dir + "/table/collect.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.substr(0, 44), "run,app,scheduler,seed,completed,completion_");
  std::vector<std::string> order;
  for (std::string row; std::getline(csv, row);) {
    std::vector<std::string> f;
    std::istringstream cells(row);
    for (std::string cell; std::getline(cells, cell, ',');) f.push_back(cell);
    ASSERT_EQ(f.size(), 13u) << row;
    const json summary = json::parse(read_text(f[0] + "/summary.json"));
    EXPECT_EQ(f[2], summary["scheduler"].get<std::string>());
    EXPECT_EQ(std::stoull(f[3]), summary["seed"].get<std::uint64_t>());
    EXPECT_NEAR(std::stod(f[5]), summary["completion_time_s"].get<double>(), 5e-4);
    double energy = 0;
    for (const auto& d : summary["drones"]) energy += d["energy_wh"].get<double>();
    EXPECT_NEAR(std::stod(f[6]), energy, 1e-6);
    EXPECT_EQ(std::stoll(f[8]), summary["tasks"]["done"].get<long long>());
    order.push_back(f[2] + f[3]);
  }
  EXPECT_EQ(order,
            (std::vector<std::string>{"greedy4", "greedy5", "greedy6", "sa4", "sa5", "sa6"}));

  // Refusals: nothing written.
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 2 --scheduler sa --seed 9 "
                            "--wind 3,1 -o " +
                            dir + "/windier")
                .exit_code,
            0);
  CliRun refused =
      run_swath_fleet("collect " + dir + "/runs/* " + dir + "/windier -o " + dir + "/refused");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("another configuration"), std::string::npos) << refused.err;
  refused = run_swath_fleet("collect " + dir + "/runs/hotspot-sa-seed4 " + dir +
                            "/runs/hotspot-sa-seed4 -o " + dir + "/refused");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("the same scheduler (sa) and seed (4)"), std::string::npos)
      << refused.err;
  fs::create_directories(dir + "/old");
  std::string old = read_text(dir + "/runs/hotspot-sa-seed5/summary.json");
  const std::size_t v = old.find("\"version\": \"");
  ASSERT_NE(v, std::string::npos);
  old.replace(v, old.find('"', v + 12) + 1 - v, "\"version\": \"0.0.9\"");
  std::ofstream(dir + "/old/summary.json") << old;
  refused = run_swath_fleet("collect " + dir + "/runs/hotspot-sa-seed4 " + dir + "/old -o " + dir +
                            "/refused");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("made by swath-fleet 0.0.9"), std::string::npos) << refused.err;
  // A real flight (summary.json's backend) is not merged with simulated runs.
  fs::create_directories(dir + "/flown");
  std::string flown = read_text(dir + "/runs/hotspot-sa-seed5/summary.json");
  const std::size_t b = flown.find("\"backend\": \"sim\"");
  ASSERT_NE(b, std::string::npos);
  flown.replace(b, 16, "\"backend\": \"mavlink\"");
  std::ofstream(dir + "/flown/summary.json") << flown;
  refused = run_swath_fleet("collect " + dir + "/runs/hotspot-sa-seed4 " + dir + "/flown -o " +
                            dir + "/refused");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("flown with the mavlink backend"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir + "/refused"));
}

TEST(FleetCli, AnAppThatCannotFinishExitsFourWithItsFiles) {
  const std::string out = fresh_dir("fleet-timeout");
  const CliRun run = run_swath_fleet(
      "run tracking --world tracking --fleet share/fleets/tracking-pair.yaml --max-time 30 -o " +
      out);
  EXPECT_EQ(run.exit_code, 4) << run.err;
  EXPECT_NE(run.err.find("did not complete"), std::string::npos) << run.err;
  const json summary = json::parse(read_text(out + "/summary.json"));
  EXPECT_FALSE(summary["completed"].get<bool>());
  EXPECT_LE(summary["end_s"].get<double>(), 30.0 + 1e-9);
  // Every task still ends exactly once in the log.
  std::istringstream events(read_text(out + "/events.jsonl"));
  std::map<int, int> created, ended;
  for (std::string line; std::getline(events, line);) {
    const json e = json::parse(line);
    const std::string ev = e["ev"];
    if (ev == "task_created") created[e["task"].get<int>()]++;
    if (ev == "task_done" || ev == "task_cancelled" || ev == "task_failed")
      ended[e["task"].get<int>()]++;
  }
  EXPECT_EQ(created.size(), ended.size());
  for (const auto& [task, n] : ended) EXPECT_EQ(n, 1) << "task " << task;
}

// --backend mavlink's inputs are refused in one sentence, exit 2, nothing written (the flights
// themselves are tested on a stepped clock in tests/fleet/mavlink_fleet_test.cpp).
TEST(FleetCli, MavlinkBackendInputsAreRefusedInOneSentence) {
  const std::string out = fresh_dir("fleet-mavlink-refused");
  const std::string run = "run hotspot --world hotspot --drones 2 ";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--backend mavlink", "--backend mavlink needs --vehicles"},
      {"--vehicles udp:127.0.0.1:14550", "--vehicles needs --backend mavlink"},
      {"--backend mavlink --vehicles serial:/dev/ttyUSB0,udp:127.0.0.1:14560",
       "\"serial:/dev/ttyUSB0\" is neither udp: nor tcp:"},
      {"--backend mavlink --vehicles udp:127.0.0.1:14550/300,udp:127.0.0.1:14560",
       "system id that is not a number in 1..255"},
      {"--backend mavlink --vehicles udp:127.0.0.1:14550",
       "--vehicles names 1 vehicles for a fleet of 2 drones"}};
  for (const auto& [args, sentence] : cases) {
    const CliRun r = run_swath_fleet(run + args + " -o " + out + "/run");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(sentence), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out + "/run")) << args;
  }
}

// The fleet file's per-drone mavlink {url, sysid} (docs/swath-fleet.md) flies `run --backend
// mavlink` without --vehicles; --vehicles overrides it; summary.json says the backend and which
// vehicle flew which drone. No vehicle answers on these ports: the wall-clock run ends at
// --max-time (exit 4, files written), which is all the addresses need.
TEST(FleetCli, FleetFileMavlinkKeysNameTheVehiclesAndSummarySaysTheBackend) {
  const std::string dir = fresh_dir("fleet-mavlink-keys");
  fs::create_directories(dir);
  std::ofstream(dir + "/fleet.yaml")
      << "drones:\n"
         "  - {name: one, speed_m_s: 10, mavlink: {url: 'udp:127.0.0.1:47651', sysid: 4}}\n"
         "  - {name: two, speed_m_s: 10, mavlink: {url: 'udp:127.0.0.1:47652'}}\n";
  const std::string run = "run hotspot --world hotspot --fleet " + dir + "/fleet.yaml ";
  const CliRun keys = run_swath_fleet(run + "--backend mavlink --max-time 1 -o " + dir + "/keys");
  ASSERT_EQ(keys.exit_code, 4) << keys.err;
  const json k = json::parse(read_text(dir + "/keys/summary.json"));
  EXPECT_EQ(k["backend"], "mavlink");
  EXPECT_EQ(k["vehicles"], json::parse(R"([{"drone": "one", "url": "udp:127.0.0.1:47651",
      "sysid": 4}, {"drone": "two", "url": "udp:127.0.0.1:47652", "sysid": 2}])"));
  const CliRun over = run_swath_fleet(
      run + "--backend mavlink --vehicles udp:127.0.0.1:47653,udp:127.0.0.1:47654/9 --max-time 1 " +
      "-o " + dir + "/over");
  ASSERT_EQ(over.exit_code, 4) << over.err;
  EXPECT_EQ(json::parse(read_text(dir + "/over/summary.json"))["vehicles"],
            json::parse(R"([{"drone": "one", "url": "udp:127.0.0.1:47653", "sysid": 1},
                            {"drone": "two", "url": "udp:127.0.0.1:47654", "sysid": 9}])"));
  // The simulated fleet ignores the keys: backend sim, no vehicles, the same events as the same
  // drones without them.
  std::ofstream(dir + "/plain.yaml") << "drones:\n  - {name: one, speed_m_s: 10}\n"
                                        "  - {name: two, speed_m_s: 10}\n";
  ASSERT_EQ(run_swath_fleet(run + "-o " + dir + "/sim").exit_code, 0);
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --fleet " + dir + "/plain.yaml -o " + dir +
                            "/plain")
                .exit_code,
            0);
  const json sim = json::parse(read_text(dir + "/sim/summary.json"));
  EXPECT_EQ(sim["backend"], "sim");
  EXPECT_FALSE(sim.contains("vehicles"));
  EXPECT_EQ(read_text(dir + "/sim/events.jsonl"), read_text(dir + "/plain/events.jsonl"));
}

TEST(FleetCli, TracksStartAtTheDronesHomes) {
  const std::string out = fresh_dir("fleet-tracks");
  ASSERT_EQ(run_swath_fleet(
                "run tracking --world tracking --fleet share/fleets/tracking-pair.yaml -o " + out)
                .exit_code,
            0);
  const json tracks = json::parse(read_text(out + "/tracks.geojson"));
  const auto world = worlds::read_world(source_path("share/worlds/tracking.yaml"));
  const geometry::LocalFrame frame(world->origin);
  const std::map<std::string, double> home_x{{"left", -5.0}, {"right", 5.0}};
  int seen = 0;
  for (const auto& f : tracks["features"]) {
    if (f["properties"]["role"] != "track") continue;
    const auto& c = f["geometry"]["coordinates"][0];
    const geometry::Point2 p = frame.to_local({c[1].get<double>(), c[0].get<double>(), 0});
    EXPECT_NEAR(p.x, home_x.at(f["properties"]["drone"]), 0.05);
    EXPECT_NEAR(p.y, 0.0, 0.05);
    ++seen;
  }
  EXPECT_EQ(seen, 2);
  // Both drones flew (60 s flights hand the walker over) and the summary says how well it went.
  const json summary = json::parse(read_text(out + "/summary.json"));
  EXPECT_GT(summary["app_metrics"]["handoffs"].get<double>(), 0);
  for (const auto& d : summary["drones"]) EXPECT_GT(d["distance_m"].get<double>(), 10.0);
}

// compare.csv read back: completion times by scheduler, in row order; every run completed.
std::map<std::string, std::vector<double>> compare_times(const std::string& path) {
  std::istringstream csv(read_text(path));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "scheduler,seed,completed,completion_time_s,censored_at_s");
  std::map<std::string, std::vector<double>> times;
  while (std::getline(csv, line)) {
    std::istringstream row(line);
    std::string name, seed, done, t;
    std::getline(row, name, ',');
    std::getline(row, seed, ',');
    std::getline(row, done, ',');
    std::getline(row, t, ',');
    EXPECT_EQ(done, "true") << line;
    times[name].push_back(std::stod(t));
  }
  return times;
}

// predictive learns from reactive's runs of the other seeds: on case 1 with two drones it wins
// on every seed, and its paired change is the mean of the per-seed ratios in compare.csv.
TEST(FleetCli, ComparePredictiveBeatsReactiveOnTheRoadSeedBySeed) {
  const std::string out = fresh_dir("fleet-compare-predictive");
  const CliRun run = run_swath_fleet(
      "compare road --world road --drones 2 --seeds 4 --schedulers reactive,predictive -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::map<std::string, std::vector<double>> times = compare_times(out + "/compare.csv");
  ASSERT_EQ(times["reactive"].size(), 4u);
  ASSERT_EQ(times["predictive"].size(), 4u);
  double change = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_LT(times["predictive"][i], times["reactive"][i]) << i;
    change += (times["predictive"][i] / times["reactive"][i] - 1) / 4;
  }
  const json summary = json::parse(read_text(out + "/summary.json"));
  ASSERT_EQ(summary["paired"].size(), 1u);
  EXPECT_EQ(summary["paired"][0]["scheduler"], "predictive");
  EXPECT_NEAR(summary["paired"][0]["relative_change_mean"].get<double>(), change, 1e-5);
}

TEST(FleetCli, CompareIntervalsAreThoseOfItsOwnRows) {
  const std::string out = fresh_dir("fleet-compare");
  const CliRun run = run_swath_fleet(
      "compare multiplexing --world sites --seeds 4 --schedulers reactive,greedy -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::map<std::string, std::vector<double>> times = compare_times(out + "/compare.csv");
  ASSERT_EQ(times["reactive"].size(), 4u);
  ASSERT_EQ(times["greedy"].size(), 4u);
  const json summary = json::parse(read_text(out + "/summary.json"));
  for (const auto& row : summary["schedulers"]) {
    const auto& x = times[row["scheduler"].get<std::string>()];
    double mean = 0;
    for (double v : x) mean += v / 4;
    double ss = 0;
    for (double v : x) ss += (v - mean) * (v - mean);
    EXPECT_NEAR(row["completion_time_s_mean"].get<double>(), mean, 1e-3 + 1e-3);
    EXPECT_NEAR(row["completion_time_s_ci95"].get<double>(), 3.182 * std::sqrt(ss / 3 / 4), 2e-3);
  }
}

// A fleet file's drone whose home is outside its fence, and one drone under a 10 m ceiling: exit
// 2, one sentence naming the drone and its home's place, nothing written.
TEST(FleetCli, AHomeOutsideTheFenceIsRefusedNamingItsPlace) {
  const std::string dir = fresh_dir("fleet-home-outside");
  fs::create_directories(dir);
  // 18 m east-west by 110 m north-south from hotspot's origin (42.3601 N, 71.0942 W) northwards.
  std::ofstream(dir + "/narrow.geojson")
      << R"({"type": "Polygon", "coordinates": [[[-71.0943214, 42.36001], [-71.0941029, 42.36001],
             [-71.0941029, 42.3610002], [-71.0943214, 42.3610002], [-71.0943214, 42.36001]]]})";
  std::ofstream(dir + "/fleet.yaml")
      << "fence: {geojson: narrow.geojson}\ndrones:\n  - {name: a, home_m: {x_m: 0, y_m: 5}}\n"
         "  - {name: c, home_m: {x_m: 12, y_m: 5}}\n";
  const CliRun r = run_swath_fleet("run hotspot --world hotspot --fleet " + dir +
                                   "/fleet.yaml -o " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("fleet.yaml: c's home (12.0, 5.0) m is outside the inclusion fence"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
  std::ofstream(dir + "/low.yaml") << "ceiling_m: 10\ndrones:\n  - {name: a}\n";
  const CliRun low = run_swath_fleet("run hotspot --world hotspot --fleet " + dir +
                                     "/low.yaml -o " + dir + "/out");
  EXPECT_EQ(low.exit_code, 2);
  EXPECT_NE(low.err.find("a fleet of 1 drone needs altitude layers up to 20 m"), std::string::npos)
      << low.err;
}

// The safety envelope at the command line: 100 default drones do not fit under the 120 m ceiling
// (layers 5 m apart from 20 m): exit 2, one sentence, nothing written; 21 fly, none above 120 m.
TEST(FleetCli, AHundredDronesAreRefusedUnderTheCeilingAndTwentyOneFly) {
  const std::string dir = fresh_dir("fleet-envelope");
  const CliRun refused =
      run_swath_fleet("run wifi --world rf_field --drones 100 -o " + dir + "/hundred");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--drones 100: a fleet of 100 drones needs altitude layers up to "
                             "515 m"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir + "/hundred"));
  ASSERT_EQ(run_swath_fleet("run wifi --world rf_field --drones 21 -o " + dir + "/fit").exit_code,
            0);
  double top_m = 0;
  std::istringstream events(read_text(dir + "/fit/events.jsonl"));
  for (std::string line; std::getline(events, line);) {
    const auto e = nlohmann::json::parse(line);
    if (e.contains("alt_m") && e["ev"] != "request_visible")
      top_m = std::max(top_m, e["alt_m"].get<double>());
  }
  EXPECT_LE(top_m, 120.0);
  EXPECT_EQ(top_m, 120.0);  // drone 21's layer: 20 + 5 × 20
  EXPECT_EQ(run_swath_fleet("check " + dir + "/fit").exit_code, 0);
}

// A bow-tie fence polygon is bad input: exit 2, one sentence naming the file, the feature and
// where it crosses itself; nothing written.
TEST(FleetCli, ASelfCrossingFenceIsRefusedNamingWhereItCrosses) {
  const std::string dir = fresh_dir("fleet-bowtie");
  fs::create_directories(dir);
  std::ofstream(dir + "/bowtie.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
         R"("geometry":{"type":"Polygon","coordinates":[[[-71.0948,42.3596],[-71.0936,42.3606],)"
         R"([-71.0936,42.3596],[-71.0948,42.3606],[-71.0948,42.3596]]]}}]})";
  std::ofstream(dir + "/fleet.yaml")
      << "fence: {geojson: bowtie.geojson}\ndrones:\n  - {name: a, speed_m_s: 10}\n";
  std::ofstream(dir + "/world.yaml")
      << "kind: static\norigin: {lat: 42.3601, lon: -71.0942}\nsensors: {cam: {time_s: 2}}\n"
         "tasks:\n  - {name: t, actions: [{fly_to: {x_m: 10, y_m: 0}}, {sense: cam}]}\n";
  const CliRun r = run_swath_fleet("run static --world " + dir + "/world.yaml --fleet " + dir +
                                   "/fleet.yaml -o " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2);
  const std::string head =
      dir + "/bowtie.geojson: features[0]: the fence polygon crosses itself at ";
  ASSERT_NE(r.err.find(head), std::string::npos) << r.err;
  double lat = 0, lon = 0;
  ASSERT_EQ(std::sscanf(r.err.c_str() + r.err.find(head) + head.size(), "%lf, %lf", &lat, &lon), 2)
      << r.err;
  EXPECT_NEAR(lat, 42.3601, 1e-4);
  EXPECT_NEAR(lon, -71.0942, 1e-4);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

// A file of the user's named as one swath-fleet writes is never replaced, by run, replay, render
// or view: refused naming it, exit 2, nothing written (run before it flies, replay before its
// first run's files); the files of their own run before are replaced as ever.
TEST(FleetCli, AFileSwathDidNotWriteIsNeverReplaced) {
  const std::string dir = fresh_dir("fleet-users-file");
  const std::string mine = "MY OWN FILE\n";
  const std::string run = "run hotspot --world hotspot --drones 2 --seed 5 -o " + dir + "/run";
  ASSERT_NO_FATAL_FAILURE(
      expect_users_file_survives("swath-fleet", run, dir + "/run", "tracks.geojson"));
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 2 --seed 6 -o " + dir + "/run2")
                .exit_code,
            0);

  // render into the run: the user's gantt.png there stays.
  std::ofstream(dir + "/run/gantt.png") << mine;
  const std::map<std::string, std::string> before = directory_files(dir + "/run");
  const CliRun render = run_swath_fleet("render " + dir + "/run");
  EXPECT_EQ(render.exit_code, 2);
  EXPECT_NE(render.err.find(dir + "/run/gantt.png: a file swath did not write"), std::string::npos)
      << render.err;
  EXPECT_EQ(directory_files(dir + "/run"), before);

  // replay of two runs: the second's directory holds the user's dtg.json; neither is written.
  fs::create_directories(dir + "/replay/run2");
  std::ofstream(dir + "/replay/run2/dtg.json") << mine;
  const CliRun replay =
      run_swath_fleet("replay " + dir + "/run " + dir + "/run2 -o " + dir + "/replay");
  EXPECT_EQ(replay.exit_code, 2);
  EXPECT_NE(replay.err.find(dir + "/replay/run2/dtg.json: a file swath did not write"),
            std::string::npos)
      << replay.err;
  EXPECT_EQ(directory_files(dir + "/replay"),
            (std::map<std::string, std::string>{{"run2/dtg.json", mine}}));

  // view's page in the run: the user's view.html stays; a page named with -o is written as asked.
  std::ofstream(dir + "/run/view.html") << mine;
  const CliRun view = run_swath_fleet("view " + dir + "/run");
  EXPECT_EQ(view.exit_code, 2);
  EXPECT_EQ(view.err, "swath-fleet view: " + dir +
                          "/run/view.html: a file swath did not write (no "
                          ".swath-fleet-view.files here lists it) would be replaced; move it, or "
                          "name another page with -o\n");
  EXPECT_EQ(read_text(dir + "/run/view.html"), mine);
  const CliRun named = run_swath_fleet("view " + dir + "/run -o " + dir + "/run/view.html");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_EQ(read_text(dir + "/run/view.html").rfind("<!DOCTYPE html>", 0), 0u);
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

TEST(FleetCli, ForecastsScoreEveryStepAfterTheFirstAndPoolTheirOwnRows) {
  // The road app spawns its 25 steps one after another: each run scores 24 next tasks per
  // forecaster; the summary pools exactly the rows of forecasts.csv.
  const std::string out = fresh_dir("fleet-forecasts");
  const CliRun run = run_swath_fleet("forecasts road --world road --seeds 3 -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream csv(read_text(out + "/forecasts.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "forecaster,seed,next_tasks,median_distance_m,recall,cancellation_pairs,brier");
  std::map<std::string, std::vector<double>> recall;
  std::map<std::string, long> tasks;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    ASSERT_GE(f.size(), 5u) << line;
    EXPECT_EQ(f[2], "24") << line;
    const double r = std::stod(f[4]);
    EXPECT_GE(r, 0.0);
    EXPECT_LE(r, 1.0);
    recall[f[0]].push_back(r);
    tasks[f[0]] += std::stol(f[2]);
  }
  ASSERT_EQ(recall.size(), 2u);
  const json summary = json::parse(read_text(out + "/summary.json"));
  for (const auto& row : summary["forecasters"]) {
    const std::string name = row["forecaster"];
    ASSERT_EQ(recall[name].size(), 3u) << name;
    EXPECT_EQ(row["next_tasks"].get<long>(), tasks[name]);
    const double mean = (recall[name][0] + recall[name][1] + recall[name][2]) / 3;
    EXPECT_NEAR(row["recall"].get<double>(), mean, 2e-4) << name;
  }
}

TEST(FleetPictures, GanttBarsAndTrackStartsAreWhereTheRecordSays) {
  const auto world = worlds::read_world(source_path("share/worlds/tracking.yaml"));
  std::vector<fleet::DroneSpec> drones(2);
  for (std::size_t i = 0; i < 2; ++i) {
    drones[i].drone.name = std::string(1, static_cast<char>('a' + i));
    drones[i].home_m = {-5.0 + 10.0 * static_cast<double>(i), 0, 0};
    drones[i].max_flight_time_s = 60;
  }
  fleet::App app;
  for (auto& a : fleet::builtin_apps())
    if (a.name == "tracking") app = a;
  const fleet::RunRecord r = fleet::run_app(app, *world, drones, fleet::RuntimeSettings{});
  ASSERT_TRUE(r.completed);
  const int w = 1200, h = 400;
  const apps::FleetPicture g = apps::gantt_picture(r, w, h);
  const render::Image gi = render::draw(g.scene, g.view);
  int checked = 0;
  for (std::size_t d = 0; d < 2; ++d)
    for (const auto& s : r.drones[d].spans) {
      const double x0 = apps::gantt_x_px(s.t0_s, r.end_s, w),
                   x1 = apps::gantt_x_px(s.t1_s, r.end_s, w);
      if (s.mode == "landed" || x1 - x0 < 8) continue;  // too thin to sample cleanly
      const int x = static_cast<int>(0.5 * (x0 + x1)),
                y = static_cast<int>(apps::gantt_row_centre_px(d, 2, h));
      const render::Color c = apps::mode_color(s.mode);
      EXPECT_NEAR(gi.at(x, y, 0), c.r * 255, 3) << s.mode << " at " << s.t0_s;
      EXPECT_NEAR(gi.at(x, y, 1), c.g * 255, 3) << s.mode << " at " << s.t0_s;
      EXPECT_NEAR(gi.at(x, y, 2), c.b * 255, 3) << s.mode << " at " << s.t0_s;
      ++checked;
    }
  EXPECT_GT(checked, 10);
  // The legend's labels end inside the picture at any width (it was cut off at 1,200 px).
  for (int width : {600, 1000, 1200, 2000}) {
    const apps::FleetPicture gw = apps::gantt_picture(r, width, h);
    int legend = 0;
    for (const render::Label& l : gw.scene.labels)
      if (l.text == "unreachable" || l.text == "flying") {
        ++legend;
        EXPECT_GE(l.x_px, 0) << width;
        EXPECT_LE(l.x_px + render::text_extent(l.text, l.height_px).width_px, width)
            << l.text << " at width " << width;
      }
    EXPECT_EQ(legend, 2) << width;
    // The time axis's labels do not touch.
    std::vector<const render::Label*> ticks;
    for (const render::Label& l : gw.scene.labels)
      if (l.text.size() > 2 && l.text.substr(l.text.size() - 2) == " s") ticks.push_back(&l);
    ASSERT_GE(ticks.size(), 2u) << width;
    for (std::size_t i = 1; i < ticks.size(); ++i)
      EXPECT_LT(ticks[i - 1]->x_px +
                    render::text_extent(ticks[i - 1]->text, ticks[i - 1]->height_px).width_px,
                ticks[i]->x_px)
          << ticks[i - 1]->text << " and " << ticks[i]->text << " at width " << width;
    EXPECT_LE(ticks.back()->x_px +
                  render::text_extent(ticks.back()->text, ticks.back()->height_px).width_px,
              width);
  }
  // Each drone's home square is drawn in its colour where the view puts its home.
  const apps::FleetPicture t = apps::tracks_picture(*world, r, w, 900);
  const render::Image ti = render::draw(t.scene, t.view);
  for (std::size_t d = 0; d < 2; ++d) {
    const geometry::Point2 p = t.view.to_pixel({drones[d].home_m.x, drones[d].home_m.y});
    const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
    const render::Color c = apps::drone_color(d);
    EXPECT_NEAR(ti.at(x, y, 0), c.r * 255, 30) << d;
    EXPECT_NEAR(ti.at(x, y, 2), c.b * 255, 30) << d;
  }
}

}  // namespace
}  // namespace swath::test

#include "fleet_main.hpp"
#include "swath/fleet/event_check.hpp"

namespace swath::test {
namespace {

// An application of the test's own, as an out-of-tree program would write it: it registers the
// app and hands its argv to swath-fleet's command line.
fleet::Co<void> corners_main(fleet::Ctx& c) {
  for (const fleet::Vec3& p :
       {fleet::Vec3{60, 0, 0}, fleet::Vec3{60, 60, 0}, fleet::Vec3{0, 60, 0}}) {
    auto h = c.spawn(fleet::Kind{"corner"}, {}, [p](fleet::Ctx& t) -> fleet::Co<fleet::Reading> {
      co_await t.fly_to(p);
      co_return co_await t.hover(2.0);
    });
    co_await h;
  }
}

int fleet_cli(std::vector<std::string> args) {
  args.insert(args.begin(), "swath-fleet");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return apps::fleet_main(static_cast<int>(argv.size()), argv.data());
}

TEST(FleetCli, AnAppOfOnesOwnIsRegisteredListedAndRunByTheSameCommandLine) {
  static const bool once = [] {
    fleet::register_app({"corners", "three corners of a square, a hover at each", corners_main},
                        "road");
    return true;
  }();
  (void)once;
  EXPECT_THROW(fleet::register_app({"road", "taken", corners_main}, "road"), std::invalid_argument);
  EXPECT_THROW(fleet::register_app({"x", "", corners_main}, "moon"), std::invalid_argument);
  const std::string out = fresh_dir("fleet-own-app");
  ASSERT_EQ(fleet_cli({"run", "corners", "--world", source_path("share/worlds/road.yaml"),
                       "--drones", "2", "-o", out}),
            0);
  const json summary = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(summary["app"], "corners");
  EXPECT_TRUE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["tasks"]["done"], 4);  // main and three corners
  const fleet::EventCheck check = fleet::check_events(read_text(out + "/events.jsonl"));
  EXPECT_TRUE(check.ok()) << check.violations.front().message;
  // A kind mismatch is refused like a built-in app's.
  EXPECT_EQ(fleet_cli({"run", "corners", "--world", source_path("share/worlds/sites.yaml"), "-o",
                       fresh_dir("fleet-own-app-kind")}),
            2);
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// render redraws a run from its files alone: the same bytes as run --render drew from memory,
// with faults (lost and unreachable spans), cancellations (wifi) and in place.
TEST(FleetCli, RenderRedrawsARunFromItsFilesByteForByte) {
  const std::string faults = fresh_dir("fleet-render-faults") + ".yaml";
  std::ofstream(faults) << "- {t_s: 20, drone: drone-1, kind: link_loss, duration_s: 15}\n"
                           "- {t_s: 60, drone: drone-2, kind: motor_failure}\n";
  std::vector<std::string> cases{std::string("road --world road --drones 2 --faults ") + faults};
#ifndef SWATH_SANITIZED  // CI's sanitized pass: the road with faults (its pictures have the most)
  cases.push_back("wifi --world rf_field --drones 2");
  cases.push_back("tracking --world tracking --drones 3");
#endif
  for (const std::string& args : cases) {
    const std::string run = fresh_dir("fleet-render-run"), again = fresh_dir("fleet-render-again");
    const CliRun r = run_swath_fleet("run " + args + " --render --size 640x480 -o " + run);
    ASSERT_NE(r.exit_code, 2) << r.err;
    const CliRun d = run_swath_fleet("render " + run + " --size 640x480 -o " + again);
    ASSERT_EQ(d.exit_code, 0) << d.err;
    EXPECT_EQ(read_text(again + "/tracks.png"), read_text(run + "/tracks.png")) << args;
    EXPECT_EQ(read_text(again + "/gantt.png"), read_text(run + "/gantt.png")) << args;
    // In place: the pictures join the run's set, the rest untouched.
    const std::string events = read_text(run + "/events.jsonl");
    fs::remove(run + "/gantt.png");
    ASSERT_EQ(run_swath_fleet("render " + run + " --size 640x480").exit_code, 0);
    EXPECT_EQ(read_text(run + "/gantt.png"), read_text(again + "/gantt.png"));
    EXPECT_EQ(read_text(run + "/events.jsonl"), events);
  }
}

// swath-fleet tune (docs/swath-fleet.md) on case 1 with a small budget. weights.yaml reads back as
// summary.json's winner; tune.csv holds the defaults, reactive's weights (no forecast terms) and
// the halving's rungs (8 trials on the first tuning seed, 4 on the second); the winner has the
// smallest mean of the trials that ran both. Then an independent path: `swath-fleet run` with
// weights.yaml, GMF over the reactive runs of the history seeds and relief, on a world drawn
// with `worlds gen`, takes exactly held_out.csv's tuned time for that seed.
TEST(FleetCli, TuneKeepsTheBetterHalfAndRunReproducesItsHeldOutTime) {
  const std::string out = fresh_dir("fleet-tune");
  const std::string common = "road --drones 2 ";
  const CliRun tune = run_swath_fleet("tune " + common +
                                      "--world road --trials 8 --tuning-seeds 2 --held-out 2 "
                                      "--histories 2 --seed 3 -o " +
                                      out);
  ASSERT_EQ(tune.exit_code, 0) << tune.err;
  const json summary = json::parse(read_text(out + "/summary.json"));
  const fleet::Weights w = fleet::read_weights(out + "/weights.yaml");
  const json& win = summary["winner"]["weights"];
  EXPECT_EQ(w.coverage, win["coverage"].get<double>());
  EXPECT_EQ(w.fairness, win["fairness"].get<double>());
  EXPECT_EQ(w.avoid_zigzag, win["avoid_zigzag"].get<double>());
  EXPECT_EQ(w.commitment, win["commitment"].get<double>());
  EXPECT_EQ(w.speculative, win["speculative"].get<double>());
  EXPECT_EQ(w.avoid_mutual, win["avoid_mutual"].get<double>());

  const auto trials = csv_rows(read_text(out + "/tune.csv"));
  ASSERT_EQ(trials.size(), 9u);
  ASSERT_EQ(trials[0].size(), 9u);
  EXPECT_EQ(trials[0][7], "tuning_seeds");
  const fleet::Weights defaults;
  EXPECT_EQ(std::stod(trials[1][2]), defaults.fairness);
  EXPECT_EQ(std::stod(trials[1][5]), defaults.speculative);
  EXPECT_EQ(std::stod(trials[2][5]), 0.0);  // reactive's weights: no speculative,
  EXPECT_EQ(std::stod(trials[2][6]), 0.0);  // no avoid-mutual
  int on_both = 0;
  double best_s = 1e300;
  for (std::size_t i = 1; i < trials.size(); ++i)
    if (trials[i][7] == "2") ++on_both, best_s = std::min(best_s, std::stod(trials[i][8]));
  EXPECT_EQ(on_both, 4);
  const auto winner = summary["winner"]["trial"].get<std::size_t>();
  EXPECT_EQ(trials[winner + 1][7], "2");
  EXPECT_EQ(std::stod(trials[winner + 1][8]), best_s);

  // Seeds: histories 3, 4; tuning 5, 6; held out 7, 8.
  const auto held = csv_rows(read_text(out + "/held_out.csv"));
  ASSERT_EQ(held.size(), 3u);
  ASSERT_EQ(held[1][0], "7");
  std::string histories;
  for (int seed : {3, 4, 7}) {
    const CliRun gen = run_swath_fleet("worlds gen road --seed " + std::to_string(seed));
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    std::ofstream(out + "/road-" + std::to_string(seed) + ".yaml") << gen.out;
  }
  for (int seed : {3, 4}) {
    const std::string dir = out + "/history-" + std::to_string(seed);
    ASSERT_EQ(
        run_swath_fleet("run " + common + "--world " + out + "/road-" + std::to_string(seed) +
                        ".yaml --scheduler reactive --seed " + std::to_string(seed) + " -o " + dir)
            .exit_code,
        0);
    histories += " " + dir;
  }
  const std::string replay = out + "/replay";
  const CliRun run = run_swath_fleet("run " + common + "--world " + out + "/road-7.yaml --seed 7 " +
                                     "--weights " + out + "/weights.yaml --forecast gmf --relief " +
                                     "--history" + histories + " -o " + replay);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json replayed = json::parse(read_text(replay + "/summary.json"));
  EXPECT_NEAR(replayed["completion_time_s"].get<double>(), std::stod(held[1][3]), 1e-3);
}

// swath-fleet replay (docs/swath-fleet.md): a run's dtg.json played back in the run's own world
// with its fleet, scheduler and seed gives the run's events byte for byte; with another scheduler
// it gives what `run` with that scheduler gives (case 1's graph does not depend on the schedule).
// Refused, writing nothing: the wifi app (its cancels depend on the schedule) unless --force, a
// directory that is no run, runs of two versions.
TEST(FleetCli, ReplayOfARunIsTheRunAndRefusesWhatItCannotReplay) {
  const std::string dir = fresh_dir("fleet-replay");
  ASSERT_EQ(
      run_swath_fleet("run road --world road --drones 2 --seed 3 -o " + dir + "/road").exit_code,
      0);
  CliRun r = run_swath_fleet("replay " + dir + "/road -o " + dir + "/again");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("trace replay completed in"), std::string::npos) << r.out;
  EXPECT_EQ(read_text(dir + "/again/events.jsonl"), read_text(dir + "/road/events.jsonl"));
  EXPECT_EQ(read_text(dir + "/again/dtg.json"), read_text(dir + "/road/dtg.json"));
  const json summary = json::parse(read_text(dir + "/again/summary.json"));
  EXPECT_EQ(summary["completion_time_s"],
            json::parse(read_text(dir + "/road/summary.json"))["completion_time_s"]);
  EXPECT_EQ(summary["replay_of"].get<std::string>(),
            fs::path(dir + "/road").lexically_normal().string());

  // Another scheduler and fleet: the replay equals the app run that way; two runs at once go
  // into a directory each.
  ASSERT_EQ(run_swath_fleet("run road --world road --drones 3 --scheduler greedy --seed 3 -o " +
                            dir + "/greedy")
                .exit_code,
            0);
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 1 --seed 2 -o " + dir + "/hot")
                .exit_code,
            0);
  r = run_swath_fleet("replay " + dir + "/road " + dir + "/hot --scheduler greedy --drones 3 -o " +
                      dir + "/both");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir + "/both/road/events.jsonl"), read_text(dir + "/greedy/events.jsonl"));
  EXPECT_TRUE(fs::exists(dir + "/both/hot/events.jsonl"));

  // Refusals (exit 2, nothing written).
  ASSERT_EQ(run_swath_fleet("run wifi --world rf_field --drones 2 -o " + dir + "/wifi").exit_code,
            0);
  r = run_swath_fleet("replay " + dir + "/wifi -o " + dir + "/refused");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("wifi app (case 2) cancels"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one sentence
  r = run_swath_fleet("replay " + dir + "/road-nowhere -o " + dir + "/refused");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a run directory"), std::string::npos) << r.err;
  fs::create_directories(dir + "/empty");
  r = run_swath_fleet("replay " + dir + "/empty -o " + dir + "/refused");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no summary.json or dtg.json"), std::string::npos) << r.err;
  fs::copy(dir + "/hot", dir + "/old");
  std::string old = read_text(dir + "/old/summary.json");
  const std::size_t v = old.find("\"version\": \"");
  old.replace(v, old.find('"', v + 12) + 1 - v, "\"version\": \"0.0.9\"");
  std::ofstream(dir + "/old/summary.json", std::ios::trunc) << old;
  r = run_swath_fleet("replay " + dir + "/road " + dir + "/old -o " + dir + "/refused");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("made by swath-fleet 0.0.9"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/refused"));
  // Forced: the recorded cancels are replayed as recorded.
  r = run_swath_fleet("replay " + dir + "/wifi --force -o " + dir + "/forced");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(read_text(dir + "/forced/summary.json"))["tasks"],
            json::parse(read_text(dir + "/wifi/summary.json"))["tasks"]);
}

// tune ask / tell (docs/swath-fleet.md): the test plays the engine — runs every line ask prints
// with the real binary, tells the run directories back — until ask has nothing left; the
// weights.yaml, tune.csv, held_out.csv and summary.json are then tune's own for the same seed and
// settings. A state file is
// the same bytes for the same settings; another app's state, a run ask did not name and a
// directory that is no run are refused.
TEST(FleetCli, TuneAskTellEndsWithTunesWeights) {
  const std::string dir = fresh_dir("fleet-tune-ask");
  const std::string settings =
      "road --world road --drones 2 --trials 6 --tuning-seeds 2 --held-out 2 --histories 2 "
      "--seed 4 ";
  ASSERT_EQ(run_swath_fleet("tune " + settings + "-o " + dir + "/tune").exit_code, 0);
  const std::string state = dir + "/state.json";
  CliRun ask = run_swath_fleet("tune ask " + state + " " + settings + "-o " + dir + "/asked");
  ASSERT_EQ(ask.exit_code, 0) << ask.err;
  const std::string first_state = read_text(state);
  int rounds = 0, runs = 0;
  for (; !ask.out.empty() && rounds < 10; ++rounds) {
    std::istringstream lines(ask.out);
    std::string told;
    for (std::string line; std::getline(lines, line); ++runs) {
      std::ofstream(dir + "/job.sh", std::ios::trunc) << line << "\n";
      ASSERT_EQ(run_program("sh", dir + "/job.sh").exit_code, 0) << line;
      told += " " + line.substr(line.rfind(" -o ") + 4);
    }
    if (rounds == 1) {  // refusals mid-way change nothing
      CliRun bad = run_swath_fleet("tune tell " + state + " " + dir + "/nowhere");
      EXPECT_EQ(bad.exit_code, 2);
      EXPECT_NE(bad.err.find("not a run directory"), std::string::npos) << bad.err;
      bad = run_swath_fleet("tune tell " + state + " " + dir + "/tune");
      EXPECT_EQ(bad.exit_code, 2);
      bad = run_swath_fleet("tune ask " + state + " hotspot --world hotspot");
      EXPECT_EQ(bad.exit_code, 2);
      EXPECT_NE(bad.err.find("tuning of road, not of hotspot"), std::string::npos) << bad.err;
    }
    const CliRun tell = run_swath_fleet("tune tell " + state + told);
    ASSERT_EQ(tell.exit_code, 0) << tell.err;
    ask = run_swath_fleet("tune ask " + state);
    ASSERT_EQ(ask.exit_code, 0) << ask.err;
  }
  EXPECT_EQ(rounds, 4);  // histories, two rungs, then the held-out runs
  // 2 histories, 6 trials, the better half of them, 2 held-out seeds x (reactive, the defaults,
  // the winner)
  EXPECT_EQ(runs, 2 + 6 + 3 + 2 * 3);
  EXPECT_EQ(read_text(dir + "/asked/weights.yaml"), read_text(dir + "/tune/weights.yaml"));
  EXPECT_EQ(read_text(dir + "/asked/tune.csv"), read_text(dir + "/tune/tune.csv"));
  EXPECT_EQ(read_text(dir + "/asked/held_out.csv"), read_text(dir + "/tune/held_out.csv"));
  EXPECT_EQ(read_text(dir + "/asked/summary.json"), read_text(dir + "/tune/summary.json"));
  const std::string held_out = read_text(dir + "/asked/held_out.csv");
  EXPECT_EQ(std::count(held_out.begin(), held_out.end(), '\n'), 3);  // header and 2 seeds
  ASSERT_FALSE(read_text(dir + "/asked/weights.yaml").empty());
  // Same settings, same state bytes.
  fs::remove(state);
  ASSERT_EQ(
      run_swath_fleet("tune ask " + state + " " + settings + "-o " + dir + "/asked").exit_code, 0);
  EXPECT_EQ(read_text(state), first_state);
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// The smallest picture --size accepts: the Gantt chart's time axis is then narrower than nothing
// (150 px of names and margins); its tick step must still be found (it was an endless loop).
TEST(FleetCli, SmallestPicturesAreDrawn) {
  const std::string run = fresh_dir("fleet-render-small");
  const CliRun r =
      run_swath_fleet("run static --world static --drones 1 --render --size 64x64 -o " + run);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // PNG width and height (bytes 16 to 23): tracks.png 64 x 64, gantt.png 64 wide and at least
  // 200 px tall (one third of the height, 200 at least).
  const std::string tracks = read_text(run + "/tracks.png"), gantt = read_text(run + "/gantt.png");
  ASSERT_GT(tracks.size(), 24u);
  ASSERT_GT(gantt.size(), 24u);
  EXPECT_EQ(tracks.substr(16, 8), std::string("\0\0\0\x40\0\0\0\x40", 8));
  EXPECT_EQ(gantt.substr(16, 8), std::string("\0\0\0\x40\0\0\0\xc8", 8));
}

}  // namespace
}  // namespace swath::test

// swath-fleet's statistics read back from its own files: compare keeps every seed's pair when
// runs hit the time limit, counts them censored and gives the Kaplan–Meier median (checked against
// Efron's redistribute-to-the-right, a second method); sweep's lines vary the world with the seed
// and name absolute paths; tracks.geojson's times are the log's; bounded inputs are refused in
// one sentence.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "fleet_images.hpp"
#include "intervals.hpp"
#include "swath/fleet/event_replay.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::test {
namespace {

using apps::TimeObservation;
using nlohmann::json;
namespace fs = std::filesystem;

// Efron's redistribute-to-the-right: every run starts with mass 1/n; going up in time (
// completions before censorings at a tie), a censored run hands its mass in equal parts to every
// run after it. The median is the first completion at which the completed mass reaches 1/2.
// Equal to Kaplan–Meier by theorem, computed without its product.
std::optional<double> brute_median(std::vector<TimeObservation> runs) {
  std::sort(runs.begin(), runs.end(), [](const TimeObservation& a, const TimeObservation& b) {
    return a.time_s != b.time_s ? a.time_s < b.time_s : a.completed > b.completed;
  });
  std::vector<double> mass(runs.size(), 1.0 / static_cast<double>(runs.size()));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (runs[i].completed || i + 1 == runs.size()) continue;
    const double share = mass[i] / static_cast<double>(runs.size() - i - 1);
    for (std::size_t j = i + 1; j < runs.size(); ++j) mass[j] += share;
    mass[i] = 0;
  }
  double done = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!runs[i].completed) continue;
    done += mass[i];
    if (done >= 0.5 - 1e-12) return runs[i].time_s;
  }
  return std::nullopt;
}

TEST(FleetStats, KaplanMeierMedianIsEfronsRedistributeToTheRight) {
  std::mt19937_64 rng(47);
  int defined = 0, undefined = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 25);
    std::vector<TimeObservation> runs;
    for (int i = 0; i < n; ++i) {
      // Whole seconds on a small range: ties between completions and censorings are common.
      const double t = static_cast<double>(10 + rng() % 20);
      const double limit = static_cast<double>(12 + rng() % 20);
      runs.push_back(t <= limit ? TimeObservation{t, true} : TimeObservation{limit, false});
    }
    const auto km = apps::kaplan_meier_median_s(runs);
    const auto brute = brute_median(runs);
    ASSERT_EQ(km.has_value(), brute.has_value()) << trial;
    if (km) {
      EXPECT_EQ(*km, *brute) << trial;
      ++defined;
    } else {
      ++undefined;
    }
  }
  EXPECT_GT(defined, 500);  // both kinds of answer were exercised
  EXPECT_GT(undefined, 20);
  // Without censoring: the lower median of the sorted times.
  EXPECT_EQ(*apps::kaplan_meier_median_s({{4, true}, {1, true}, {3, true}, {2, true}}), 2.0);
}

// A pair's sign, when pair_runs says it is known, is the sign of the true difference.
TEST(FleetStats, PairedSignsAgreeWithTheUncensoredTimes) {
  std::mt19937_64 rng(48);
  int known = 0, unknown = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const double a = static_cast<double>(rng() % 100), b = static_cast<double>(rng() % 100);
    const double limit_a = static_cast<double>(rng() % 120),
                 limit_b = static_cast<double>(rng() % 120);
    const TimeObservation first =
        a <= limit_a ? TimeObservation{a, true} : TimeObservation{limit_a, false};
    const TimeObservation other =
        b <= limit_b ? TimeObservation{b, true} : TimeObservation{limit_b, false};
    const apps::PairedRuns p = apps::pair_runs(first, other);
    if (!p.known) {
      ++unknown;
      EXPECT_FALSE(first.completed && other.completed);
      continue;
    }
    ++known;
    EXPECT_EQ(p.sign, (b > a) - (b < a)) << a << " " << limit_a << " " << b << " " << limit_b;
    EXPECT_EQ(p.relative_change.has_value(), first.completed && other.completed);
  }
  EXPECT_GT(known, 1000);
  EXPECT_GT(unknown, 100);
}

struct CompareRow {
  std::string scheduler;
  std::uint64_t seed = 0;
  bool completed = false;
  double time_s = 0;  ///< completion, or where it was censored
};

// A CSV file's cells, empty cells kept (a line ending in a comma has an empty last cell).
std::vector<std::vector<std::string>> csv_cells(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    rows.emplace_back();
    std::size_t start = 0;
    for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
      rows.back().push_back(line.substr(start, comma - start));
    rows.back().push_back(line.substr(start));
  }
  return rows;
}

std::vector<CompareRow> compare_rows(const std::string& path) {
  const auto rows = csv_cells(read_text(path));
  EXPECT_EQ(rows.at(0), (std::vector<std::string>{"scheduler", "seed", "completed",
                                                  "completion_time_s", "censored_at_s"}));
  std::vector<CompareRow> out;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& r = rows[i];
    EXPECT_EQ(r.size(), 5u);
    CompareRow c{r[0], std::stoull(r[1]), r[2] == "true", 0};
    c.time_s = std::stod(c.completed ? r[3] : r[4]);
    EXPECT_TRUE(c.completed ? r[4].empty() : r[3].empty()) << i;
    out.push_back(c);
  }
  return out;
}

// The time limit between the runs' completion times: some time out. Each seed's pair is still
// reported (by seed), the censored counted, and the median is Kaplan–Meier's of the rows.
TEST(FleetStats, CompareKeepsEveryPairBySeedWhenRunsHitTheTimeLimit) {
  const std::string out = fresh_dir("fleet-compare-censored");
  const CliRun run = run_swath_fleet(
      "compare multiplexing --world sites --seeds 6 --schedulers reactive,round-robin --max-time "
      "170 "
      "-o " +
      out);
  ASSERT_EQ(run.exit_code, 4) << run.err;  // some did not complete
  const std::vector<CompareRow> rows = compare_rows(out + "/compare.csv");
  ASSERT_EQ(rows.size(), 12u);
  std::map<std::string, std::map<std::uint64_t, CompareRow>> by;
  std::map<std::string, int> censored;
  for (const CompareRow& r : rows) {
    by[r.scheduler][r.seed] = r;
    if (!r.completed) {
      ++censored[r.scheduler];
      EXPECT_NEAR(r.time_s, 170.0, 1.0);  // censored at the time limit
    }
  }
  ASSERT_GT(censored["reactive"] + censored["round-robin"], 0) << "no run hit the limit: raise it";
  ASSERT_LT(censored["reactive"] + censored["round-robin"], 12) << "every run hit the limit";
  const json summary = json::parse(read_text(out + "/summary.json"));
  for (const auto& s : summary["schedulers"]) {
    const std::string name = s["scheduler"];
    EXPECT_EQ(s["censored"].get<int>(), censored[name]) << name;
    EXPECT_EQ(s["completed"].get<int>(), 6 - censored[name]) << name;
    std::vector<TimeObservation> obs;
    for (const auto& [seed, r] : by[name]) obs.push_back({r.time_s, r.completed});
    const auto median = brute_median(obs);
    if (median)
      EXPECT_NEAR(s["completion_time_s_km_median"].get<double>(), *median, 1e-3) << name;
    else
      EXPECT_TRUE(s["completion_time_s_km_median"].is_null()) << name;
  }
  EXPECT_NE(run.out.find("censored"), std::string::npos) << run.out;
  ASSERT_EQ(summary["paired"].size(), 1u);
  const json& p = summary["paired"][0];
  ASSERT_EQ(p["per_seed"].size(), 6u);  // never dropped
  int both = 0;
  for (const auto& s : p["per_seed"]) {
    const CompareRow& a = by["reactive"].at(s["seed"].get<std::uint64_t>());
    const CompareRow& b = by["round-robin"].at(s["seed"].get<std::uint64_t>());
    std::string sign = "unknown";
    if (a.completed && b.completed) {
      ++both;
      sign = b.time_s < a.time_s ? "faster" : b.time_s > a.time_s ? "slower" : "equal";
      EXPECT_NEAR(s["relative_change"].get<double>(), b.time_s / a.time_s - 1, 1e-4);
    } else if (a.completed && b.time_s >= a.time_s) {
      sign = "slower";
    } else if (b.completed && a.time_s >= b.time_s) {
      sign = "faster";
    }
    EXPECT_EQ(s["sign"], sign) << s.dump();
  }
  EXPECT_EQ(p["both_completed"].get<int>(), both);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The value after `flag` in a command line ("" when absent); every value after `flag` for a list.
std::vector<std::string> values_after(const std::string& line, const std::string& flag) {
  std::vector<std::string> words, out;
  std::istringstream in(line);
  for (std::string w; in >> w;) words.push_back(w);
  for (std::size_t i = 0; i + 1 < words.size(); ++i)
    if (words[i] == flag) out.push_back(words[i + 1]);
  return out;
}

// swath-fleet run from `dir` (relative paths on its command line are relative to it).
CliRun run_fleet_in(const std::string& dir, const std::string& args) {
  return run_program("/bin/sh",
                     "-c \"cd '" + dir + "' && '" + SWATH_FLEET_BINARY + "' " + args + "\"");
}

TEST(FleetStats, SweepLinesVaryTheWorldWithTheSeedAndNameAbsolutePaths) {
  const std::string dir = fresh_dir("fleet-sweep-seeds");
  fs::create_directories(dir);
  std::ofstream(dir + "/spec.yaml") << "app: road\nworld: road\ndrones: 2\n"
                                    << "schedulers: [reactive, predictive]\n"
                                    << "seeds: {from: 3, to: 6}\nhistories: 2\n";
  // Run from the spec's folder with a relative --runs: the lines still name absolute paths.
  const CliRun all = run_fleet_in(dir, "sweep spec.yaml --runs runs");
  EXPECT_EQ(all.exit_code, 2);
  EXPECT_NE(all.err.find("--part histories"), std::string::npos) << all.err;
  const CliRun histories = run_fleet_in(dir, "sweep spec.yaml --runs runs --part histories");
  ASSERT_EQ(histories.exit_code, 0) << histories.err;
  const CliRun runs = run_fleet_in(dir, "sweep spec.yaml --runs runs --part runs");
  ASSERT_EQ(runs.exit_code, 0) << runs.err;
  const auto history_lines = lines_of(histories.out), run_lines = lines_of(runs.out);
  ASSERT_EQ(history_lines.size(), 4u);
  ASSERT_EQ(run_lines.size(), 4u);
  const std::string runs_dir = fs::canonical(dir).string() + "/runs";
  std::vector<std::string> history_dirs;
  for (const std::string& line : history_lines) {
    const auto seed = values_after(line, "--seed"), world_seed = values_after(line, "--world-seed");
    ASSERT_EQ(seed.size(), 1u) << line;
    ASSERT_EQ(world_seed, seed) << line;  // the world drawn from the run's seed
    EXPECT_EQ(values_after(line, "--scheduler"), std::vector<std::string>{"reactive"});
    const auto o = values_after(line, "-o");
    ASSERT_EQ(o.size(), 1u);
    EXPECT_EQ(o[0], runs_dir + "/road-reactive-seed" + seed[0]) << line;
    history_dirs.push_back(o[0]);
  }
  std::set<std::string> world_seeds;
  for (const std::string& line : run_lines) {
    const auto seed = values_after(line, "--seed");
    ASSERT_EQ(values_after(line, "--world-seed"), seed) << line;
    world_seeds.insert(seed.at(0));
    EXPECT_EQ(values_after(line, "-o").at(0), runs_dir + "/road-predictive-seed" + seed[0]);
    const auto h = values_after(line, "--history");
    ASSERT_EQ(h.size(), 2u) << line;
    for (const std::string& d : h) {
      EXPECT_EQ(d[0], '/') << d;
      EXPECT_NE(std::find(history_dirs.begin(), history_dirs.end(), d), history_dirs.end()) << d;
      EXPECT_NE(d, runs_dir + "/road-reactive-seed" + seed[0]) << "its own seed: " << line;
    }
    EXPECT_NE(line.find("--forecast gmf"), std::string::npos);
    EXPECT_NE(line.find("--relief"), std::string::npos);
  }
  EXPECT_EQ(world_seeds.size(), 4u);

  // A second method: the two parts run in order and collected give compare's own table (compare's
  // predictive learns from the same reactive runs of the next seeds).
  std::ofstream(dir + "/histories.txt") << histories.out;
  std::ofstream(dir + "/runs.txt") << runs.out;
  ASSERT_EQ(run_program("/bin/sh", dir + "/histories.txt").exit_code, 0);
  ASSERT_EQ(run_program("/bin/sh", dir + "/runs.txt").exit_code, 0);
  const CliRun collect = run_swath_fleet("collect " + dir + "/runs/* -o " + dir + "/table");
  ASSERT_EQ(collect.exit_code, 0) << collect.err;
  const CliRun compare = run_swath_fleet(
      "compare road --world road --drones 2 --seed 3 --seeds 4 --histories 2 "
      "--schedulers reactive,predictive -o " +
      dir + "/compare");
  ASSERT_EQ(compare.exit_code, 0) << compare.err;
  std::map<std::string, std::string> swept, compared;  // "scheduler seed": completion time
  for (const auto& r : csv_cells(read_text(dir + "/table/collect.csv")))
    if (r.at(0) != "run") swept[r.at(2) + " " + r.at(3)] = r.at(5);
  for (const auto& r : csv_cells(read_text(dir + "/compare/compare.csv")))
    if (r.at(0) != "scheduler") compared[r.at(0) + " " + r.at(1)] = r.at(3);
  EXPECT_EQ(swept.size(), 8u);
  EXPECT_EQ(swept, compared);
}

// tracks.geojson's times_s: one per vertex, never going back, and each vertex where the log's
// drone_state (t_s) or drone_mode (at_s) put that drone at that time.
TEST(FleetStats, TrackTimesAreTheLogsPositions) {
  const std::string out = fresh_dir("fleet-track-times");
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 2 -o " + out).exit_code, 0);
  std::map<int, std::vector<std::array<double, 3>>> logged;  // drone: t, x, y
  std::istringstream log(read_text(out + "/events.jsonl"));
  for (std::string line; std::getline(log, line);) {
    const json e = json::parse(line);
    if (e["ev"] == "drone_state")
      logged[e["drone"]].push_back(
          {e["t_s"].get<double>(), e["x_m"].get<double>(), e["y_m"].get<double>()});
    if (e["ev"] == "drone_mode")
      logged[e["drone"]].push_back(
          {e["at_s"].get<double>(), e["x_m"].get<double>(), e["y_m"].get<double>()});
  }
  const json tracks = json::parse(read_text(out + "/tracks.geojson"));
  const auto world = worlds::read_world(source_path("share/worlds/hotspot.yaml"));
  const geometry::LocalFrame frame(world->origin);
  int drone = 0;
  for (const auto& f : tracks["features"]) {
    if (f["properties"]["role"] != "track") continue;
    const auto& coords = f["geometry"]["coordinates"];
    const auto& times = f["properties"]["times_s"];
    const auto& want = logged[drone++];
    ASSERT_EQ(times.size(), coords.size());
    ASSERT_EQ(times.size(), want.size());
    ASSERT_GT(times.size(), 10u);
    for (std::size_t i = 0; i < times.size(); ++i) {
      if (i > 0) EXPECT_GE(times[i].get<double>(), times[i - 1].get<double>()) << i;
      EXPECT_NEAR(times[i].get<double>(), want[i][0], 1e-6) << i;
      const geometry::Point2 p =
          frame.to_local({coords[i][1].get<double>(), coords[i][0].get<double>(), 0});
      EXPECT_NEAR(p.x, want[i][1], 0.05) << i;
      EXPECT_NEAR(p.y, want[i][2], 0.05) << i;
    }
  }
  EXPECT_EQ(drone, 2);
}

// A log line longer than 1 MiB (here a run_start declaring 200,000 drones) is refused before it
// is parsed: exit 2, one sentence, for check and for render.
TEST(FleetStats, CheckAndRenderRefuseAnEventLongerThanOneMiB) {
  const std::string dir = fresh_dir("fleet-long-event");
  fs::create_directories(dir);
  {
    std::ofstream log(dir + "/events.jsonl");
    log << R"({"ev":"run_start","t_s":0,"max_time_s":10,"drones":[)";
    for (int i = 0; i < 200000; ++i) log << (i ? "," : "") << R"({"drone":)" << i << "}";
    log << "]}\n"
        << R"({"ev":"run_end","t_s":1})"
        << "\n";
  }
  const CliRun check = run_swath_fleet("check " + dir);
  EXPECT_EQ(check.exit_code, 2) << check.out;
  EXPECT_NE(check.err.find("events.jsonl: line 1: an event of"), std::string::npos) << check.err;
  EXPECT_NE(check.err.find("at most 1 MiB"), std::string::npos) << check.err;
  EXPECT_EQ(check.out, "");
  const CliRun render = run_swath_fleet("render " + dir + " -o " + dir + "/pictures");
  EXPECT_EQ(render.exit_code, 2);
  EXPECT_NE(render.err.find("line 1: an event of"), std::string::npos) << render.err;
  EXPECT_FALSE(fs::exists(dir + "/pictures"));
}

// Energies each finite that add up beyond a double: collect refuses instead of writing inf.
TEST(FleetStats, CollectRefusesSumsThatAreNotFinite) {
  const std::string dir = fresh_dir("fleet-collect-inf");
  ASSERT_EQ(run_swath_fleet("run hotspot --world hotspot --drones 2 -o " + dir + "/run").exit_code,
            0);
  json summary = json::parse(read_text(dir + "/run/summary.json"));
  for (auto& d : summary["drones"]) d["energy_wh"] = 1.5e308;
  std::ofstream(dir + "/run/summary.json") << summary.dump(2) << "\n";
  const CliRun collect = run_swath_fleet("collect " + dir + "/run -o " + dir + "/table");
  EXPECT_EQ(collect.exit_code, 2);
  EXPECT_NE(collect.err.find("add up to more than a finite number"), std::string::npos)
      << collect.err;
  EXPECT_FALSE(fs::exists(dir + "/table"));
}

// Every field of a tune state is checked with tune's ranges before it is used.
TEST(FleetStats, TuneStateFieldsOutOfRangeAreRefusedInOneSentence) {
  const json good =
      json::parse(read_text(source_path("tests/bad-input/fleet/tune-state-histories.json")));
  const std::string dir = fresh_dir("fleet-tune-state");
  fs::create_directories(dir);
  struct Edit {
    std::string key;
    json value;
    std::string fragment;
  };
  const std::vector<Edit> edits{
      {"histories", 5, ""},  // the fixture made valid: ask then prints its lines
      {"histories", 1e9, "histories must be a whole number from 1 to 1000"},
      {"histories", 2.5, "histories must be a whole number"},
      {"phase", "polishing", "phase \"polishing\" is none of"},
      {"rung", 3, "rung must be a whole number from 0 to 2"},
      {"alive", json::array({1, 1}), "alive names trial 1 twice"},
      {"alive", json::array({2}), "alive must be a whole number from 0 to 1"},
      {"max_time_s", 0, "max_time_s must be a number from 1 to 604800"},
      {"seed", -1, "seed must be a whole number from 0 to 9007199254740991"},
      {"trials", json::array({json::object()}), "trials must be a list of 2 to 4096"},
      {"times_s", json::array({json::array({-1}), json::array()}), "times_s must be a number"},
      {"told", json::object({{"/x", "soon"}}), "told[/x] must be a number"},
      {"drones", 1000, "drones must be a whole number from 0 to 100"},
      {"program", 7, "program must be a non-empty string"},
  };
  for (const Edit& e : edits) {
    json st = good;
    if (e.fragment.empty() || e.key != "histories") st["histories"] = 5;
    st[e.key] = e.value;
    std::ofstream(dir + "/state.json") << st.dump() << "\n";
    const CliRun ask = run_swath_fleet("tune ask " + dir + "/state.json");
    if (e.fragment.empty()) {
      EXPECT_EQ(ask.exit_code, 0) << ask.err;
      EXPECT_EQ(lines_of(ask.out).size(), 5u) << ask.out;  // one per history run
      continue;
    }
    EXPECT_EQ(ask.exit_code, 2) << e.key << ": " << ask.out;
    EXPECT_NE(ask.err.find("state.json: " + e.fragment), std::string::npos) << ask.err;
    EXPECT_EQ(ask.out, "");
  }
}

// tracks.png's legend: each drone's name beside a swatch of its track's colour, inside the picture.
TEST(FleetStats, TracksLegendNamesEachDroneInItsColour) {
  const std::string out = fresh_dir("fleet-tracks-legend");
  ASSERT_EQ(run_swath_fleet(
                "run tracking --world tracking --fleet share/fleets/tracking-pair.yaml -o " + out)
                .exit_code,
            0);
  const fleet::RunRecord r =
      fleet::replay_record(read_text(out + "/events.jsonl"), out + "/events.jsonl");
  const auto world = worlds::read_world(source_path("share/worlds/tracking.yaml"));
  for (const auto& [width_px, height_px] : {std::pair{1000, 700}, std::pair{500, 400}}) {
    const apps::FleetPicture p = apps::tracks_picture(*world, r, width_px, height_px);
    ASSERT_EQ(r.drones.size(), 2u);
    for (std::size_t i = 0; i < r.drones.size(); ++i) {
      const auto label =
          std::find_if(p.scene.labels.begin(), p.scene.labels.end(),
                       [&](const render::Label& l) { return l.text == r.drones[i].name; });
      ASSERT_NE(label, p.scene.labels.end()) << r.drones[i].name;
      EXPECT_GE(label->x_px, 0);
      EXPECT_LE(label->y_px, height_px);
      EXPECT_GE(label->y_px - label->height_px, 0);
      // Its swatch: a short screen line of the drone's colour, left of the name, on its row.
      const render::Color c = apps::drone_color(i);
      bool swatch = false;
      for (const render::Polyline& line : p.scene.screen_polylines) {
        if (line.color.r != c.r || line.color.g != c.g || line.color.b != c.b) continue;
        for (const auto& q : line.points)
          swatch |= q.x < label->x_px && q.x > label->x_px - 60 &&
                    std::abs(q.y - (label->y_px - label->height_px / 2)) < label->height_px;
      }
      EXPECT_TRUE(swatch) << r.drones[i].name << " at " << width_px;
    }
  }
}

}  // namespace
}  // namespace swath::test

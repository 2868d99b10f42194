// swath-control run as a user runs it: swath's own plan flown in wind and checked against the
// plan's area, the files parsed back, the exit codes of docs/swath-control.md, the same bytes for
// the same seed, and the picture's pixels where the start and the no-fly zone are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "control_images.hpp"
#include "swath/control/mission.hpp"
#include "swath/render/image.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

std::vector<std::vector<double>> numeric_csv_rows(const std::string& text, std::size_t* columns) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  *columns = static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// The yard (120 m x 110 m) planned with swath at 60 m: a two-minute flight.
const std::string& yard_plan() {
  static const std::string dir = [] {
    const std::string d = fresh_dir("control-yard-plan");
    const CliRun plan = run_swath(
        "plan share/fields/yard-local.csv --local --origin 47.4,8.5 --camera dji-phantom-4-pro "
        "--altitude 60 -o " +
        d);
    EXPECT_EQ(plan.exit_code, 0) << plan.err;
    return d;
  }();
  return dir;
}

TEST(ControlCli, SwathsPlanIsFlownInWindAndItsFilesAgree) {
  const std::string out = fresh_dir("control-yard-run");
  const CliRun run =
      run_swath_control("run " + yard_plan() + "/mission.geojson --environment lab -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["status"], "completed");
  EXPECT_EQ(s["inputs"]["speed_m_s"], 5.0);  // the plan's cruise speed
  // Lines at 5 m/s in LAB's light wind: within 2 m of the path everywhere.
  EXPECT_LT(s["tracking"]["cross_track_max_m"].get<double>(), 2.0);
  ASSERT_TRUE(s.contains("plan_check"));
  EXPECT_EQ(s["plan_check"]["inside_no_fly_m"], 0.0);
  // The timeseries: one row per 20 ms, each as wide as the header; its last SoC is the summary's.
  std::size_t columns = 0;
  const auto rows = numeric_csv_rows(read_text(out + "/timeseries.csv"), &columns);
  EXPECT_EQ(columns, 23u + 4 + 4 + 5);  // 4 rotors: pwm and omega
  const double t = s["flight_time_s"].get<double>();
  EXPECT_NEAR(static_cast<double>(rows.size()), t / 0.02, 1.0);
  for (const auto& r : rows) ASSERT_EQ(r.size(), columns);
  EXPECT_NEAR(rows.back()[columns - 2], s["energy"]["final_soc"].get<double>(), 2e-3);
  // The track's length from the rows against the summary's distance (1 ms steps there).
  double length = 0;
  for (std::size_t k = 1; k < rows.size(); ++k)
    length += std::hypot(rows[k][1] - rows[k - 1][1], rows[k][2] - rows[k - 1][2],
                         rows[k][3] - rows[k - 1][3]);
  EXPECT_NEAR(length, s["distance_m"].get<double>(), 0.02 * length);
  // rate.csv: a row per second, 400 time-triggered executions in each whole one.
  const auto seconds = numeric_csv_rows(read_text(out + "/rate.csv"), &columns);
  ASSERT_GE(seconds.size(), static_cast<std::size_t>(t));
  for (std::size_t k = 0; k + 1 < seconds.size(); ++k) EXPECT_EQ(seconds[k][1], 400) << k;
  for (const char* png : {"trajectory.png", "attitude.png", "energy.png", "triggers.png"}) {
    const render::Image image = render::decode_png(read_text(out + "/" + png));
    EXPECT_EQ(image.width, 1200);
    EXPECT_EQ(image.height, 900);
  }
}

// A flight stopped before its first logged row (20 ms) still draws every panel of its pictures:
// each says it has no samples, none is blank.
TEST(ControlCli, AFlightStoppedAtOnceDrawsPanelsThatSayTheyHaveNoSamples) {
  const std::string out = fresh_dir("control-stopped");
  const CliRun run =
      run_swath_control("run random:4@30x30 --max-time 0.001 --size 600x450 -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* png : {"attitude.png", "energy.png"}) {
    const render::Image image = render::decode_png(read_text(out + "/" + png));
    ASSERT_EQ(image.height, 450);
    const int panels = std::string(png) == "attitude.png" ? 3 : 2;
    for (int k = 0; k < panels; ++k) {
      int ink = 0;  // dark pixels of the panel's title and note
      for (int y = k * 450 / panels; y < (k + 1) * 450 / panels; ++y)
        for (int x = 0; x < 600; ++x)
          if (image.at(x, y, 0) < 128) ++ink;
      EXPECT_GT(ink, 100) << png << " panel " << k;
    }
  }
}

TEST(ControlCli, AReactiveFlightWritesItsFitsAndTheRaster) {
  const std::string out = fresh_dir("control-reactive");
  const CliRun run = run_swath_control(
      "run random:4@30x30 --scheduler reactive --environment rugby --max-time 12 --set "
      "scheduler.reactive.boot_s=5 --set scheduler.run.metrics_from_s=5 --raster-at 8 "
      "--size 600x450 --log-executions -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  // fits.csv: a row per sensor and refit, as many as summary.json counts.
  std::int64_t refits = 0;
  for (const auto& [sensor, t] : s["triggers"].items()) refits += t["refits"].get<std::int64_t>();
  const std::string fits = read_text(out + "/fits.csv");
  EXPECT_EQ(fits.rfind("t_s,sensor,n,beta1,beta2,threshold,method\n", 0), 0u);
  EXPECT_EQ(static_cast<std::int64_t>(std::count(fits.begin(), fits.end(), '\n')) - 1, refits);
  EXPECT_GE(refits, 5 * 5);  // five sensors, a refit a second from 5 s to 12 s
  // executions.csv: a row per execution; those that ended after metrics_from are the summary's.
  std::istringstream ex(read_text(out + "/executions.csv"));
  std::string line;
  std::getline(ex, line);
  EXPECT_EQ(std::count(line.begin(), line.end(), ','), 7 + 5);
  std::int64_t counted = 0, false_positives = 0;
  while (std::getline(ex, line)) {
    std::vector<std::string> cells;
    std::istringstream c(line);
    std::string cell;
    while (std::getline(c, cell, ',')) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 13u) << line;
    EXPECT_LE(std::stod(cells[0]), std::stod(cells[1]));  // requested, then started, then ended
    EXPECT_LT(std::stod(cells[1]), std::stod(cells[2]));
    if (std::stod(cells[2]) >= 5.0) ++counted;
    false_positives += cells[6] == "1" ? 1 : 0;
  }
  EXPECT_EQ(counted, s["executions"]["total"].get<std::int64_t>());
  EXPECT_EQ(false_positives, s["feedback"]["false_positives"].get<std::int64_t>());
  // triggers.png: the raster's rows hold ticks (dark blue) where executions happened.
  const render::Image image = render::decode_png(read_text(out + "/triggers.png"));
  int blue = 0;
  for (int y = 450 / 2 + 40; y < 450 - 40; ++y)
    for (int x = 220; x < 560; ++x)
      if (image.at(x, y, 2) > 150 && image.at(x, y, 0) < 100) ++blue;
  EXPECT_GT(blue, 1000);
}

TEST(ControlCli, TheSameSeedWritesTheSameBytes) {
  const std::string a = fresh_dir("control-same-a"), b = fresh_dir("control-same-b");
  const std::string args = "run random:4@30x30 --environment arch --seed 3 --size 400x300 -o ";
  ASSERT_EQ(run_swath_control(args + a).exit_code, 0);
  ASSERT_EQ(run_swath_control(args + b).exit_code, 0);
  for (const char* f : {"timeseries.csv", "rate.csv", "fits.csv", "summary.json", "trajectory.png",
                        "attitude.png", "energy.png", "triggers.png"})
    EXPECT_EQ(read_text(a + "/" + f), read_text(b + "/" + f)) << f;
  const std::string c = fresh_dir("control-same-c");
  ASSERT_EQ(
      run_swath_control("run random:4@30x30 --environment arch --seed 4 --size 400x300 -o " + c)
          .exit_code,
      0);
  EXPECT_NE(read_text(a + "/timeseries.csv"), read_text(c + "/timeseries.csv"));
}

TEST(ControlCli, ExitCodesSayHowTheFlightEnded) {
  // 5: lost control; the files are still written. (No pictures: the exit code is the point.)
  std::string out = fresh_dir("control-lost");
  CliRun run = run_swath_control(
      "run random:3@20x20 --environment arch --set vehicle.controller.limits.max_tilt_deg=0.5 "
      "--set vehicle.controller.limits.crash_tilt_deg=1 --no-pictures -o " +
      out);
  EXPECT_EQ(run.exit_code, 5) << run.err;
  EXPECT_EQ(json::parse(read_text(out + "/summary.json"))["status"], "lost_control");
  // 4: the battery ran empty before the end.
  out = fresh_dir("control-empty");
  run = run_swath_control(
      "run random:3@20x20 --set vehicle.battery.capacity_ah=0.002 --no-pictures -o " + out);
  EXPECT_EQ(run.exit_code, 4) << run.err;
  EXPECT_EQ(json::parse(read_text(out + "/summary.json"))["status"], "battery_empty");
}

TEST(ControlCli, BadInputIsOneSentenceExitTwoAndNoFiles) {
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases{
      {"random:1@20x20", "random:N@WxH"},
      {"random:8@20x20 --vehicle nosuch", "bundled: "},
      {"random:8@20x20 --set vehicle.controller.nosuch=1", "nosuch"},
      {"random:8@20x20 --set wind=3", "FILE.KEY=VALUE"},
      {"random:8@20x20 --scheduler reactive --set scheduler.reactive.p_run=1.5", "p_run"},
      {"random:8@20x20 --set scheduler.rate_hz=0", "rate_hz"},
      {"random:8@20x20 --environment storm", "environment"},
      {"random:8@20x20 --speed 0.0", "--speed"},
      {"random:8@20x20 --max-time 1e9", "--max-time"},
      {"share/fields/meadow.geojson", "meadow.geojson"},
      {yard_plan() + "/mission.geojson --drone 7", "no drone \"7\""},
  };
  for (const Case& c : cases) {
    const std::string out = fresh_dir("control-bad");
    fs::remove_all(out);
    const CliRun run = run_swath_control("run " + c.args + " -o " + out);
    EXPECT_EQ(run.exit_code, 2) << c.args << ": " << run.err;
    EXPECT_NE(run.err.find(c.says), std::string::npos) << c.args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

TEST(ControlCli, CompareIsPairedByteIdenticalForAnyJobsAndAgreesWithItsRuns) {
  const std::string one = fresh_dir("control-compare-1"), two = fresh_dir("control-compare-2");
  // Under the sanitizers one environment (the flights are 5-15x slower there; the pairing and the
  // --jobs identity do not depend on how many environments are compared).
#ifdef SWATH_SANITIZED
  const std::size_t environments = 1;
  const std::string args = "compare paper --quick --environments lab --tt-rates 200 -o ";
#else
  const std::size_t environments = 2;
  const std::string args = "compare paper --quick --environments lab,arch --tt-rates 200 -o ";
#endif
  CliRun run = run_swath_control(args + one + " --jobs 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_EQ(run_swath_control(args + two + " --jobs 2").exit_code, 0);
  for (const char* f :
       {"runs.csv", "comparison.json", "comparison.md", "improvement.png", "rate.png"})
    EXPECT_EQ(read_text(one + "/" + f), read_text(two + "/" + f)) << f;
  EXPECT_EQ(render::decode_png(read_text(one + "/improvement.png")).height, 1200);
  // Environments x 3 modes (tt-400, reactive, tt-200) x 2 seeds.
  std::istringstream in(read_text(one + "/runs.csv"));
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream c(line);
    std::string cell;
    while (std::getline(c, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), environments * 6);
  // The reactive mode's attitude improvement in the lab, recomputed from runs.csv's pairs.
  double sum = 0;
  for (int seed = 0; seed < 2; ++seed) {
    const double b = std::stod(rows[static_cast<std::size_t>(seed)][6]);
    const double m = std::stod(rows[static_cast<std::size_t>(2 + seed)][6]);
    EXPECT_EQ(rows[static_cast<std::size_t>(2 + seed)][2], "reactive");
    sum += (b - m) / b;
  }
  const json c = json::parse(read_text(one + "/comparison.json"));
  ASSERT_EQ(c["comparisons"].size(), environments * 2);
  EXPECT_EQ(c["comparisons"][0]["mode"], "reactive");
  EXPECT_NEAR(c["comparisons"][0]["attitude"]["mean"].get<double>(), sum / 2, 2e-4);
  // Roll, pitch and yaw apart (columns 17-28): the roll-and-pitch figure is their quadratic
  // mean, and the yaw improvement is recomputed from the yaw column's pairs.
  double yaw_sum = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), 30u);
    const double roll = std::stod(rows[r][17]), pitch = std::stod(rows[r][19]);
    EXPECT_NEAR(std::stod(rows[r][6]), std::sqrt((roll * roll + pitch * pitch) / 2), 2e-4);
    EXPECT_LE(std::stod(rows[r][17]), std::stod(rows[r][18]));  // RMS ≤ max
    EXPECT_LE(std::stod(rows[r][21]), std::stod(rows[r][22]));
  }
  for (std::size_t seed = 0; seed < 2; ++seed) {
    const double b = std::stod(rows[seed][21]), m = std::stod(rows[2 + seed][21]);
    yaw_sum += (b - m) / b;
  }
  EXPECT_NEAR(c["comparisons"][0]["axes"]["yaw"]["rms"]["mean"].get<double>(), yaw_sum / 2, 2e-4);
  EXPECT_NE(read_text(one + "/comparison.md").find("| roll RMS / max | pitch RMS / max | yaw"),
            std::string::npos);
  // The first row's axes against `run`'s summary.json for the same flight (seed 1, TT400, what
  // --quick sets), which writes them straight from the simulation's summary.
  const std::string single = fresh_dir("control-compare-single");
  ASSERT_EQ(run_swath_control("run random:8@20x20 --environment lab --max-time 20 --set "
                              "scheduler.reactive.boot_s=5 --set scheduler.run.metrics_from_s=5 "
                              "--no-pictures -o " +
                              single)
                .exit_code,
            0);
  const json summary = json::parse(read_text(single + "/summary.json"));
  std::size_t column = 17;
  for (const char* group : {"attitude_error_deg", "attitude_error_disturbance_deg"})
    for (const char* axis : {"roll", "pitch", "yaw"})
      for (const char* stat : {"rms", "max"})
        EXPECT_NEAR(std::stod(rows[0][column++]), summary[group][axis][stat].get<double>(), 1e-4)
            << group << ' ' << axis << ' ' << stat;
  EXPECT_NEAR(std::stod(rows[0][29]),
              summary["attitude_error_disturbance_deg"]["share_of_samples"].get<double>(), 1e-4);
}

TEST(ControlCli, SweepFliesEachValueAsRunWouldWithThatSet) {
  const std::string out = fresh_dir("control-sweep");
  const CliRun run = run_swath_control(
      "sweep random:4@20x20 --param scheduler.rate_hz=100:400:150 --seeds 2 --max-time 15 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream in(read_text(out + "/runs.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("environment,vehicle,mode,value,seed,", 0), 0u);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream c(line);
    std::string cell;
    while (std::getline(c, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), 6u);  // 100, 250, 400 Hz x seeds 1, 2
  EXPECT_EQ(rows[2][3], "250");
  EXPECT_EQ(rows[2][4], "1");
  EXPECT_EQ(std::stod(rows[2][10]), 250.0);  // executions/s
  // The same flight by run: --set scheduler.rate_hz=250, seed 1.
  const std::string single = fresh_dir("control-sweep-single");
  ASSERT_EQ(run_swath_control("run random:4@20x20 --set scheduler.rate_hz=250 --seed 1 "
                              "--max-time 15 --no-pictures -o " +
                              single)
                .exit_code,
            0);
  const json s = json::parse(read_text(single + "/summary.json"));
  EXPECT_NEAR(std::stod(rows[2][9]), s["tracking"]["cross_track_rms_m"].get<double>(), 1e-4);
  EXPECT_NEAR(std::stod(rows[2][15]), s["energy"]["total_j"].get<double>(), 0.1);
}

TEST(ControlCli, SweepPairsEachValueWithItsBaselineOnTheSameSeeds) {
  const std::string out = fresh_dir("control-sweep-baseline");
  const CliRun run = run_swath_control(
      "sweep random:4@20x20 --scheduler reactive --baseline tt-400 --param "
      "scheduler.reactive.p_run=0.3,0.8 --seeds 2 --max-time 15 --set "
      "scheduler.reactive.boot_s=5 --set scheduler.run.metrics_from_s=5 --set "
      "vehicle.controller.change_threshold_us=10 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(out + "/sweep.png"));
  std::istringstream in(read_text(out + "/runs.csv"));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::istringstream h(line);
    for (std::string c; std::getline(h, c, ',');) header.push_back(c);
  }
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  std::map<std::string, std::map<std::string, double>> pitch;  // value → seed → pitch RMS
  std::map<std::string, std::string> mode;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream c(line);
    for (std::string cell; std::getline(c, cell, ',');) cells.push_back(cell);
    pitch[cells[column("value")]][cells[column("seed")]] =
        std::stod(cells[column("pitch_rms_deg")]);
    mode[cells[column("value")]] = cells[column("mode")];
  }
  // The baseline flown once per seed (a scheduler key does not reach tt-400's file).
  ASSERT_EQ(pitch.size(), 3u);
  EXPECT_EQ(mode["-"], "tt-400");
  EXPECT_EQ(mode["0.8"], "reactive");
  // sweep.md's pitch improvement of each value is the mean over seeds of (b − m) / b.
  const std::string md = read_text(out + "/sweep.md");
  for (const std::string value : {"0.3", "0.8"}) {
    double sum = 0;
    for (const std::string seed : {"1", "2"})
      sum += (pitch["-"][seed] - pitch[value][seed]) / pitch["-"][seed];
    const std::string row = "| " + value + " | ";
    const auto at = md.find(row);
    ASSERT_NE(at, std::string::npos) << value;
    const std::string rest = md.substr(at, md.find('\n', at) - at);
    // From the value: status, seven figures, then the improvements, the pitch's first.
    std::vector<std::string> cells;
    std::istringstream c(rest);
    for (std::string cell; std::getline(c, cell, '|');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 11u) << rest;
    EXPECT_NEAR(std::stod(cells[10]), 100 * sum / 2, 0.051) << rest;
  }
}

TEST(ControlCli, FitRecoversTheCoefficientsOfItsData) {
  // 20,000 points of L(x) with β = (−3, 2), written as a user would.
  const std::string dir = fresh_dir("control-fit");
  fs::create_directories(dir);
  std::string csv = "t_s,x,changed\n";
  std::uint64_t state = 12345;
  for (int i = 0; i < 20'000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double x = 4.0 * static_cast<double>(state >> 11) * 0x1.0p-53;
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
    csv += std::to_string(i) + "," + std::to_string(x) + "," +
           (u < 1 / (1 + std::exp(3 - 2 * x)) ? "1" : "0") + "\n";
  }
  std::ofstream(dir + "/data.csv") << csv;
  const CliRun run = run_swath_control("fit " + dir + "/data.csv --method mle --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);
  EXPECT_EQ(j["points"], 20'000);
  EXPECT_NEAR(j["beta1"].get<double>(), -3, 0.25);
  EXPECT_NEAR(j["beta2"].get<double>(), 2, 0.15);
  const double b1 = j["beta1"], b2 = j["beta2"];
  EXPECT_NEAR(j["threshold"].get<double>(), (std::log(0.6 / 0.4) - b1) / b2, 1e-9);
}

TEST(ControlCli, ThePictureShowsTheNoFlyZoneAndTheStartWhereTheyAre) {
  control::SimulationSettings settings;
  settings.mission.name = "test";
  settings.mission.legs = {{{0, 0, 5}, {100, 0, 5}}};
  settings.mission.area = {{{-10, -40}, {110, -40}, {110, 40}, {-10, 40}}};
  settings.mission.no_fly = {{{40, 15}, {60, 15}, {60, 35}, {40, 35}}};
  control::SimulationSummary summary;
  apps::FlightSeries flight;
  const apps::ControlPicture p = apps::trajectory_picture(settings, summary, flight, 800, 600);
  const render::Image image = render::draw(p.scene, p.view);
  struct Rgb {
    int r, g, b;
  };
  auto pixel = [&](geometry::Point2 world) {
    const geometry::Point2 px = p.view.to_pixel(world);
    const int x = static_cast<int>(px.x), y = static_cast<int>(px.y);
    return Rgb{image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
  };
  const auto zone = pixel({50, 25});  // the no-fly fill: reddish
  EXPECT_GT(zone.r, zone.g + 40);
  const auto start = pixel({0, 0});  // the start marker: dark
  EXPECT_LT(start.r + start.g + start.b, 150);
  const auto area = pixel({80, -20});  // the area fill: greenish
  EXPECT_GT(area.g, area.r);
}

// A file of the user's named as one the run writes (trace pictures, summary.json) is never
// replaced: refused naming it, exit 2, nothing written, before the flight; the files of the run
// before are replaced as ever.
TEST(ControlCli, AFileSwathDidNotWriteIsNeverReplaced) {
  const std::string out = fresh_dir("control-users-file");
  const std::string run = "run random:4@30x30 --max-time 0.001 --size 600x450 -o " + out;
  ASSERT_NO_FATAL_FAILURE(expect_users_file_survives("swath-control", run, out, "trajectory.png"));
  EXPECT_EQ(render::decode_png(read_text(out + "/trajectory.png")).width, 600);
}

}  // namespace
}  // namespace swath::test

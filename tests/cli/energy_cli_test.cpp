// swath-energy: this input gives this output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../../apps/swath-energy/energy_images.hpp"
#include "cli_runner.hpp"
#include "swath/base/number_text.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/energy/simulation.hpp"

namespace swath::test {
namespace {

using nlohmann::json;

TEST(EnergyCli, RunsThePapersSurvey) {
  const std::string out = fresh_dir("energy-run");
  const CliRun run = run_swath_energy(
      "run plans/survey.stages --config plans/survey-sim.yaml --progress -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");  // no progress bar off a terminal
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_TRUE(s["completed"].get<bool>());
  ASSERT_EQ(s["stages"].size(), 5u);
  EXPECT_EQ(s["stages"][4]["line"], 40);
  const auto traj = csv_rows(read_text(out + "/trajectory.csv"));
  const auto energy = csv_rows(read_text(out + "/energy.csv"));
  ASSERT_EQ(traj[0][0], "t_s");
  ASSERT_EQ(energy[0].size(), 5u + 7u);  // t, measured, model, SoC, predicted, q0..q6
  ASSERT_EQ(traj.size(), energy.size());
  // The energy is the integral of the measured power (rows every 0.1 s, steps of 0.01 s).
  double integral = 0.0;
  for (std::size_t i = 2; i < energy.size(); ++i)
    integral += std::stod(energy[i][1]) * (std::stod(energy[i][0]) - std::stod(energy[i - 1][0]));
  EXPECT_NEAR(integral, s["energy_j"].get<double>(), 0.02 * s["energy_j"].get<double>());
  // The flight ends at the last triggering point: (-3 * 70 + 105, 147) within 5 m.
  const auto& last = traj.back();
  EXPECT_LE(std::hypot(std::stod(last[1]) + 105.0, std::stod(last[2]) - 147.0), 5.0 + 1e-6);
  EXPECT_DOUBLE_EQ(std::stod(last[0]), s["flight_time_s"].get<double>());
  // SoC at the end as the summary says, and the same bytes from a second run.
  EXPECT_NEAR(std::stod(energy.back()[3]), s["final_soc"].get<double>(), 1e-6);
  const std::string again = fresh_dir("energy-run-again");
  ASSERT_EQ(run_swath_energy("run plans/survey.yaml --config plans/survey-sim.yaml -o " + again)
                .exit_code,
            0);
  EXPECT_EQ(read_text(again + "/energy.csv"), read_text(out + "/energy.csv"));
}

TEST(EnergyCli, BadPlanIsOneSentenceAndNoOutput) {
  const std::string out = fresh_dir("energy-bad");
  const std::string plan = out + ".stages";
  {
    std::ofstream f(plan);
    f << "# a stage with an unknown variable\n0.05; 90; x+z\n0, 10\n[0, 0]\n";
  }
  const CliRun run = run_swath_energy("run " + plan + " --config plans/survey-sim.yaml -o " + out);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find(plan + ": line 2 (phi): unknown variable 'z'"), std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // The config has two computation curves, this plan none.
  {
    std::ofstream f(plan);
    f << "0.05; 90; x\n0, 10\n[0, 0]\n";
  }
  const CliRun mismatch =
      run_swath_energy("run " + plan + " --config plans/survey-sim.yaml -o " + out);
  EXPECT_EQ(mismatch.exit_code, 2);
  EXPECT_NE(mismatch.err.find("plans/survey-sim.yaml: power.computations lists 2 computation "
                              "power curves, the plan " +
                              plan + " has 0 computations"),
            std::string::npos)
      << mismatch.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  const CliRun usage = run_swath_energy("run plans/survey.stages -o " + out);
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_NE(usage.err.find("--config is required"), std::string::npos) << usage.err;
  const CliRun help = run_swath_energy("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("4 a drone cannot finish"), std::string::npos);
}

TEST(EnergyCli, BudgetOfAPlannedSurveyAndExitFourWhenItCannotFinish) {
  const std::string plan = fresh_dir("energy-budget-plan");
  ASSERT_EQ(
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + plan)
          .exit_code,
      0);
  const json summary = json::parse(read_text(plan + "/summary.json"));
  const std::string out = fresh_dir("energy-budget");
  const CliRun run = run_swath_energy(
      "budget " + plan + "/mission.geojson --drone share/drones/quad-5ah.yaml -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json b = json::parse(read_text(out + "/budget.json"));
  ASSERT_EQ(b["drones"].size(), 1u);
  const json& d = b["drones"][0];
  // The path swath planned, flown at its speed, plus climbing to 60 m at 3 m/s and descending at
  // 2 m/s.
  const double path_m = summary["drones"][0]["path_length_m"].get<double>();
  const double speed = summary["drones"][0]["speed_m_s"].get<double>();
  EXPECT_NEAR(d["distance_m"].get<double>(), path_m, 0.01 * path_m);
  EXPECT_NEAR(d["flight_time_s"].get<double>(), path_m / speed + 60 / 3.0 + 60 / 2.0,
              0.01 * path_m / speed);
  EXPECT_TRUE(d["can_finish"].get<bool>());
  EXPECT_NE(run.out.find("drone-1"), std::string::npos);
  // The same mission through the QGC plan swath wrote: the same budget.
  const CliRun qgc = run_swath_energy("budget " + plan +
                                      "/drone-1.plan --drone share/drones/quad-5ah.yaml --json");
  ASSERT_EQ(qgc.exit_code, 0) << qgc.err;
  const json q = json::parse(qgc.out);
  EXPECT_NEAR(q["drones"][0]["energy_j"].get<double>(), d["energy_j"].get<double>(),
              0.01 * d["energy_j"].get<double>());
  // And through the WPL file (Mission Planner's): the same again.
  const CliRun wpl = run_swath_energy(
      "budget " + plan + "/drone-1.waypoints --drone share/drones/quad-5ah.yaml --json");
  ASSERT_EQ(wpl.exit_code, 0) << wpl.err;
  EXPECT_NEAR(json::parse(wpl.out)["drones"][0]["energy_j"].get<double>(),
              d["energy_j"].get<double>(), 0.01 * d["energy_j"].get<double>());
  // A fleet's drones are named in the budget as in the plan.
  const std::string fleet = fresh_dir("energy-budget-fleet");
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
                      "--fleet share/fleets/three-quads.yaml -o " +
                      fleet)
                .exit_code,
            0);
  const CliRun named =
      run_swath_energy("budget " + fleet + "/mission.geojson --drone share/drones/quad-5ah.yaml");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  for (const char* name : {"\nalpha ", "\nbravo ", "\ncharlie "})
    EXPECT_NE(named.out.find(name), std::string::npos) << named.out;
  // A small battery: exit 4, and the place where the reserve is crossed.
  const std::string small = out + "/small.yaml";
  {
    std::ofstream f(small);
    f << read_text(source_path("share/drones/quad-5ah.yaml")) << "\n";
  }
  std::string text = read_text(small);
  text.replace(text.find("capacity_ah: 5"), 14, "capacity_ah: 0.5");
  {
    std::ofstream f(small);
    f << text;
  }
  const CliRun weak = run_swath_energy("budget " + plan + "/mission.geojson --drone " + small);
  EXPECT_EQ(weak.exit_code, 4) << weak.err;
  EXPECT_NE(weak.out.find("drone-1 reaches the 20 % reserve at t = "), std::string::npos)
      << weak.out;
}

// A real survey as a stage plan, flown by swath-energy with a pack too small for the highest
// computations: the fixed-highest flight ends below the reserve, the replanned one above it.
TEST(EnergyCli, SurveyEnergyPlanIsFlownAndReplanned) {
  const std::string dir = fresh_dir("energy-survey-plan");
  const CliRun plan = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --energy-plan "
      "meadow.stages -o " +
      dir);
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const energy::Plan stages = energy::read_plan(dir + "/meadow.stages");
  const json summary = json::parse(read_text(dir + "/summary.json"));
  // Home leg, the lines, a turn between each two, the leg back.
  const std::size_t lines = summary["drones"][0]["lines"].get<std::size_t>();
  EXPECT_EQ(stages.stages.size(), 2 * lines - 1 + 2);
  ASSERT_EQ(stages.computations(), 2u);
  const energy::Interval c1 = stages.stages[0].trajectory[0];
  EXPECT_EQ(c1.hi, 1.0);
  EXPECT_GT(c1.lo, 0.5);
  EXPECT_LT(c1.lo, 1.0);
  // The header's home is the config's start (plans/meadow-sim.yaml).
  const energy::SimConfig config = energy::read_sim_config(source_path("plans/meadow-sim.yaml"));
  const std::string text = read_text(dir + "/meadow.stages");
  const std::string home = "start_m: [" + base::fixed_text(config.start.x, 2) + ", " +
                           base::fixed_text(config.start.y, 2) + "]";
  EXPECT_NE(text.find(home), std::string::npos) << text.substr(0, 400);

  const std::string out = dir + "/energy";
#ifdef SWATH_SANITIZED
  // Under the sanitizers the three flights (replanned, highest, lowest) at 0.01 s steps took two
  // minutes of CPU; 0.05 s steps (0.25 m at 5 m/s, well inside the 3 m trigger radius) run the
  // same code five times fewer times, and the assertions below hold at both steps.
  std::string sim = read_text(source_path("plans/meadow-sim.yaml"));
  const std::string step = "time_step_s: 0.01";
  ASSERT_NE(sim.find(step), std::string::npos);
  sim.replace(sim.find(step), step.size(), "time_step_s: 0.05");
  const std::string sim_path = dir + "/meadow-sim.yaml";
  std::ofstream(sim_path) << sim;
#else
  const std::string sim_path = "plans/meadow-sim.yaml";
#endif
  const CliRun run =
      run_swath_energy("run " + dir + "/meadow.stages --config " + sim_path + " -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_TRUE(s["completed"].get<bool>());
  const double reserve = s["reserve_soc"].get<double>();
  EXPECT_GE(s["final_soc"].get<double>(), reserve);
  EXPECT_LT(s["fixed"]["highest"]["final_soc"].get<double>(), reserve);
  EXPECT_GT(s["fixed"]["lowest"]["final_soc"].get<double>(), reserve);
  const double detection = s["replanning"]["mean_computations"][0].get<double>();
  EXPECT_GT(detection, s["fixed"]["lowest"]["computations"][0].get<double>());
  EXPECT_LT(detection, s["fixed"]["highest"]["computations"][0].get<double>());
  // The survey's path: the drone flies about the planned path length (turns on half circles
  // instead of straight legs between the lines' ends, so a few per cent apart).
  const double path_m = summary["drones"][0]["path_length_m"].get<double>();
  EXPECT_NEAR(s["flight_time_s"].get<double>() * config.speed_m_s, path_m, 0.05 * path_m);

  // A fleet: one plan per drone, each its own lines.
  const std::string fleet = fresh_dir("energy-survey-plan-fleet");
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
                      "--drones 2 --division region --energy-plan m.stages -o " +
                      fleet)
                .exit_code,
            0);
  const json fleet_summary = json::parse(read_text(fleet + "/summary.json"));
  for (int drone = 1; drone <= 2; ++drone) {
    const energy::Plan p = energy::read_plan(fleet + "/m-" + std::to_string(drone) + ".stages");
    const std::size_t n = fleet_summary["drones"][drone - 1]["lines"].get<std::size_t>();
    EXPECT_EQ(p.stages.size(), 2 * n - 1 + 2) << drone;
  }
  EXPECT_FALSE(std::filesystem::exists(fleet + "/m.stages"));

  // Bad requests: one sentence, exit 2, nothing written.
  const std::string bad = fresh_dir("energy-survey-plan-bad");
  for (const std::string& args :
       {std::string("--energy-plan sub/meadow.stages"),
        std::string("--energy-plan m.stages "
                    "--energy-computation 10,2"),
        std::string("--energy-plan m.stages --energy-min-coverage 1.5")}) {
    const CliRun r =
        run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 " + args +
                  " -o " + bad + "/out");
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find("--energy-"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(bad + "/out")) << args;
  }
}

// A file of the user's named as one swath-energy writes (summary.json, soc.csv) is never
// replaced: the run and the budget are refused naming it, exit 2, nothing written; the files of
// their own run before are replaced as ever.
TEST(EnergyCli, AFileSwathDidNotWriteIsNeverReplaced) {
  const std::string out = fresh_dir("energy-users-file");
  const std::string run = "run plans/survey.stages --config plans/survey-sim.yaml -o " + out;
  ASSERT_NO_FATAL_FAILURE(expect_users_file_survives("swath-energy", run, out, "summary.json"));
  EXPECT_TRUE(json::parse(read_text(out + "/summary.json"))["completed"].get<bool>());

  const std::string plan = fresh_dir("energy-users-file-plan");
  ASSERT_EQ(
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + plan)
          .exit_code,
      0);
  const std::string mine = "MY OWN STATE OF CHARGE\n";
  const std::string budget_out = fresh_dir("energy-users-file-budget");
  std::filesystem::create_directories(budget_out);
  std::ofstream(budget_out + "/soc.csv") << mine;
  const std::string budget =
      "budget " + plan + "/mission.geojson --drone share/drones/quad-5ah.yaml -o " + budget_out;
  const CliRun kept = run_swath_energy(budget);
  EXPECT_EQ(kept.exit_code, 2);
  EXPECT_NE(kept.err.find(budget_out + "/soc.csv: a file swath did not write"), std::string::npos)
      << kept.err;
  EXPECT_EQ(read_text(budget_out + "/soc.csv"), mine);
  EXPECT_EQ(directory_files(budget_out).size(), 1u);
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// The pictures, drawn in-process from a simulation, checked at known pixels; the command writes
// the same bytes.
TEST(EnergyImages, TrajectoryAndChartsAtKnownPixels) {
  const energy::Plan plan = energy::read_plan(source_path("plans/survey.stages"));
  const energy::SimConfig config = energy::read_sim_config(source_path("plans/survey-sim.yaml"));
  const energy::SimulationResult r = energy::simulate(plan, config);
  const apps::TrajectoryImage map = apps::trajectory_image(r, config, 800, 600);
  const render::Image image = render::draw(map.scene, map.view);
  // A flight sample halfway: the colour of its piece's state of charge.
  const std::size_t n = r.samples.size(), piece = std::max<std::size_t>(2, n / 200);
  const std::size_t mid = n / 2, start = mid / piece * piece;
  const render::Color expected = apps::soc_color(r.samples[start].soc, config.battery);
  const geometry::Point2 px = map.view.to_pixel(r.samples[mid].position);
  const int x = static_cast<int>(std::lround(px.x)), y = static_cast<int>(std::lround(px.y));
  EXPECT_NEAR(image.at(x, y, 0), 255 * expected.r, 12);
  EXPECT_NEAR(image.at(x, y, 1), 255 * expected.g, 12);
  EXPECT_EQ(image.at(3, 300, 0), 255);  // background at the left edge
  // The scale bar is as long as it claims.
  int dark = 0;
  for (int i = 0; i < 400; ++i)
    dark += image.at(i, static_cast<int>(map.scale_bar.start_px.y), 0) < 100;
  EXPECT_NEAR(dark, map.scale_bar.length_px, 2.0);

  const apps::EnergyImage charts = apps::energy_image(r, plan, config, 800, 900);
  ASSERT_EQ(charts.charts.size(), 3u);
  const render::Image e = render::draw(charts.scene, charts.view);
  // The state of charge passes through its data point: green there.
  const auto& soc = charts.charts[1];
  const auto& s = r.samples[n / 2];
  const int sx = static_cast<int>(std::lround(soc.to_x_px(s.t_s)));
  const int sy = static_cast<int>(std::lround(soc.to_y_px(100 * s.soc) + charts.offsets_px[1]));
  int green = 0;
  for (int dy = -2; dy <= 2; ++dy) green += e.at(sx, sy + dy, 1) > e.at(sx, sy + dy, 0) + 60;
  EXPECT_GE(green, 1);

  // swath-energy run writes these bytes.
  const std::string out = fresh_dir("energy-images");
  ASSERT_EQ(run_swath_energy(
                "run plans/survey.stages --config plans/survey-sim.yaml --size 800x600 -o " + out)
                .exit_code,
            0);
  EXPECT_EQ(read_text(out + "/trajectory.png"), render::encode_png(image));
  EXPECT_EQ(render::decode_png(read_text(out + "/energy.png")).height, 600);
}

}  // namespace
}  // namespace swath::test

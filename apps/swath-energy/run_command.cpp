#include "run_command.hpp"

#include <iostream>

#include "energy_images.hpp"
#include "map_furniture.hpp"
#include "progress_bar.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/energy/energy_files.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/energy/simulation.hpp"

namespace swath::apps {

void RunCommand::setup(CLI::App& app) {
  app.add_option(
         "PLAN", plan_,
         "Plan of flight stages: stage format (.stages; .plan read with a warning) or YAML (.yaml)")
      ->required();
  app.add_option("--config", config_,
                 "Simulation config YAML: time step, speed, wind, model, Kalman, battery, power "
                 "(see plans/survey-sim.yaml)")
      ->required();
  app.add_option("-o,--output", output_, "Directory for trajectory.csv, energy.csv, summary.json")
      ->required();
  app.add_flag("--no-replan", no_replan_,
               "Keep the parameters at the config's values (default: replan them every "
               "mpc.period_s so that the mission finishes above the battery reserve)");
  app.add_option("--size", size_, "Size of trajectory.png and energy.png, WxH pixels")
      ->capture_default_str();
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

int RunCommand::run() {
  std::vector<std::string> warnings;
  const energy::Plan plan = energy::read_plan(plan_, &warnings);
  for (const std::string& w : warnings) std::cerr << "swath-energy run: warning: " << w << '\n';
  energy::SimConfig config = energy::read_sim_config(config_);
  for (const std::string& w : config.warnings)
    std::cerr << "swath-energy run: warning: " << w << '\n';
  if (no_replan_) config.replan = false;
  // The rows stream into the set's temporaries as they are taken: memory stays flat however
  // long the flight. Opened only now: bad input above leaves nothing behind.
  base::OutputSet set(output_, "energy-run");
  // The files added after the flight refused before it too: no simulation for nothing.
  base::check_output_names(output_, "energy-run",
                           {"control.csv", "summary.json", "trajectory.png", "energy.png"});
  base::OutputSet::Stream& trajectory = set.stream("trajectory.csv");
  base::OutputSet::Stream& energy_rows = set.stream("energy.csv");
  trajectory << energy::trajectory_csv_header();
  bool first = true;
  const energy::SampleSink sink = [&](const energy::FlightSample& s) {
    if (first) energy_rows << energy::energy_csv_header(s);
    first = false;
    trajectory << energy::trajectory_csv_row(s);
    energy_rows << energy::energy_csv_row(s);
  };
  energy::SimulationResult result;
  {
    ProgressBar bar(progress_, "simulating");
    result = energy::simulate(
        plan, config, [&](double f) { bar.update(f); }, sink);
  }
  if (first) energy_rows << energy::energy_csv_header({});
  const energy::FixedComparison fixed = energy::compare_fixed(plan, config);
  const auto [w, h] = parse_size(size_);
  const TrajectoryImage map = trajectory_image(result, config, w, h);
  const EnergyImage charts = energy_image(result, plan, config, w, h);
  set.add("control.csv", energy::control_csv(result));
  set.add("summary.json", energy::simulation_summary_json(result, plan, config, &fixed));
  set.add("trajectory.png", render::encode_png(render::draw(map.scene, map.view)));
  set.add("energy.png", render::encode_png(render::draw(charts.scene, charts.view)));
  set.commit();
  using base::fixed_text;
  std::cout << "swath-energy run: " << energy::to_string(result.status) << " after "
            << fixed_text(result.flight_time_s, 1) << " s, "
            << fixed_text(result.energy_j / 3600, 2) << " Wh, final SoC "
            << fixed_text(100 * result.final_soc, 1) << " %";
  if (result.status == energy::SimulationEnd::completed)
    std::cout << ", predicted total energy within "
              << fixed_text(100 * result.max_relative_error, 2) << " % after the first period";
  if (config.replan)
    std::cout << ", " << result.replans << " replans, " << result.control.size() - 1 << " changes";
  std::cout << "; wrote " << output_ << '\n';
  if (result.infeasible_replans > 0)
    std::cerr << "swath-energy run: warning: at " << result.infeasible_replans
              << " replans no parameters fitted the battery above its reserve; the lowest levels "
                 "were flown\n";
  return result.status == energy::SimulationEnd::completed ? base::kExitSuccess
                                                           : base::kExitNotCompleted;
}

}  // namespace swath::apps

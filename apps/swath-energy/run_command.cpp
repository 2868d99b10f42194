#include "run_command.hpp"

#include <iostream>

#include "progress_bar.hpp"
#include "swath/energy/energy_files.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/energy/simulation.hpp"
#include "swath/planning/number_text.hpp"
#include "swath/planning/output_files.hpp"

namespace swath::apps {

void RunCommand::setup(CLI::App& app) {
  app.add_option("PLAN", plan_, "Plan of flight stages: stage format (.plan) or YAML (.yaml)")
      ->required();
  app.add_option("--config", config_,
                 "Simulation config YAML: time step, speed, wind, model, Kalman, battery, power "
                 "(see plans/survey-sim.yaml)")
      ->required();
  app.add_option("-o,--output", output_, "Directory for trajectory.csv, energy.csv, summary.json")
      ->required();
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

int RunCommand::run() {
  const energy::Plan plan = energy::read_plan(plan_);
  const energy::SimConfig config = energy::read_sim_config(config_);
  ProgressBar bar(progress_, "simulating");
  const energy::SimulationResult result =
      energy::simulate(plan, config, [&](double f) { bar.update(f); });
  planning::write_files_atomically(
      output_, {{"trajectory.csv", energy::trajectory_csv(result)},
                {"energy.csv", energy::energy_csv(result)},
                {"summary.json", energy::simulation_summary_json(result, plan, config)}});
  using planning::fixed_text;
  std::cout << "swath-energy run: " << energy::to_string(result.status) << " after "
            << fixed_text(result.flight_time_s, 1) << " s, "
            << fixed_text(result.energy_j / 3600, 2) << " Wh, final SoC "
            << fixed_text(100 * result.final_soc, 1) << " %, predicted total energy within "
            << fixed_text(100 * result.max_relative_error, 2) << " % after the first period; wrote "
            << output_ << '\n';
  return result.status == energy::FlightStatus::completed ? kSuccess : kCannotFinish;
}

}  // namespace swath::apps

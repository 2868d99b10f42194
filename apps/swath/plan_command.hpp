#pragma once

#include <optional>
#include <string>
#include <vector>

#include "area_options.hpp"
#include "command.hpp"
#include "swath/planning/survey.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::apps {

/// `swath plan FIELD --camera CAM (--altitude M | --gsd CM | --mode detection ...) -o DIR`.
class PlanCommand : public Command {
 public:
  const char* name() const override { return "plan"; }
  const char* description() const override {
    return "Plan a camera survey of an area and write mission files (QGC .plan, WPL 110, GeoJSON, "
           "CSV, KML) and summary.json into -o DIR";
  }
  void setup(CLI::App& app) override;
  int run() override;
  /// The options checked as run() would before planning, without reading the area (swath
  /// batch, once for all its areas): its mission config applied, the numbers, the camera, the
  /// files they name (fleet, zones, DEM). Throws InputError with run()'s sentence.
  void check_options();

 private:
  /// setup()'s groups of options.
  void add_input_options(CLI::App& app);
  void add_imaging_options(CLI::App& app);
  void add_sweep_options(CLI::App& app);
  void add_division_options(CLI::App& app);
  void add_output_options(CLI::App& app);
  void add_mission_file_options(CLI::App& app);
  void add_terrain_energy_options(CLI::App& app);
  /// Every number given, against planning/limits.hpp's ranges, before any work.
  void check_numbers() const;
  /// The steps of run(): the request from the options, the files of the plan, what to print.
  planning::SurveyRequest request() const;
  /// Everything of the request but the area (request() reads it first).
  void fill_request(planning::SurveyRequest& request) const;
  /// The mission files' options that need each other (--basemap and --render or --html).
  void check_file_options() const;
  std::optional<planning::TerrainRequest> terrain() const;
  std::vector<std::pair<std::string, std::string>> files(const planning::SurveyPlan& plan) const;
  /// What the files about to be written are checked against (swath verify's checks).
  preflight::CheckOptions check_options(const planning::SurveyPlan& plan) const;
  void report(const planning::SurveyPlan& plan,
              const std::vector<std::pair<std::string, std::string>>& files) const;

  CLI::App* app_ = nullptr;
  std::string config_;
  std::string field_;
  std::string camera_;
  std::string output_;
  std::string mode_ = "photogrammetry";
  std::optional<double> altitude_m_;
  std::optional<double> gsd_cm_;
  double side_overlap_ = 0.7;
  double front_overlap_ = 0.7;
  std::string pattern_;
  std::optional<double> min_pixels_;
  double overlap_ = 0.0;
  bool portrait_ = false;
  std::optional<double> angle_deg_;
  std::string angle_search_ = "exact";
  double angle_step_deg_ = 0.1;
  std::string placement_ = "centered";
  std::optional<double> turnaround_m_;
  std::optional<double> waypoint_spacing_m_;
  std::string start_ = "nearest-home";
  std::string home_;
  std::string origin_;
  bool local_ = false;
  AreaChoice area_choice_;
  std::string concave_ = "split";
  std::string split_cells_ = "best";
  std::string directions_ = "one";
  unsigned threads_ = 0;
  std::vector<std::string> exclude_;
  bool repair_ = false;
  bool progress_ = false;
  std::optional<int> drones_;
  bool far_home_ = false;
  std::string fleet_;
  std::string division_ = "path";
  std::string balance_ = "capability";
  bool allow_partial_ = false;
  bool render_ = false;
  std::string size_ = "1600x1200";
  std::string firmware_ = "ardupilot";
  std::string vehicle_ = "multirotor";
  std::optional<double> speed_m_s_;
  double clearance_m_ = 5.0;
  double ceiling_m_ = 120.0;
  double boundary_clearance_m_ = 0.0;
  double outside_margin_m_ = 0.0;
  std::string trigger_ = "distance";
  std::string camera_command_ = "digicam";
  bool photos_in_turns_ = false;
  double gimbal_pitch_deg_ = -90.0;
  bool crosshatch_ = false;
  std::optional<double> fence_margin_m_;
  double layer_spacing_m_ = 10.0;
  bool fence_files_ = false;
  bool litchi_ = false;
  bool dji_ = false;
  bool qgc_survey_ = false;
  bool coverage_tif_ = false;
  bool html_ = false;
  std::string basemap_url_;
  std::string basemap_;
  double coverage_cell_m_ = 0.5;
  std::string terrain_;  ///< --terrain DEM
  double terrain_tolerance_m_ = 2.0;
  std::string altitude_frame_ = "relative";
  std::string dem_heights_ = "geoid";
  std::string dem_units_;  ///< --dem-units m|ft|us-ft; empty: the DEM's own, else metres
  bool land_ = false;
  double max_bank_deg_ = 30.0;
  std::string sorties_ = "off";
  std::optional<double> endurance_s_;
  double reserve_ = 0.2;
  mutable std::vector<std::string> energy_warnings_;  ///< from files(), printed by report()
  mutable std::vector<std::string> export_warnings_;  ///< from files(), printed by report()
  std::string energy_plan_;
  double energy_min_coverage_ = 0.99;
  std::vector<std::string> energy_computations_ = {"2,10", "32,448"};
};

}  // namespace swath::apps

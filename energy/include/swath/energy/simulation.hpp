#pragma once
// Flight simulation of a plan of stages with the energy model running alongside (paper 004
// Algorithm 1 without the replanning: the parameters stay fixed).

#include <functional>
#include <optional>
#include <vector>

#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/geometry/point.hpp"

namespace swath::energy {

/// How a simulation ended. A stalled plan (the field vanishes, or the drone stops approaching its
/// triggering point) is bad input and throws base::InputError instead.
enum class SimulationEnd {
  completed,      ///< the last triggering point was reached
  battery_empty,  ///< the state of charge reached 0 first
  time_limit,     ///< max_time_s passed first
};

const char* to_string(SimulationEnd status);

struct FlightSample {
  double t_s = 0.0;
  geometry::Point2 position;
  int stage = 0;            ///< 0-based
  double course_deg = 0.0;  ///< ground track, compass bearing (0 north, 90 east)
  double ground_speed_m_s = 0.0;
  double airspeed_m_s = 0.0;
  double path_distance_m = 0.0;  ///< |phi| / |grad phi|: distance to the stage's curve, 1st order
  double measured_w = 0.0;       ///< NaN where a replayed trace has no value
  double model_w = 0.0;
  double soc = 0.0;
  double predicted_total_j = 0.0;  ///< energy used so far + the model's prediction of the rest
  std::vector<double> coefficients;
};

struct StageEntry {
  int stage = 0;
  double t_s = 0.0;
  geometry::Point2 position;
};

/// The parameters from a time on (control.csv).
struct ControlSample {
  double t_s = 0.0;
  std::vector<double> trajectory, computations;  ///< as chosen (each stage clamps them)
  bool feasible = true;  ///< false: nothing fitted the battery; the lowest levels were taken
};

/// The most samples a SimulationResult keeps (about 2.4 MB with 8 coefficients).
inline constexpr std::size_t kMaxKeptSamples = 20'000;

/// Receives every sample as it is taken, in time order (swath-energy run streams them to its CSV
/// files, so memory does not grow with the flight).
using SampleSink = std::function<void(const FlightSample&)>;

struct SimulationResult {
  SimulationEnd status = SimulationEnd::completed;
  /// Every output interval and the last step; beyond kMaxKeptSamples evenly decimated (every 2nd,
  /// 4th, ... sample; the last one always kept). The prediction errors below are over these.
  std::vector<FlightSample> samples;
  std::vector<StageEntry> stages;  ///< when each stage began
  double flight_time_s = 0.0;
  double energy_j = 0.0;  ///< measured (model power where no measurement)
  double final_soc = 0.0;
  std::optional<double> reserve_crossed_s;
  double planned_time_s = 0.0;       ///< flight time of the path at these parameters
  double first_period_s = 0.0;       ///< predictions are scored from here on
  double mean_relative_error = 0.0;  ///< |predicted total - actual total| / actual, after that
  double max_relative_error = 0.0;
  long corrections = 0;  ///< Kalman corrections applied
  long steps = 0;
  double final_period_s = 0.0;
  std::vector<ControlSample> control;  ///< the initial parameters and every change
  long replans = 0;                    ///< choices made by the replanner
  long infeasible_replans = 0;         ///< of which nothing fitted
  std::vector<double> mean_trajectory, mean_computations;  ///< time-weighted, as flown (clamped)
  double mean_power_w = 0.0;
  /// The plan flown at the initial parameters, every output interval (decimated like samples).
  std::vector<geometry::Point2> planned_path;
  std::vector<geometry::Point2> planned_triggers;  ///< each stage's triggering point, likewise
};

/// The path the guidance of `plan` flies with `config` (its start, speed, wind, time step) at the
/// highest trajectory parameters, every output interval (decimated beyond kMaxKeptSamples), local
/// metres: what other vehicles (swath-control's multirotor) are asked to follow. Throws
/// base::InputError as simulate() does.
std::vector<geometry::Point2> guided_path(const Plan& plan, const SimConfig& config);

/// The same plan and battery flown with fixed highest and fixed lowest parameters (no
/// replanning): what lowering the computations buys.
struct FixedComparison {
  SimulationResult highest, lowest;
  /// Extra flight per hour of flight the lowest levels give over the highest on the same battery:
  /// 60 (P_highest / P_lowest - 1) minutes, from the two runs' mean powers.
  double minutes_per_hour = 0.0;
};

FixedComparison compare_fixed(const Plan& plan, const SimConfig& config);

/// Flies `plan` with `config`. `progress` (optional) gets the fraction of the planned time flown,
/// now and then; `sink` (optional) every sample. Throws base::InputError for a plan that cannot be
/// flown (stall, field zero, wind stronger than the drone, triggering point undefined) naming the
/// stage's line.
SimulationResult simulate(const Plan& plan, const SimConfig& config,
                          const std::function<void(double)>& progress = {},
                          const SampleSink& sink = {});

}  // namespace swath::energy

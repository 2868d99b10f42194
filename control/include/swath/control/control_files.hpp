#pragma once
// The files of `swath-control run` (docs/swath-control.md, with the one spelling of
// speeds, _m_s): timeseries.csv and rate.csv row by row (streamed by the caller), summary.json.
// Numbers are written with a fixed number of decimals and without the locale, so the same flight
// gives the same bytes.

#include <string>

#include "swath/control/simulation.hpp"

namespace swath::control {

/// timeseries.csv: the header for `rotors` rotors, and one row.
std::string timeseries_csv_header(std::size_t rotors);
std::string timeseries_csv_row(const TimeseriesRow& row);

/// rate.csv: the header with one triggers_<name> column per trigger sensor, and one row.
std::string rate_csv_header(const std::vector<std::string>& trigger_sensors);
std::string rate_csv_row(const RateRow& row);

/// executions.csv: the header with one x_<name> column per trigger sensor, and one row.
std::string executions_csv_header(const std::vector<std::string>& trigger_sensors);
std::string executions_csv_row(const ExecutionRow& row, std::size_t trigger_sensors);

/// fits.csv: one row per sensor and refit.
std::string fits_csv_header();
std::string fits_csv_row(const FitRow& row, FitMethod method);

/// What summary.json names as the inputs.
struct SummaryInputs {
  std::string mission, vehicle, scheduler, environment;
  std::uint64_t seed = 1;
  double speed_m_s = 0;
  bool loop = false;
};

/// summary.json (its keys: docs/formats.md, 'Outputs of swath-control and swath-fleet';
/// `plan_check` for a swath plan).
std::string summary_json(const SimulationSummary& summary, const SummaryInputs& inputs,
                         const SimulationSettings& settings);

}  // namespace swath::control

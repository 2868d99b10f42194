#pragma once
// Paper 002's experiment (paper 002 §7; docs/swath-control.md): flights paired by seed (common
// random numbers, so the modes see the same wind and sensor noise) and the paired improvement of a
// mode over the time-triggered baseline with a 95 % Student-t interval.

#include <array>
#include <string>
#include <vector>

#include "swath/control/simulation.hpp"

namespace swath::control {

/// A mean over n values with its two-sided 95 % Student-t interval (n − 1 degrees of freedom);
/// n = 1: the interval is the value; n = 0: all zero.
struct MeanInterval {
  double mean = 0, low = 0, high = 0;
  int n = 0;
};
MeanInterval mean_interval(const std::vector<double>& values);

/// The figures a comparison pairs, from one flight's summary.
struct FlightFigures {
  double attitude_rms_deg = 0;  ///< roll and pitch together: √((r² + p²) / 2), true vs setpoint
  double attitude_estimated_rms_deg = 0;  ///< the same against the estimate (the paper's measure)
  double cross_track_rms_m = 0;
  double executions_per_s = 0;
  double unchanged_fraction = 0;
  double flight_time_s = 0;  ///< to the reserve when it was reached, else the flight's
  double cpu_j = 0, total_j = 0;
  double cpu_utilisation = 0;  ///< the core's busy share
  double background_completed =
      0;  ///< the share of background releases completed (1: none released)
  /// Roll, pitch, yaw separately (the paper's Figs. 9-10), true vs setpoint, RMS and max.
  std::array<ErrorStat, 3> axis_error_deg{};
  /// The same over the samples when nothing was commanded (summary.json's
  /// attitude_error_disturbance_deg: the carrot at constant velocity, the heading not slewing).
  std::array<ErrorStat, 3> axis_disturbance_error_deg{};
  double disturbance_rms_deg = 0;  ///< roll and pitch together over those samples
  double disturbance_share = 0;    ///< the share of the samples that counted for it
};
FlightFigures figures_of(const SimulationSummary& s);

/// Relative improvements of `mode` over `baseline`, paired (same seed, same index):
/// (b − m) / b for errors and executions (positive: fewer), (m − b) / b for flight time (positive:
/// longer). Pairs where the baseline is 0 are skipped.
struct Improvements {
  MeanInterval attitude, attitude_estimated, cross_track, executions, flight_time;
  std::array<MeanInterval, 3> axis_rms, axis_max;  ///< roll, pitch, yaw
  MeanInterval disturbance;                        ///< disturbance_rms_deg
};
Improvements paired_improvements(const std::vector<FlightFigures>& baseline,
                                 const std::vector<FlightFigures>& mode);

}  // namespace swath::control

#pragma once
// Means over seeds with their 95 % confidence intervals (compare, forecasts), and what is known
// of runs that did not complete: censored completion times (compare).

#include <cstdint>
#include <optional>
#include <vector>

namespace swath::apps {

/// The two-sided 95 % Student t quantile for n − 1 degrees of freedom (n ≥ 2).
double t95(int n);

struct Interval {
  double mean = 0;
  double half = 0;  ///< half-width of the 95 % interval of the mean
};
/// The mean of `x` (at least two values) and its Student-t 95 % half-width.
Interval mean_interval95(const std::vector<double>& x);

/// A run's completion time as far as it is known: `completed` at time_s, or censored at time_s
/// (the run ended there, at the time limit or because the app could not finish: its completion
/// time exceeds time_s).
struct TimeObservation {
  double time_s = 0;
  bool completed = false;
};

/// The Kaplan–Meier median completion time: the smallest completion time t at which the
/// estimated fraction of runs still running, S(t), is at most one half (completions at a time
/// count before censorings at the same time). nullopt when S stays above one half (more than
/// half the runs censored before the median could be seen).
std::optional<double> kaplan_meier_median_s(std::vector<TimeObservation> runs);

/// Two runs of one seed, `other` against `first`: their relative change when both completed,
/// else the sign when the censoring still tells it (a censored run is slower than a completed
/// one that finished before the censored one ended).
struct PairedRuns {
  std::optional<double> relative_change;  ///< other / first − 1, both completed
  int sign = 0;        ///< −1 other faster, +1 other slower, 0 equal or unknown
  bool known = false;  ///< the sign is known
};
PairedRuns pair_runs(const TimeObservation& first, const TimeObservation& other);

}  // namespace swath::apps

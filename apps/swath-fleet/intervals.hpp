#pragma once
// Means over seeds with their 95 % confidence intervals (compare, forecasts).

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

}  // namespace swath::apps

#include "swath/energy/period_estimate.hpp"

#include <cmath>

namespace swath::energy {

std::optional<double> estimate_period_s(const std::vector<double>& samples, double sample_dt_s,
                                        double min_s, double max_s, double min_correlation) {
  const std::size_t n = samples.size();
  const auto min_lag = static_cast<std::size_t>(std::ceil(min_s / sample_dt_s));
  std::size_t max_lag = static_cast<std::size_t>(std::floor(max_s / sample_dt_s));
  if (max_lag > n / 2) max_lag = n / 2;
  if (min_lag < 1 || max_lag < min_lag + 2) return std::nullopt;
  double mean = 0.0;
  for (double v : samples) mean += v;
  mean /= static_cast<double>(n);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = samples[i] - mean;
  // Normalised correlation of the overlapping parts, lags min_lag - 1 .. max_lag + 1.
  std::vector<double> corr(max_lag + 2, 0.0);
  for (std::size_t lag = min_lag - 1; lag <= max_lag + 1 && lag < n; ++lag) {
    double xy = 0.0, xx = 0.0, yy = 0.0;
    for (std::size_t i = 0; i + lag < n; ++i) {
      xy += x[i] * x[i + lag];
      xx += x[i] * x[i];
      yy += x[i + lag] * x[i + lag];
    }
    corr[lag] = xx > 0.0 && yy > 0.0 ? xy / std::sqrt(xx * yy) : 0.0;
  }
  double best = -1.0;
  for (std::size_t lag = min_lag; lag <= max_lag; ++lag) best = std::max(best, corr[lag]);
  if (best < min_correlation) return std::nullopt;
  // The shortest lag that repeats nearly as well: multiples of the period score alike.
  for (std::size_t lag = min_lag; lag <= max_lag; ++lag) {
    if (corr[lag] < 0.9 * best || corr[lag] < corr[lag - 1] || corr[lag] < corr[lag + 1]) continue;
    const double a = corr[lag - 1], b = corr[lag], c = corr[lag + 1];
    const double denom = a - 2.0 * b + c;
    const double shift = denom < 0.0 ? 0.5 * (a - c) / denom : 0.0;
    return (static_cast<double>(lag) + shift) * sample_dt_s;
  }
  return std::nullopt;
}

}  // namespace swath::energy

#pragma once
// Re-estimating the period of the energy signal as the plan repeats.

#include <optional>
#include <vector>

namespace swath::energy {

/// The lag in [min_s, max_s] at which `samples` (equally spaced by `sample_dt_s`, oldest first)
/// best repeats: the maximum of the normalised autocorrelation, refined by a parabola through
/// its neighbours. Lags are searched up to min(max_s, half the window), so that every lag is
/// compared over at least as many samples as it spans. Empty when that leaves no lag >= min_s, or
/// when the best correlation is below `min_correlation` (no clear repetition). Cost O(n * lags).
std::optional<double> estimate_period_s(const std::vector<double>& samples, double sample_dt_s,
                                        double min_s, double max_s, double min_correlation = 0.5);

}  // namespace swath::energy

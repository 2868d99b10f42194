#include "swath/energy/replanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace swath::energy {
namespace {

// Every combination of integer levels, stepping coarser when there are too many.
std::vector<std::vector<double>> level_combinations(const std::vector<Interval>& bounds) {
  constexpr double kMaxCombinations = 20000.0;
  std::vector<double> step(bounds.size(), 1.0);
  double count = 1.0;
  for (const Interval& b : bounds) count *= std::floor(b.hi) - std::ceil(b.lo) + 1.0;
  if (count > kMaxCombinations) {
    const double factor =
        std::pow(count / kMaxCombinations, 1.0 / static_cast<double>(bounds.size()));
    for (double& s : step) s = std::ceil(factor);
  }
  std::vector<std::vector<double>> out{{}};
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    std::vector<double> levels;
    const double lo = std::ceil(bounds[j].lo), hi = std::floor(bounds[j].hi);
    if (hi < lo) {
      levels.push_back(bounds[j].lo);  // no integer inside: the bound itself
    } else {
      for (double v = hi; v >= lo; v -= step[j]) levels.push_back(v);
      if (levels.back() != lo) levels.push_back(lo);
    }
    std::vector<std::vector<double>> next;
    for (const auto& prefix : out)
      for (double v : levels) {
        next.push_back(prefix);
        next.back().push_back(v);
      }
    out = std::move(next);
  }
  return out;
}

}  // namespace

double computation_quality(const std::vector<Interval>& bounds, const std::vector<double>& weights,
                           const std::vector<double>& computations) {
  double q = 0.0;
  for (std::size_t j = 0; j < bounds.size() && j < computations.size(); ++j) {
    const double span = bounds[j].hi - bounds[j].lo;
    if (span <= 0) continue;
    const double w = j < weights.size() ? weights[j] : 1.0;
    q += w * (computations[j] - bounds[j].lo) / span;
  }
  return q;
}

bool fits(const ReplanProblem& p, double lambda, const std::vector<double>& computations,
          ReplanChoice* out) {
  const double energy = p.rest_energy_j(lambda, computations);
  const double time = p.rest_time_s(lambda);
  double available = 0.0;
  if (time > 0.0 && energy > 0.0) {
    const double mean_power = energy / time;
    available = std::isnan(battery_current_a(p.battery, mean_power))
                    ? 0.0
                    : (1.0 - p.margin) *
                          usable_energy_j(p.battery, p.soc, p.battery.reserve_soc, mean_power);
  } else {
    available = energy <= 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  if (out) {
    out->lambda = lambda;
    out->computations = computations;
    out->rest_energy_j = energy;
    out->available_j = available;
    out->feasible = energy <= available;
  }
  return energy <= available;
}

ReplanChoice choose_parameters(const ReplanProblem& p) {
  auto candidates = level_combinations(p.computation_bounds);
  std::vector<double> quality;
  for (const auto& c : candidates)
    quality.push_back(computation_quality(p.computation_bounds, p.quality_weights, c));
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  // Stable: among equal quality the enumeration order (higher levels of the first parameter first).
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return quality[a] > quality[b]; });

  std::vector<double> grid;
  if (p.trajectory_free) {
    for (int i = 8; i >= 0; --i) grid.push_back(i / 8.0);  // widest first
  } else {
    grid.push_back(1.0);
  }
  for (std::size_t index : order) {
    const auto& comps = candidates[index];
    // The widest grid lambda that fits; none: this level set does not fit at all.
    std::size_t g = 0;
    while (g < grid.size() && !fits(p, grid[g], comps)) ++g;
    if (g == grid.size()) continue;
    double lo = grid[g];
    if (g > 0) {
      double hi = grid[g - 1];  // does not fit
      while (hi - lo > 1e-6) {
        const double mid = 0.5 * (lo + hi);
        (fits(p, mid, comps) ? lo : hi) = mid;
      }
    }
    ReplanChoice choice;
    fits(p, lo, comps, &choice);
    return choice;
  }
  // Nothing fits: the lowest levels at the most economical lambda.
  std::vector<double> lowest;
  for (const Interval& b : p.computation_bounds) lowest.push_back(b.lo);
  double best_lambda = grid.front(), best_slack = -std::numeric_limits<double>::infinity();
  for (double l : grid) {
    ReplanChoice c;
    fits(p, l, lowest, &c);
    if (c.available_j - c.rest_energy_j > best_slack) {
      best_slack = c.available_j - c.rest_energy_j;
      best_lambda = l;
    }
  }
  ReplanChoice choice;
  fits(p, best_lambda, lowest, &choice);
  choice.feasible = false;
  return choice;
}

}  // namespace swath::energy

#pragma once
// Energy-aware choice of the plan's parameters (paper 004 §III-B, Algorithm line 3): the highest
// quality whose predicted energy for the rest of the mission the battery can still deliver above
// its reserve (eq. 12-13).

#include <functional>
#include <vector>

#include "swath/energy/battery.hpp"
#include "swath/energy/plan.hpp"

namespace swath::energy {

/// One replanning problem. Trajectory parameters move together along their box's diagonal:
/// c(lambda) = lo + lambda (hi - lo), lambda in [0, 1] (1: the widest). Computation parameters
/// are integers within their bounds.
struct ReplanProblem {
  std::vector<Interval> computation_bounds;  ///< of the current stage
  std::vector<double> quality_weights;       ///< per computation (empty: all 1)
  bool trajectory_free = false;              ///< false: lambda is fixed at 1
  /// Predicted energy of the rest of the mission (J) and its duration (s) for a choice.
  std::function<double(double lambda, const std::vector<double>& computations)> rest_energy_j;
  std::function<double(double lambda)> rest_time_s;
  Battery battery;
  double soc = 1.0;
  double margin = 0.02;  ///< keep this share of the available energy unused, [0, 1)
};

struct ReplanChoice {
  double lambda = 1.0;
  std::vector<double> computations;
  bool feasible = false;  ///< false: nothing fits; the lowest levels were chosen
  double rest_energy_j = 0.0;
  double available_j = 0.0;  ///< what the battery delivers above the reserve at that mean power
};

/// Quality of computation levels: sum of weight x (c - lo) / (hi - lo) (degenerate bounds: 0).
double computation_quality(const std::vector<Interval>& bounds, const std::vector<double>& weights,
                           const std::vector<double>& computations);

/// Whether a choice fits: rest energy <= (1 - margin) x the energy the battery delivers from the
/// current SoC down to the reserve at the rest's mean power. Fills energy and availability.
bool fits(const ReplanProblem& p, double lambda, const std::vector<double>& computations,
          ReplanChoice* out = nullptr);

/// The solver: every integer combination of computation levels (a coarser step per parameter
/// when there are more than 20,000), in decreasing quality; for each, feasibility is first tested
/// at the most economical lambda of a 9-point grid, and for the first that fits, the widest
/// feasible lambda is found by bisection above the highest feasible grid point (1e-6). Quality
/// first, then the widest trajectory. If nothing fits: the lowest levels at the economical lambda,
/// feasible = false.
ReplanChoice choose_parameters(const ReplanProblem& p);

}  // namespace swath::energy

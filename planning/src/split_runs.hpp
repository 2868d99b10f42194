#pragma once
// Internal to split.cpp (and its tests): which runs candidates the direction search estimates.
#include <cstddef>
#include <functional>
#include <tuple>
#include <vector>

#include "swath/planning/cell_order.hpp"

namespace swath::planning::split_detail {

/// The candidates to refine: of each kind the `per_kind` least estimates (then the lowest index),
/// kind by kind. estimates: (kind, estimate, candidate).
std::vector<std::size_t> best_of_each_kind(
    std::vector<std::tuple<int, double, std::size_t>> estimates, std::size_t per_kind);

/// A lower bound on every order's length of `problem` (its cells' least internal lengths, less
/// 1e-9 for rounding), cheaper than order_lower_bound(): the first bound of the runs' estimates.
double internal_lower_bound(const CellOrderProblem& problem);

/// The estimates of candidates i (kinds[i]) where they may rank among the `per_kind` least of
/// their kind, +inf where they cannot. Two lower bounds of each estimate(i): bounds_m[i], known,
/// and tighter_bound(i) (if given), asked only where bounds_m[i] does not rule i out. The estimates
/// are asked in order of bounds_m (on `threads` threads), and not asked where per_kind estimates of
/// the kind found are below either bound by more than rounding. best_of_each_kind() chooses from
/// these the candidates it chooses from every estimate, in the same order. tighter_bound() and
/// estimate() may run on several threads at once, for different i.
std::vector<double> estimates_by_bound(const std::vector<int>& kinds,
                                       const std::vector<double>& bounds_m, std::size_t per_kind,
                                       unsigned threads,
                                       const std::function<double(std::size_t)>& tighter_bound,
                                       const std::function<double(std::size_t)>& estimate);

}  // namespace swath::planning::split_detail

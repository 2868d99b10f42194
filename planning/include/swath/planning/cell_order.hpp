#pragma once
// In which order, from which corner and in which direction to sweep the cells of an area.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::planning {

/// One way to sweep a cell: where it is entered and left, and the length flown inside it (lines
/// and the turns between them).
struct CellVariant {
  geometry::Point2 entry;
  geometry::Point2 exit;
  double internal_m = 0.0;
};

/// Each cell has up to four variants (first line at the bottom or top, flown one way or the
/// other); `distance` is the transit length between two points (e.g. routed inside the area).
struct CellOrderProblem {
  geometry::Point2 home;
  std::vector<std::vector<CellVariant>> cells;
  std::function<double(geometry::Point2, geometry::Point2)> distance;
  /// Optional: the cells whose lanes the transit from a cell's exit to another's entry crosses,
  /// bit k for cell k (cells from 64 on are never counted). A transit over lanes still to be
  /// flown is what a pilot distrusts (docs/swath-plan.md): the orders below minimise the length
  /// plus `crossing_weight` x the transit's length per such cell (home legs are not counted).
  std::function<std::uint64_t(geometry::Point2, geometry::Point2)> crossed;
  double crossing_weight = 1.0;
  /// Set when `distance(a, b)` is never below geometry::distance(a, b) (straight transits, paths
  /// routed inside an area; rounding aside): nearest neighbour (nearest_neighbour_order(),
  /// heuristic_cell_order()'s start) then asks only the cells near enough to win, same order.
  bool distance_at_least_straight = false;
  /// Set when `distance(a, b) == distance(b, a)` and `crossed(a, b) == crossed(b, a)`, bit for
  /// bit, and both answer a point pair the same whenever asked (a routed metric that keeps one
  /// path per pair of ends): the orderings (heuristic and exact) then ask a pair of points once,
  /// wherever it recurs (a run's exit is another variant's entry), and know its reverse too.
  bool symmetric = false;
};

struct CellVisit {
  std::size_t cell = 0;
  std::size_t variant = 0;
};

struct CellOrder {
  std::vector<CellVisit> visits;
  double length_m = 0.0;      ///< home -> every cell -> home, internal lengths included
  double objective_m = 0.0;   ///< what the order minimises: length_m plus the crossing penalty
  std::size_t crossings = 0;  ///< transits x cells still to be flown whose lanes they cross
};

/// Total length of visiting the cells in `visits` order with those variants.
double tour_length(const CellOrderProblem& problem, const std::vector<CellVisit>& visits);

/// The order's length, objective and crossings, from `problem` alone (a check of the searches).
CellOrder evaluate_order(const CellOrderProblem& problem, const std::vector<CellVisit>& visits);

/// The optimum of the objective by dynamic programming over subsets (Held-Karp with variants; the
/// cells still to be flown are the complement of the subset): O(2^n n² v²). Precondition: at
/// most 16 cells.
CellOrder exact_cell_order(const CellOrderProblem& problem);

/// Nearest neighbour only (from home, the cheapest next transit + cell each time; ties to the lower
/// cell, then variant): O(n² v), or about O(n v) for cells spread evenly with
/// `distance_at_least_straight`. A quick estimate for ranking candidate directions.
CellOrder nearest_neighbour_order(const CellOrderProblem& problem);

/// Nearest neighbour, then local search (move a cell or a block of two or three, swap two,
/// reverse a run; every position below 24 cells, within 8 beyond) where every candidate order gets
/// its best variants by dynamic programming, then up to 24 double-bridge kicks each followed by
/// local search (iterated local search; the kicks from a generator seeded by n: deterministic).
/// Stops after about 200,000 / n candidate orders. Accuracy: Held-Karp's optimum on 12 of 12
/// random instances of 13-14 cells (tests/planning/split_test.cpp).
CellOrder heuristic_cell_order(const CellOrderProblem& problem);

/// A lower bound on the length (so on the objective) of every order of the cells, when `distance`
/// is never below the straight distance (distance_at_least_straight; only straight distances are
/// used): each cell is entered once, from home or another cell's exit, and flown by one of its
/// variants, and the tour comes home once; so the sum over cells of the least (internal length +
/// straight way in) plus the least way home bounds it, and so does the same with the ways out (the
/// larger of the two is returned). O(n v log(n v)) for cells spread evenly (nearest ends by a scan
/// of the ends sorted by x), O((n v)²) at worst; 0 without cells.
double order_lower_bound(const CellOrderProblem& problem);

/// exact_cell_order() up to `exact_limit` cells, heuristic_cell_order() beyond.
CellOrder order_cells(const CellOrderProblem& problem, std::size_t exact_limit = 12);

}  // namespace swath::planning

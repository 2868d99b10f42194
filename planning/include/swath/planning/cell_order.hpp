#pragma once
// In which order, from which corner and in which direction to sweep the cells of an area.

#include <array>
#include <cstddef>
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
};

struct CellVisit {
  std::size_t cell = 0;
  std::size_t variant = 0;
};

struct CellOrder {
  std::vector<CellVisit> visits;
  double length_m = 0.0;  ///< home -> every cell -> home, internal lengths included
};

/// Total length of visiting the cells in `visits` order with those variants.
double tour_length(const CellOrderProblem& problem, const std::vector<CellVisit>& visits);

/// The optimum by dynamic programming over subsets (Held-Karp with variants): O(2^n n² v²).
/// Precondition: at most 16 cells.
CellOrder exact_cell_order(const CellOrderProblem& problem);

/// Nearest neighbour only (from home, the cheapest next transit + cell each time): O(n² v). A
/// quick estimate for ranking candidate directions.
CellOrder nearest_neighbour_order(const CellOrderProblem& problem);

/// Nearest neighbour, then local search (move a cell, swap two, reverse a run, within 8
/// positions) where every candidate order gets its best variants by dynamic programming; stops at
/// a local optimum or after about 200,000 / n candidate orders.
CellOrder heuristic_cell_order(const CellOrderProblem& problem);

/// exact_cell_order() up to `exact_limit` cells, heuristic_cell_order() beyond.
CellOrder order_cells(const CellOrderProblem& problem, std::size_t exact_limit = 10);

}  // namespace swath::planning

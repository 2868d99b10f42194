#pragma once
// The photos over every spot of the ground, on a grid (docs/swath-plan.md): for each
// cell, how many planned photo footprints cover its centre, and whether the centre lies in the
// area. What swath plan --coverage-tif writes as a GeoTIFF.

#include <cstdint>
#include <vector>

#include "swath/planning/survey.hpp"

namespace swath::planning {

struct CoverageGrid {
  double west_m = 0.0, north_m = 0.0;  ///< the grid's top-left corner, local frame
  double cell_m = 0.0;                 ///< square cells
  int width = 0, height = 0;           ///< cells; row 0 is the northernmost
  /// Photo footprints over each cell's centre, row by row (saturated at 65,534).
  std::vector<std::uint16_t> photos;
  /// 1 where the cell's centre lies in the area (holes and no-fly zones excluded), else 0.
  std::vector<std::uint8_t> inside;
};

/// The grid over every photo footprint of every flight (sorties included) and the area, with
/// cells of `cell_m` (> 0) metres, enlarged when the grid would exceed `max_cells`. A footprint is
/// the photo's footprint_across_m x footprint_along_m rectangle centred on it, its long sides
/// along the line it is taken on (a nadir camera). O(cells + photos x footprint cells).
CoverageGrid coverage_grid(const SurveyPlan& plan, double cell_m,
                           std::size_t max_cells = 16'000'000);

}  // namespace swath::planning

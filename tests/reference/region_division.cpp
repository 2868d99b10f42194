#include "region_division.hpp"

#include <cmath>
#include <limits>

#include "swath/planning/division.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::reference {

std::vector<double> paper_region_cuts(const std::vector<geometry::Ring>& rings, double angle_deg,
                                      const std::vector<double>& fractions, double tuning,
                                      std::size_t& evaluations) {
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const auto& ring : rings)
    for (const geometry::Point2& p : ring) {
      const double y = planning::rotate(p, -angle_deg).y;
      y_min = std::min(y_min, y);
      y_max = std::max(y_max, y);
    }
  auto below = [&](double y) {
    ++evaluations;
    return planning::area_below(rings, angle_deg, y);
  };
  const double total = below(y_max + 1), height = y_max - y_min, step = height / 1000;
  const double delta = tuning * total;
  std::vector<double> cuts;
  double previous = y_min, previous_area = 0;
  for (std::size_t i = 0; i + 1 < fractions.size(); ++i) {
    const double target = fractions[i] * total;
    double y = previous + height / static_cast<double>(fractions.size());  // the even split
    double band = below(y) - previous_area;
    // Move the cut a step at a time towards the target band area (the paper's recursion).
    for (int guard = 0; guard < 100000 && std::abs(band - target) > delta; ++guard) {
      y += band < target ? step : -step;
      y = std::clamp(y, previous, y_max);
      band = below(y) - previous_area;
    }
    cuts.push_back(y);
    previous = y;
    previous_area += band;
  }
  return cuts;
}

}  // namespace swath::reference

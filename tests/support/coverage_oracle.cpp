#include "coverage_oracle.hpp"

#include <algorithm>
#include <limits>

#include "swath/geometry/predicates.hpp"

namespace swath::test {

using geometry::Point2;

SampledCoverage sample_coverage(const geometry::Polygon& area,
                                const std::vector<planning::SweepLine>& lines,
                                double footprint_width_m, int per_side) {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const Point2& p : area.outer) {
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  SampledCoverage s;
  for (int i = 0; i < per_side; ++i) {
    for (int j = 0; j < per_side; ++j) {
      const Point2 p{x0 + (x1 - x0) * (i + 0.5) / per_side, y0 + (y1 - y0) * (j + 0.5) / per_side};
      bool inside = geometry::locate_point(p, area.outer) == geometry::Containment::inside;
      for (const auto& hole : area.holes)
        if (inside && geometry::locate_point(p, hole) != geometry::Containment::outside)
          inside = false;
      if (!inside) continue;
      ++s.inside;
      for (const planning::SweepLine& l : lines) {
        // Footprint rectangle: along the segment, within half a footprint across it.
        const Point2 d = l.end - l.start;
        const double len2 = geometry::dot(d, d);
        const double t = geometry::dot(p - l.start, d) / len2;
        const double across = std::abs(geometry::cross(d, p - l.start)) / std::sqrt(len2);
        if (t >= -1e-12 && t <= 1 + 1e-12 && across <= footprint_width_m / 2 + 1e-9) {
          ++s.covered;
          break;
        }
      }
    }
  }
  return s;
}

}  // namespace swath::test

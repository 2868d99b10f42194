// The photos over every cell of a grid (coverage_grid.hpp).
#include "swath/planning/coverage_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swath::planning {
namespace {

struct Footprint {
  geometry::Point2 centre;
  double ux = 1, uy = 0;  // along the line
};

std::vector<Footprint> footprints(const SurveyPlan& plan) {
  std::vector<Footprint> out;
  auto add = [&out](const DroneMission& m, const std::vector<PhotoPoint>& photos) {
    for (const PhotoPoint& p : photos) {
      Footprint f{p.position};
      if (p.line >= 0 && static_cast<std::size_t>(p.line) < m.lines.size()) {
        const SweepLine& l = m.lines[static_cast<std::size_t>(p.line)];
        const double len = std::hypot(l.end.x - l.start.x, l.end.y - l.start.y);
        if (len > 0) {
          f.ux = (l.end.x - l.start.x) / len;
          f.uy = (l.end.y - l.start.y) / len;
        }
      }
      out.push_back(f);
    }
  };
  for (const DronePlan& d : plan.drones) {
    if (d.sorties.empty()) {
      add(d.mission, d.photos);
    } else {
      for (const Sortie& s : d.sorties) add(s.mission, s.photos);
    }
  }
  return out;
}

}  // namespace

CoverageGrid coverage_grid(const SurveyPlan& plan, double cell_m, std::size_t max_cells) {
  const std::vector<Footprint> shots = footprints(plan);
  const double half_across = plan.imaging.footprint_across_m / 2;
  const double half_along = plan.imaging.footprint_along_m / 2;
  const double reach = std::hypot(half_across, half_along);
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  auto extend = [&](geometry::Point2 p, double r) {
    x0 = std::min(x0, p.x - r);
    y0 = std::min(y0, p.y - r);
    x1 = std::max(x1, p.x + r);
    y1 = std::max(y1, p.y + r);
  };
  const geometry::Polygon& area = plan.area;
  for (const geometry::Point2& p : area.outer) extend(p, 0);
  for (const Footprint& f : shots) extend(f.centre, reach);
  CoverageGrid g;
  g.cell_m = cell_m;
  const double w = x1 - x0, h = y1 - y0;
  if (w / g.cell_m * (h / g.cell_m) > static_cast<double>(max_cells))
    g.cell_m = std::sqrt(w * h / static_cast<double>(max_cells));
  g.width = std::max(1, static_cast<int>(std::ceil(w / g.cell_m)));
  g.height = std::max(1, static_cast<int>(std::ceil(h / g.cell_m)));
  g.west_m = x0;
  g.north_m = y0 + g.height * g.cell_m;
  const auto cells = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
  g.photos.assign(cells, 0);
  g.inside.assign(cells, 0);
  auto centre_x = [&](int i) { return g.west_m + (i + 0.5) * g.cell_m; };
  auto centre_y = [&](int j) { return g.north_m - (j + 0.5) * g.cell_m; };

  // Each footprint: the cells of its bounding box whose centres fall in the rectangle.
  for (const Footprint& f : shots) {
    const int i0 =
        std::max(0, static_cast<int>(std::floor((f.centre.x - reach - g.west_m) / g.cell_m)));
    const int i1 = std::min(
        g.width - 1, static_cast<int>(std::ceil((f.centre.x + reach - g.west_m) / g.cell_m)));
    const int j0 =
        std::max(0, static_cast<int>(std::floor((g.north_m - f.centre.y - reach) / g.cell_m)));
    const int j1 = std::min(
        g.height - 1, static_cast<int>(std::ceil((g.north_m - f.centre.y + reach) / g.cell_m)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double dx = centre_x(i) - f.centre.x, dy = centre_y(j) - f.centre.y;
        const double along = dx * f.ux + dy * f.uy, across = -dx * f.uy + dy * f.ux;
        if (std::abs(along) <= half_along && std::abs(across) <= half_across) {
          std::uint16_t& c = g.photos[static_cast<std::size_t>(j) * g.width + i];
          if (c < 65'534) ++c;
        }
      }
  }
  // The area by scanlines through the cell centres (even-odd over the outer ring and the holes).
  std::vector<const geometry::Ring*> rings{&area.outer};
  for (const geometry::Ring& r : area.holes) rings.push_back(&r);
  std::vector<double> xs;
  for (int j = 0; j < g.height; ++j) {
    const double y = centre_y(j);
    xs.clear();
    for (const geometry::Ring* ring : rings)
      for (std::size_t k = 0; k < ring->size(); ++k) {
        const geometry::Point2 a = (*ring)[k], b = (*ring)[(k + 1) % ring->size()];
        if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
      }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int from =
          std::max(0, static_cast<int>(std::ceil((xs[k] - g.west_m) / g.cell_m - 0.5)));
      const int to = std::min(
          g.width - 1, static_cast<int>(std::floor((xs[k + 1] - g.west_m) / g.cell_m - 0.5)));
      for (int i = from; i <= to; ++i) g.inside[static_cast<std::size_t>(j) * g.width + i] = 1;
    }
  }
  return g;
}

}  // namespace swath::planning

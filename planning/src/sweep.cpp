#include "swath/planning/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace swath::planning {

using geometry::Point2;

Point2 rotate(Point2 p, double angle_deg) {
  const double t = angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(t), s = std::sin(t);
  return {c * p.x - s * p.y, s * p.x + c * p.y};
}

std::vector<double> line_offsets(double y_min, double y_max, double spacing, double footprint,
                                 LinePlacement placement) {
  const double height = y_max - y_min;
  std::vector<double> ys;
  if (placement == LinePlacement::centered) {
    // Fewest n with (n - 1) spacing + footprint >= height; the relative slack absorbs rounding
    // so that an exact fit does not cost a line.
    const double needed = (height - footprint) / spacing;
    const auto n = static_cast<std::size_t>(needed <= 0 ? 1 : std::ceil(needed - 1e-9) + 1);
    const double first = y_min + height / 2 - static_cast<double>(n - 1) * spacing / 2;
    for (std::size_t i = 0; i < n; ++i) ys.push_back(first + static_cast<double>(i) * spacing);
    return ys;
  }
  // Paper: y = min_y + step/2; while y <= max_y { line; y += step, or for the last line
  // y = min(y + step/2, max_y) }. Read literally the loop never ends once y reaches max_y; the
  // meaning is one last line and stop.
  double y = std::min(y_min + spacing / 2, y_max);
  while (true) {
    ys.push_back(y);
    if (y + spacing >= y_max) {
      if (y < y_max) ys.push_back(std::min(y + spacing / 2, y_max));
      return ys;
    }
    y += spacing;
  }
}

Sweep plan_sweep(const geometry::Polygon& area, const SweepSettings& s) {
  if (!(s.line_spacing_m > 0) || !(s.footprint_width_m >= s.line_spacing_m) ||
      !(s.turnaround_m >= 0))
    throw std::invalid_argument(
        "plan_sweep: need 0 < spacing <= footprint width and turnaround >= 0");
  Sweep sweep;
  sweep.angle_deg = std::fmod(std::fmod(s.angle_deg, 180.0) + 180.0, 180.0);

  // Work in a frame where the lines are horizontal.
  std::vector<geometry::Ring> rings;
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (std::size_t r = 0; r < geometry::ring_count(area); ++r) {
    geometry::Ring ring;
    for (const Point2& p : geometry::ring_at(area, r)) {
      ring.push_back(rotate(p, -sweep.angle_deg));
      y_min = std::min(y_min, ring.back().y);
      y_max = std::max(y_max, ring.back().y);
    }
    rings.push_back(std::move(ring));
  }
  sweep.height_m = y_max - y_min;
  const std::vector<double> ys =
      line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);

  // Strip k spans [bounds[k], bounds[k + 1]].
  std::vector<double> bounds{y_min};
  for (std::size_t k = 0; k + 1 < ys.size(); ++k) bounds.push_back((ys[k] + ys[k + 1]) / 2);
  bounds.push_back(y_max);
  const std::size_t strips = ys.size();
  std::vector<double> x_lo(strips, std::numeric_limits<double>::infinity());
  std::vector<double> x_hi(strips, -std::numeric_limits<double>::infinity());

  // Each edge, clipped to every strip it crosses, widens that strip's x extent.
  for (const geometry::Ring& ring : rings) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      if (a.y > b.y) std::swap(a, b);
      auto k = static_cast<std::size_t>(
          std::upper_bound(bounds.begin() + 1, bounds.end() - 1, a.y) - bounds.begin() - 1);
      for (; k < strips && bounds[k] <= b.y; ++k) {
        const double lo = std::max(a.y, bounds[k]);
        const double hi = std::min(b.y, bounds[k + 1]);
        if (lo > hi) continue;
        auto x_at = [&](double y) {
          return b.y == a.y ? a.x : a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y);
        };
        const double x0 = b.y == a.y ? std::min(a.x, b.x) : std::min(x_at(lo), x_at(hi));
        const double x1 = b.y == a.y ? std::max(a.x, b.x) : std::max(x_at(lo), x_at(hi));
        x_lo[k] = std::min(x_lo[k], x0);
        x_hi[k] = std::max(x_hi[k], x1);
      }
    }
  }
  for (std::size_t k = 0; k < strips; ++k) {
    if (x_lo[k] > x_hi[k]) continue;
    sweep.lines.push_back({rotate({x_lo[k] - s.turnaround_m, ys[k]}, sweep.angle_deg),
                           rotate({x_hi[k] + s.turnaround_m, ys[k]}, sweep.angle_deg)});
  }
  return sweep;
}

std::vector<SweepLine> order_lines(const Sweep& sweep, StartCorner start,
                                   std::optional<Point2> home) {
  if (sweep.lines.empty()) return {};
  if (start == StartCorner::nearest_home && !home)
    throw std::invalid_argument("order_lines: nearest_home needs a home point");
  // Variants: (bottom first | top first) x (first line flown +x | -x).
  auto variant = [&](bool top_first, bool reverse_first) {
    std::vector<SweepLine> out;
    const std::size_t n = sweep.lines.size();
    for (std::size_t i = 0; i < n; ++i) {
      SweepLine line = sweep.lines[top_first ? n - 1 - i : i];
      if ((i % 2 == 1) != reverse_first) std::swap(line.start, line.end);
      out.push_back(line);
    }
    return out;
  };
  auto score = [&](const std::vector<SweepLine>& v) {
    const Point2 p = v.front().start;
    switch (start) {
      case StartCorner::sw:
        return p.x + p.y;
      case StartCorner::se:
        return -p.x + p.y;
      case StartCorner::nw:
        return p.x - p.y;
      case StartCorner::ne:
        return -p.x - p.y;
      case StartCorner::nearest_home:
        break;
    }
    return geometry::distance(*home, p) + geometry::distance(v.back().end, *home);
  };
  std::vector<SweepLine> best;
  double best_score = std::numeric_limits<double>::infinity();
  for (bool top_first : {false, true})
    for (bool reverse_first : {false, true}) {
      std::vector<SweepLine> v = variant(top_first, reverse_first);
      const double sc = score(v);
      if (sc < best_score - 1e-9) {
        best_score = sc;
        best = std::move(v);
      }
    }
  return best;
}

std::vector<Point2> line_waypoints(const SweepLine& line, std::optional<double> spacing_m) {
  std::vector<Point2> points{line.start};
  const double length = geometry::distance(line.start, line.end);
  if (spacing_m && *spacing_m > 0 && length > *spacing_m) {
    const auto parts = static_cast<std::size_t>(std::ceil(length / *spacing_m - 1e-9));
    for (std::size_t i = 1; i < parts; ++i)
      points.push_back(line.start + (line.end - line.start) *
                                        (static_cast<double>(i) / static_cast<double>(parts)));
  }
  points.push_back(line.end);
  return points;
}

}  // namespace swath::planning

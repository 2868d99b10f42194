#include "swath/geometry/min_height.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "swath/geometry/convex_hull.hpp"

namespace swath::geometry {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

double normalise_line_angle(double deg) {
  double a = std::fmod(deg, 180.0);
  if (a < 0) a += 180.0;
  if (a >= 180.0) a -= 180.0;
  return a;
}

}  // namespace

double height_at(const std::vector<Point2>& points, double angle_deg) {
  // Project on the normal of the sweep lines.
  const double t = angle_deg / kDegPerRad;
  const Point2 normal{-std::sin(t), std::cos(t)};
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Point2& p : points) {
    const double s = dot(p, normal);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return points.empty() ? 0.0 : hi - lo;
}

namespace {

// Rotating calipers over a counter-clockwise hull without collinear vertices.
SweepDirection calipers(const Ring& hull) {
  const std::size_t h = hull.size();
  if (h < 3) {
    // Degenerate: a segment (or point) has height 0 along itself.
    if (h < 2) return {0.0, 0.0};
    const Point2 d = hull[1] - hull[0];
    return {normalise_line_angle(std::atan2(d.y, d.x) * kDegPerRad), 0.0};
  }
  // Rotating calipers: for edge i, the antipodal vertex j is the farthest from its line; j only
  // moves forward as i does, so the whole pass is O(h). Along one edge, distances compare by
  // their cross products (same length); the root and the angle only for a new best.
  SweepDirection best{0.0, std::numeric_limits<double>::infinity()};
  auto reach = [&](std::size_t i, std::size_t k) {  // |edge i| x distance of vertex k from it
    return cross(hull[(i + 1) % h] - hull[i], hull[k % h] - hull[i]);
  };
  // The first antipode by a full pass: hull vertices nearly collinear with edge 0 (a field's
  // straight side traced in several points) can sit a rounding error below it, and a climb from
  // vertex 1 would stop there at height 0. Later climbs start high, where such a plateau is an
  // edge parallel to edge i and either end gives the same height.
  std::size_t j = 1;
  for (std::size_t k = 2; k < h; ++k)
    if (reach(0, k) > reach(0, j)) j = k;
  for (std::size_t i = 0; i < h; ++i) {
    if (j < i + 1) j = i + 1;
    while (reach(i, j + 1) >= reach(i, j) && j + 1 < i + h) ++j;
    const Point2 e = hull[(i + 1) % h] - hull[i];
    const double height = reach(i, j) / std::sqrt(dot(e, e));
    if (height > best.height_m) continue;
    const double angle = normalise_line_angle(std::atan2(e.y, e.x) * kDegPerRad);
    if (height < best.height_m || angle < best.angle_deg) best = {angle, height};
  }
  return best;
}

}  // namespace

SweepDirection min_height_rotation(const std::vector<Point2>& points) {
  return calipers(convex_hull(points));
}

SweepDirection min_height_of_simple_ring(const Ring& ring) {
  return calipers(convex_hull_of_simple_ring(ring));
}

SweepDirection min_height_scan(const std::vector<Point2>& points, double step_deg) {
  SweepDirection best{0.0, std::numeric_limits<double>::infinity()};
  const auto steps = static_cast<long>(std::ceil(180.0 / step_deg - 1e-9));
  for (long k = 0; k < steps; ++k) {
    const double angle = static_cast<double>(k) * step_deg;
    const double height = height_at(points, angle);
    if (height < best.height_m) best = {angle, height};
  }
  return best;
}

double line_bearing_deg(double angle_deg) {
  return normalise_line_angle(90.0 - angle_deg);
}

}  // namespace swath::geometry

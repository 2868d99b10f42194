#include "swath/geometry/regularity.hpp"

#include <cmath>
#include <numbers>

namespace swath::geometry {

std::vector<double> interior_angles_deg(const Ring& ring) {
  const std::size_t n = ring.size();
  const double orientation_sign = signed_area(ring) >= 0 ? 1.0 : -1.0;
  std::vector<double> angles(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 in = ring[i] - ring[(i + n - 1) % n];
    const Point2 out = ring[(i + 1) % n] - ring[i];
    // Signed turn (left positive for a counter-clockwise ring); interior angle = 180 - turn.
    const double turn = std::atan2(cross(in, out), dot(in, out)) * orientation_sign;
    angles[i] = 180.0 - turn * 180.0 / std::numbers::pi;
  }
  return angles;
}

Regularity regularity(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return {};
  const std::vector<double> angles = interior_angles_deg(ring);
  double mean_angle = 0.0;
  for (double a : angles) mean_angle += a;
  mean_angle /= static_cast<double>(n);
  const double mean_edge = perimeter(ring) / static_cast<double>(n);

  double a = 0.0;
  double m = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    a += std::abs(mean_angle - angles[i]) / 360.0;
    m += std::abs(mean_edge - distance(ring[(i + n - 1) % n], ring[i])) / mean_edge;
  }
  Regularity r;
  r.angle = 1.0 - a / static_cast<double>(n);
  r.edge = 1.0 - m / static_cast<double>(n);
  r.overall = (r.angle + r.edge) / 2.0;
  return r;
}

}  // namespace swath::geometry

#include "random_polygons.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

namespace swath::test {

using geometry::Point2;
using geometry::Ring;

namespace {
std::vector<double> sorted_angles(Rng& rng, std::size_t n) {
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  std::vector<double> a(n);
  for (double& x : a) x = angle(rng);
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}
}  // namespace

Ring random_star_polygon(Rng& rng, std::size_t n, double r_min, double r_max) {
  std::uniform_real_distribution<double> radius(r_min, r_max);
  Ring ring;
  for (double t : sorted_angles(rng, n)) {
    const double r = radius(rng);
    ring.push_back({r * std::cos(t), r * std::sin(t)});
  }
  return ring;
}

Ring random_field_polygon(Rng& rng, std::size_t n, double r) {
  std::uniform_real_distribution<double> phase(0.0, 2 * std::numbers::pi);
  const double spacing = 2 * std::numbers::pi * r / double(n);
  std::uniform_real_distribution<double> jitter(-0.2 * spacing, 0.2 * spacing);
  const double p2 = phase(rng), p3 = phase(rng), p5 = phase(rng);
  Ring ring;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * double(i) / double(n);
    const double radius = r * (1 + 0.25 * std::cos(2 * t + p2) + 0.08 * std::cos(3 * t + p3) +
                               0.04 * std::cos(5 * t + p5)) +
                          jitter(rng);
    ring.push_back({radius * std::cos(t), radius * std::sin(t)});
  }
  return ring;
}

Ring random_convex_polygon(Rng& rng, std::size_t n, double a, double b) {
  std::uniform_real_distribution<double> turn(0.0, 180.0);
  Ring ring;
  for (double t : sorted_angles(rng, n)) ring.push_back({a * std::cos(t), b * std::sin(t)});
  return transformed(ring, turn(rng), 0.0, 0.0);
}

Ring random_grid_ring(Rng& rng, std::size_t n, int grid) {
  std::uniform_int_distribution<int> coordinate(0, grid - 1);
  std::set<std::pair<int, int>> seen;
  Ring ring;
  for (std::size_t i = 0; i < n; ++i) {
    const int x = coordinate(rng);
    const int y = coordinate(rng);
    if (seen.insert({x, y}).second) ring.push_back({double(x), double(y)});
  }
  return ring;
}

Ring comb_polygon(int teeth, double w, double h, double b) {
  // Base (0,0)-(width,0); tooth k spans x in [2kw, 2kw + w] up to b + h; gaps come down to b.
  const double width = (2 * teeth - 1) * w;
  Ring ring{{0, 0}, {width, 0}};
  for (int k = teeth - 1; k >= 0; --k) {
    const double x0 = 2 * k * w;
    ring.push_back({x0 + w, b + h});
    ring.push_back({x0, b + h});
    if (k > 0) {
      ring.push_back({x0, b});
      ring.push_back({x0 - w, b});
    }
  }
  return ring;
}

Ring spiral_polygon(int arms, double length, double gap, double half_width) {
  // Centre line: axis-aligned arms turning left, shortening by `gap` every second arm.
  std::vector<Point2> centre{{0, 0}};
  const Point2 directions[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  double arm = length;
  for (int k = 0; k < arms; ++k) {
    centre.push_back(centre.back() + directions[k % 4] * arm);
    if (k % 2 == 1) arm -= gap;
  }
  // Offset both sides; at a right-angle corner the offsets of both arms meet at P + h(n1 + n2).
  auto normal = [&](std::size_t segment) {  // left normal of centre[segment] -> centre[segment + 1]
    const Point2 d = directions[segment % 4];
    return Point2{-d.y, d.x};
  };
  Ring left, right;
  const std::size_t n = centre.size();
  for (std::size_t i = 0; i < n; ++i) {
    Point2 offset = i == 0 ? normal(0) : i + 1 == n ? normal(i - 1) : normal(i - 1) + normal(i);
    left.push_back(centre[i] + offset * half_width);
    right.push_back(centre[i] - offset * half_width);
  }
  Ring ring = right;
  ring.insert(ring.end(), left.rbegin(), left.rend());
  return ring;
}

Ring transformed(const Ring& ring, double angle_deg, double dx, double dy) {
  const double t = angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(t), s = std::sin(t);
  Ring out;
  for (const Point2& p : ring) out.push_back({c * p.x - s * p.y + dx, s * p.x + c * p.y + dy});
  return out;
}

}  // namespace swath::test

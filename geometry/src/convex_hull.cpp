#include "swath/geometry/convex_hull.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "swath/geometry/predicates.hpp"

namespace swath::geometry {

Ring convex_hull(const std::vector<Point2>& points) {
  std::vector<Point2> p = points;
  std::sort(p.begin(), p.end(),
            [](Point2 a, Point2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;

  // Andrew's monotone chain: lower hull left to right, upper hull right to left; pop on any turn
  // that is not strictly counter-clockwise so collinear points are dropped.
  Ring hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && orientation(hull[k - 2], hull[k - 1], p[i]) != Orientation::counter_clockwise)
      --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower &&
           orientation(hull[k - 2], hull[k - 1], p[i]) != Orientation::counter_clockwise)
      --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  if (hull.size() == 2 && hull[0] == hull[1]) hull.pop_back();
  return hull;
}

namespace {

// orientation() == counter_clockwise with the same filter (Shewchuk's stage-A bound), written
// branch-light for the walk below, which asks it a few times per vertex.
inline bool strictly_left(Point2 a, Point2 b, Point2 c) {
  const double l = (a.x - c.x) * (b.y - c.y), r = (a.y - c.y) * (b.x - c.x);
  const double det = l - r;
  const double bound = 3.3306690738754716e-16 * (std::abs(l) + std::abs(r));
  if (det > bound) return true;
  if (det < -bound) return false;
  return orientation_exact(a, b, c) == Orientation::counter_clockwise;
}

}  // namespace

Ring convex_hull_of_simple_ring(const Ring& ring) {
  // Consecutive duplicates (and a closing copy of the first vertex) carry nothing: skipped as
  // the walk goes, without copying the ring.
  std::size_t n = ring.size();
  while (n > 1 && ring[n - 1] == ring[0]) --n;
  const auto left = strictly_left;
  // Start from a triangle: the first vertex, the last of the collinear run after it, and the
  // first vertex off their line (a simple ring's collinear run goes one way along its line).
  std::size_t k = 1;
  while (k < n && ring[k] == ring[0]) ++k;
  if (k >= n) return convex_hull(ring);
  const std::size_t second = k;
  for (++k; k < n; ++k)
    if (!(ring[k] == ring[k - 1]) &&
        orientation(ring[0], ring[second], ring[k]) != Orientation::collinear)
      break;
  if (k >= n) return convex_hull(ring);  // all on one line
  const Point2 a = ring[0], b = ring[k - 1], c = ring[k];
  // deque[bottom..top] (vertex indices), deque[bottom] == deque[top] == the vertex added last.
  std::vector<std::uint32_t> deque(2 * n + 4);
  std::size_t bottom = n, top = bottom + 3;
  deque[bottom] = deque[top] = std::uint32_t(k);
  const bool counter_clockwise = left(a, b, c);
  deque[bottom + 1] = std::uint32_t(counter_clockwise ? 0 : k - 1);
  deque[bottom + 2] = std::uint32_t(counter_clockwise ? k - 1 : 0);
  for (std::size_t i = k + 1; i < n; ++i) {
    const Point2 v = ring[i];
    // Inside the hull so far (strictly left of both edges at the last vertex): nothing changes.
    if (left(ring[deque[bottom]], ring[deque[bottom + 1]], v) &&
        left(ring[deque[top - 1]], ring[deque[top]], v))
      continue;
    while (top - bottom > 1 && !left(ring[deque[bottom]], ring[deque[bottom + 1]], v)) ++bottom;
    deque[--bottom] = std::uint32_t(i);
    while (top - bottom > 1 && !left(ring[deque[top - 1]], ring[deque[top]], v)) --top;
    deque[++top] = std::uint32_t(i);
  }
  // The walk keeps a vertex that lies on the hull edge between the ring's last and first
  // vertices; the sorted hull drops collinear vertices, so this one does too.
  Ring hull;
  for (std::size_t d = bottom; d < top; ++d) hull.push_back(ring[deque[d]]);
  Ring out;
  for (std::size_t d = 0; d < hull.size(); ++d) {
    const Point2 prev = out.empty() ? hull[(d + hull.size() - 1) % hull.size()] : out.back();
    if (left(prev, hull[d], hull[(d + 1) % hull.size()])) out.push_back(hull[d]);
  }
  return out.size() >= 3 ? out : convex_hull(ring);
}

}  // namespace swath::geometry

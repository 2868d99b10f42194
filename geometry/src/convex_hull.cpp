#include "swath/geometry/convex_hull.hpp"

#include <algorithm>

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

}  // namespace swath::geometry

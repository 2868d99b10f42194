#pragma once
// What the two halves of the division share (division.cpp: along a path and by area;
// division_lanes.cpp: by lanes): clipping in the rotated frame, the home legs, the shares and
// the greedy cuts' bisection.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/planning/division.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning::division_detail {

using geometry::Point2;
using geometry::Ring;

// Sutherland-Hodgman against p[axis] <= limit (keep_below) or >= limit, in the rotated frame
// (axis 0: x, 1: y).
inline Ring clip_half(const Ring& ring, double limit, bool keep_below, int axis = 1) {
  Ring out;
  auto coordinate = [axis](Point2 p) { return axis == 0 ? p.x : p.y; };
  auto inside = [&](Point2 p) {
    return keep_below ? coordinate(p) <= limit : coordinate(p) >= limit;
  };
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    const bool in_a = inside(a), in_b = inside(b);
    if (in_a) out.push_back(a);
    if (in_a != in_b)
      out.push_back(a + (b - a) * ((limit - coordinate(a)) / (coordinate(b) - coordinate(a))));
  }
  return out;
}

inline Ring rotated(const Ring& ring, double angle_deg) {
  Ring out;
  for (const Point2& p : ring) out.push_back(rotate(p, angle_deg));
  return out;
}

// Twice the distance from each drone's home to the farthest of `points` (paper:
// findFlyFromToHomeCost).
inline std::vector<double> home_costs(const std::vector<Point2>& points,
                                      const std::vector<DroneResource>& drones) {
  std::vector<double> cost;
  for (const DroneResource& d : drones) {
    double far = 0;
    for (const Point2& p : points) far = std::max(far, geometry::distance(d.home, p));
    cost.push_back(2 * far);
  }
  return cost;
}

// Whether a flight of `length_m` taking `time_s` is more than drone `d` can fly: its range, or
// its flight time limit (its charge: the climbs, stops and descents count, not just the metres).
inline bool beyond_limits(const DroneResource& d, double length_m, double time_s) {
  return (d.range_m && length_m > *d.range_m * (1 + 1e-12)) ||
         (d.flight_limit_s && time_s > *d.flight_limit_s * (1 + 1e-12));
}

// Shares from the corrected capabilities; budgets where ranges are known.
inline std::vector<double> weights(const std::vector<DroneResource>& drones,
                                   const std::vector<double>& home_cost,
                                   std::vector<std::optional<double>>& budgets) {
  std::vector<double> w;
  budgets.assign(drones.size(), std::nullopt);
  for (std::size_t i = 0; i < drones.size(); ++i) {
    const DroneResource& d = drones[i];
    if (d.range_m) {
      const double budget = *d.range_m - home_cost[i];
      if (!(budget > 0))
        throw base::InputError(
            "drone " + d.name + ": flying to the farthest point of the survey and back (" +
            std::to_string(std::lround(home_cost[i])) + " m) takes its whole range (" +
            std::to_string(std::lround(*d.range_m)) + " m)");
      budgets[i] = budget;
      w.push_back(budget);
    } else {
      w.push_back(d.capability);
    }
  }
  return w;
}
// The greedy cuts' one step: the point farthest from `from` towards `to` (either direction)
// where `fits` holds (`fits(from)` assumed): `to` when it fits, else bisection until the bracket
// is within `tolerance` or `max_steps` halvings are done.
template <class Fits>
double farthest_fitting(double from, double to, double tolerance, const Fits& fits,
                        int max_steps = std::numeric_limits<int>::max()) {
  if (fits(to)) return to;
  double ok = from, fail = to;
  for (int k = 0; k < max_steps && std::abs(fail - ok) > tolerance; ++k) {
    const double mid = (ok + fail) / 2;
    (fits(mid) ? ok : fail) = mid;
  }
  return ok;
}

}  // namespace swath::planning::division_detail

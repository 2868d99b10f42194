// A direction per region (docs/swath-plan.md): the area cut by chords from reflex vertices into
// regions, each swept at its own best direction, kept when the whole routed path is shorter.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/planning/cell_order.hpp"
#include "swath/planning/coverage.hpp"
#include "swath/planning/lane_runs.hpp"

#include "split_candidate.hpp"

namespace swath::planning::split_detail {
namespace {

// Directions worth trying for one region: its four longest edges' (its hull's included), `also`
// and a scan every 30 degrees; closer than 0.25 degrees count once. Few: every one is a lane_runs.
std::vector<double> region_angles(const geometry::Ring& region, const std::vector<double>& also) {
  std::vector<std::pair<double, double>> edges;  // (length, angle)
  const geometry::Ring hull = geometry::convex_hull(region);
  for (const geometry::Ring* ring : {&region, &hull})
    for (std::size_t i = 0; i < ring->size(); ++i) {
      const Point2 a = (*ring)[i], b = (*ring)[(i + 1) % ring->size()];
      edges.push_back({geometry::distance(a, b), line_angle(a, b)});
    }
  std::sort(edges.begin(), edges.end(), std::greater<>());
  std::vector<double> angles;
  for (const auto& edge : edges) {  // not a structured binding: clang 14 cannot capture one
    const double angle = edge.second;
    if (angles.size() >= 4) break;
    if (std::none_of(angles.begin(), angles.end(), [&](double a) {
          const double d = std::abs(a - angle);
          return std::min(d, 180 - d) <= 0.25;
        }))
      angles.push_back(angle);
  }
  for (double a : also) angles.push_back(std::fmod(std::fmod(a, 180.0) + 180.0, 180.0));
  for (double a = 0; a < 180 - 1e-9; a += 30) angles.push_back(a);
  std::sort(angles.begin(), angles.end());
  std::vector<double> unique;
  for (double a : angles)
    if (unique.empty() || a - unique.back() > 0.25) unique.push_back(a);
  if (unique.size() > 1 && unique.back() - unique.front() > 179.75) unique.pop_back();
  return unique;
}

// One region swept by runs at its best direction by the straight-transit estimate (lines, turns
// and its runs chained nearest first from its centroid, the legs to and from it left out): its
// lanes lie inside it and see all of it (lane_runs' coverage lanes), so regions that tile the area
// see all of it too.
struct RegionSweep {
  geometry::Ring ring;
  double angle_deg = 0;
  double estimate_m = std::numeric_limits<double>::infinity();
  Candidate c;
};

// The first lane ordinate of the whole area's grid at `angle_deg` (the frame turned by -angle).
double grid_ordinate(const geometry::Ring& area, double angle_deg, const SplitSettings& s) {
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const Point2& p : area) {
    const double y = rotate(p, -angle_deg).y;
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
  }
  const std::vector<double> ys =
      line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  return ys.empty() ? y_min : ys.front();
}

RegionSweep sweep_region(geometry::Ring ring, const geometry::Ring& area, const SplitSettings& s,
                         const std::vector<double>& also) {
  SplitSettings rs = s;
  rs.seen_rings = {ring};
  rs.bridge_rings.clear();
  const Point2 centre = geometry::centroid(geometry::Polygon{ring, {}});
  RegionSweep best;
  std::vector<Point2>
      samples;  // lane_runs' buffer, its capacity kept from one direction to the next
  for (const double angle : region_angles(ring, also)) {
    // Every lane of the grid kept: across a region narrower than two footprints every lane is
    // "short", and dropping those the others' footprints already see would keep one lane per
    // footprint width, the side overlap lost (the one-direction plan's slivers are the area's).
    // On the whole area's grid at this direction: neighbours at one direction keep the spacing
    // across their seam.
    Candidate c =
        sweep_runs({ring}, angle, rs, false, samples, false, grid_ordinate(area, angle, s));
    if (c.cells.empty()) continue;
    // Without the legs from and back to the centre: a region is entered from its neighbour.
    CellOrderProblem p = problem_for(c, centre, straight_m);
    p.distance_at_least_straight = true;
    const CellOrder order = nearest_neighbour_order(p);
    const CellVariant& first = p.cells[order.visits.front().cell][order.visits.front().variant];
    const CellVariant& last = p.cells[order.visits.back().cell][order.visits.back().variant];
    const double estimate = order.length_m - geometry::distance(centre, first.entry) -
                            geometry::distance(last.exit, centre);
    if (estimate < best.estimate_m) {
      best.angle_deg = angle;
      best.estimate_m = estimate;
      best.c = std::move(c);
    }
  }
  best.ring = std::move(ring);
  return best;
}

// The two rings a chord cuts `ring` into: from reflex vertex `v` along the extension of one of its
// edges (`backward`: of the edge arriving at v, else of the edge leaving it) to where it first
// meets the boundary. At a reflex vertex both extensions enter the area. Empty when the chord is
// degenerate.
std::vector<geometry::Ring> chord_cut(const geometry::Ring& ring, std::size_t v, bool backward) {
  const std::size_t n = ring.size();
  const Point2 o = ring[v];
  const Point2 d = backward ? o - ring[(v + n - 1) % n] : o - ring[(v + 1) % n];
  double best_t = std::numeric_limits<double>::infinity();
  std::size_t best_e = n;
  for (std::size_t e = 0; e < n; ++e) {
    if (e == v || (e + 1) % n == v) continue;  // the edges at v
    const Point2 a = ring[e], f = ring[(e + 1) % n] - a;
    const double denominator = geometry::cross(d, f);
    if (denominator == 0) continue;
    const double t = geometry::cross(a - o, f) / denominator;
    const double u = geometry::cross(a - o, d) / denominator;
    if (t > 1e-9 && u >= 0 && u <= 1 && t < best_t) {
      best_t = t;
      best_e = e;
    }
  }
  if (best_e == n) return {};
  const Point2 p = o + d * best_t;
  // One ring from v forward to the hit edge's start, then p; the other from p on round to v.
  std::vector<geometry::Ring> out(2);
  for (std::size_t i = v;; i = (i + 1) % n) {
    out[0].push_back(ring[i]);
    if (i == best_e) break;
  }
  out[0].push_back(p);
  out[1].push_back(p);
  for (std::size_t i = (best_e + 1) % n;; i = (i + 1) % n) {
    out[1].push_back(ring[i]);
    if (i == v) break;
  }
  for (geometry::Ring& r : out) {  // a chord ending at a vertex repeats it
    geometry::Ring clean;
    for (const Point2& q : r)
      if (clean.empty() || geometry::distance(clean.back(), q) > 1e-9) clean.push_back(q);
    while (clean.size() > 1 && geometry::distance(clean.back(), clean.front()) <= 1e-9)
      clean.pop_back();
    if (clean.size() < 3 || !(geometry::signed_area(clean) > 1e-6)) return {};
    r = std::move(clean);
  }
  return out;
}

// Regions cut from one ring (no holes) greedily: of every chord from a reflex vertex along one
// of its edges (chord_cut) in every region, the cut whose two parts, each swept at its own best
// direction, save the most on the estimate (less the chord, a transit between them); while a cut
// saves more than 1 % of the region's estimate, up to six regions. The regions after each cut:
// the estimate leaves the order out, so the routed order picks among them. Rings with more than 12
// reflex vertices are left whole (every chord costs two regions' direction searches).
std::vector<std::vector<RegionSweep>> regions_by_chords(const geometry::Ring& ring, double main_deg,
                                                        const SplitSettings& s) {
  const auto reflex = [](const geometry::Ring& r) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Point2 a = r[(i + r.size() - 1) % r.size()], b = r[i], c = r[(i + 1) % r.size()];
      if (geometry::cross(b - a, c - b) <
          -1e-9 * geometry::distance(a, c) * geometry::distance(a, c))
        out.push_back(i);
    }
    return out;
  };
  if (ring.size() < 4 || reflex(ring).size() > 12) return {};
  std::vector<RegionSweep> regions{sweep_region(ring, ring, s, {main_deg})};
  if (regions.front().c.cells.empty()) return {};
  std::vector<std::vector<RegionSweep>> snapshots;  // after each cut
  while (regions.size() < 6) {
    double best_gain = 0;
    std::size_t best_r = 0;
    std::vector<RegionSweep> best_parts;
    for (std::size_t r = 0; r < regions.size(); ++r)
      for (const std::size_t v : reflex(regions[r].ring))
        for (const bool backward : {false, true}) {
          std::vector<geometry::Ring> parts = chord_cut(regions[r].ring, v, backward);
          if (parts.empty()) continue;
          const double chord_m = geometry::distance(parts[0].front(), parts[0].back());
          std::vector<RegionSweep> swept;
          double parts_m = 0;
          for (geometry::Ring& part : parts) {
            swept.push_back(sweep_region(std::move(part), ring, s, {regions[r].angle_deg}));
            parts_m += swept.back().estimate_m;
          }
          // The region's estimate less its parts', less the chord: parts are joined by a transit
          // that the estimates (legs left out) do not count, about as long as their seam.
          const double gain = regions[r].estimate_m - parts_m - chord_m;
          if (gain > 0.01 * regions[r].estimate_m && gain > best_gain) {
            best_gain = gain;
            best_r = r;
            best_parts = std::move(swept);
          }
        }
    if (best_parts.empty()) break;
    regions[best_r] = std::move(best_parts[0]);
    regions.push_back(std::move(best_parts[1]));
    snapshots.push_back(regions);
  }
  return snapshots;
}

// The regions' runs as one candidate, ordered together; `angle_deg` the largest region's.
Candidate mixed_candidate(const std::vector<RegionSweep>& regions) {
  Candidate c;
  c.method = SplitCells::runs;
  double largest = -1;
  for (const RegionSweep& r : regions) {
    const double a = std::abs(geometry::signed_area(r.ring));
    if (a > largest) {
      largest = a;
      c.angle_deg = r.angle_deg;
    }
    for (std::size_t k = 0; k < r.c.sweeps.size(); ++k) {
      c.cells.push_back(r.c.cells[k]);
      c.sweeps.push_back(r.c.sweeps[k]);
    }
  }
  return c;
}

}  // namespace

// The best plan with a direction per region, when its whole routed path is shorter than `single`'s
// (the best one-direction plan) and it sees >= 99.9 % of `to_see`, footprints along each line's
// own direction. The regions: chords cut greedily from reflex vertices (regions_by_chords); an
// area with holes or in several pieces keeps one direction.
std::optional<SplitPlan> per_region_plan(const std::vector<geometry::Ring>& rings, Point2 home,
                                         const SplitSettings& s, const geometry::Polygon& to_see,
                                         const SplitPlan& single, RoutedMetric& routed) {
  if (rings.size() != 1) return std::nullopt;
  std::optional<SplitPlan> best;
  for (const std::vector<RegionSweep>& regions :
       regions_by_chords(rings.front(), single.angle_deg, s)) {
    Candidate c = mixed_candidate(regions);
    SplitPlan plan = ordered_plan(c, home, routed);
    const double shortest = best ? best->path_length_m : single.path_length_m;
    if (!(plan.path_length_m < shortest - 1e-6)) continue;
    if (measure_coverage_any_direction(to_see, plan.lines, s.footprint_width_m, 1024)
            .covered_fraction < 0.999)
      continue;
    for (const RegionSweep& r : regions) {
      plan.regions.push_back(r.ring);
      plan.region_angles_deg.push_back(r.angle_deg);
    }
    plan.candidates = single.candidates;
    best = std::move(plan);
  }
  return best;
}

}  // namespace swath::planning::split_detail

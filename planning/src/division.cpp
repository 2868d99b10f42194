// Division of the survey among drones along a path (divide_path) and by area (divide_region);
// by lanes in division_lanes.cpp.
#include "swath/planning/division.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "swath/base/input_error.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/planning/sweep.hpp"

#include "division_shared.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;
using geometry::Ring;

using division_detail::clip_half;
using division_detail::farthest_fitting;
using division_detail::home_costs;
using division_detail::rotated;
using division_detail::weights;

// Cumulative lengths along a path, for points at a distance.
struct PathIndex {
  const SurveyPath& path;
  std::vector<double> at;
  explicit PathIndex(const SurveyPath& p) : path(p) {
    at.push_back(0);
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i)
      at.push_back(at.back() + geometry::distance(p.points[i], p.points[i + 1]));
  }
  double length() const { return at.back(); }
  Point2 point(double s) const {
    const auto k = static_cast<std::size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin());
    if (k == 0) return path.points.front();
    if (k >= at.size()) return path.points.back();
    const double t = (s - at[k - 1]) / std::max(at[k] - at[k - 1], 1e-300);
    return path.points[k - 1] + (path.points[k] - path.points[k - 1]) * t;
  }
};

// The measured flight of drone i over [s, e] of the path.
FlightCost measured(const PathIndex& index, std::size_t i, const FlightMeasure& measure, double s,
                    double e) {
  std::vector<double> at;
  if (s > 0) at.push_back(s);
  if (e < index.length()) at.push_back(e);
  return measure(i, cut_path(index.path, at)[s > 0 ? 1 : 0]);
}

// Flight time of drone i over [s, e] of the path: measured where a measure is given, else straight
// home legs at cruise speed; +inf beyond its range or flight time limit. Without a measure the
// flight time limit is checked on `limit`'s measured flight where given (the straight legs count
// no climb, stop or descent).
double piece_time(const PathIndex& index, const std::vector<DroneResource>& drones, std::size_t i,
                  const FlightMeasure& measure, const FlightMeasure& limit, double s, double e) {
  const DroneResource& d = drones[i];
  double distance = 0, time_s = 0;
  if (measure) {
    if (!(e > s)) return 0.0;
    const FlightCost cost = measured(index, i, measure, s, e);
    distance = cost.length_m;
    time_s = cost.time_s;
  } else {
    distance = geometry::distance(d.home, index.point(s)) + (e - s) +
               geometry::distance(index.point(e), d.home);
    time_s = distance / d.speed_m_s;
  }
  const double limited_s = !measure && limit && d.flight_limit_s && e > s
                               ? measured(index, i, limit, s, e).time_s
                               : time_s;
  if (division_detail::beyond_limits(d, distance, limited_s))
    return std::numeric_limits<double>::infinity();
  return time_s;
}

// Greedy cuts that keep every drone within `makespan`: each takes the longest piece it can.
std::vector<double> cuts_within(const PathIndex& index, const std::vector<DroneResource>& drones,
                                const FlightMeasure& measure, const FlightMeasure& limit,
                                double makespan) {
  auto time_of = [&](std::size_t i, double s, double e) {
    return piece_time(index, drones, i, measure, limit, s, e);
  };
  std::vector<double> cuts;
  double s = 0;
  for (std::size_t i = 0; i < drones.size(); ++i) {
    const double start = s;
    s = farthest_fitting(
        start, index.length(), 1e-9 * (1 + index.length()),
        [&](double e) { return time_of(i, start, e) <= makespan; }, 60);
    if (i + 1 < drones.size()) cuts.push_back(s);
  }
  cuts.push_back(s);  // how far the fleet gets
  return cuts;
}

DivisionResult finish_path(const SurveyPath& path, const std::vector<DroneResource>& drones,
                           std::vector<double> cuts, const std::vector<double>& home_cost,
                           const std::vector<std::optional<double>>& budgets,
                           const FlightMeasure& measure, const FlightMeasure& limit) {
  const PathIndex index(path);
  DivisionResult r;
  const double reach = cuts.back();
  cuts.pop_back();
  r.unflown_path_m = std::max(0.0, index.length() - reach);
  std::vector<double> inner;
  for (double c : cuts)
    if (c > 0 && c < index.length()) inner.push_back(c);
  // Pieces follow the cuts; a drone whose cut equals the previous one gets an empty piece.
  std::vector<double> bounds{0};
  bounds.insert(bounds.end(), cuts.begin(), cuts.end());
  bounds.push_back(reach);
  for (std::size_t i = 0; i < drones.size(); ++i) {
    DroneWork w;
    const double s = bounds[i], e = std::max(bounds[i], bounds[i + 1]);
    if (e > s) {
      std::vector<double> at;
      if (s > 0) at.push_back(s);
      if (e < index.length()) at.push_back(e);
      const std::vector<SurveyPath> pieces = cut_path(path, at);
      w.path = pieces[s > 0 ? 1 : 0];
    }
    w.share = index.length() > 0 ? (e - s) / index.length() : 0;
    w.home_cost_m = home_cost[i];
    w.budget_m = budgets[i];
    w.estimated_time_s = e > s ? piece_time(index, drones, i, measure, limit, s, e) : 0;
    r.makespan_s = std::max(r.makespan_s, w.estimated_time_s);
    r.drones.push_back(std::move(w));
  }
  return r;
}

}  // namespace

DivisionResult divide_path(const SurveyPath& path, const std::vector<DroneResource>& drones,
                           Balance balance, const FlightMeasure& measure,
                           const FlightMeasure& limit) {
  const PathIndex index(path);
  const std::vector<double> home_cost = home_costs(path.points, drones);
  std::vector<std::optional<double>> budgets;
  const std::vector<double> w = weights(drones, home_cost, budgets);
  const double total_w = std::accumulate(w.begin(), w.end(), 0.0);
  const double length = index.length();
  const bool budgeted =
      std::all_of(budgets.begin(), budgets.end(), [](const auto& b) { return b.has_value(); });
  const bool short_of_path = budgeted && total_w < length;

  // Proportional cuts (short fleet: each flies its budget).
  std::vector<double> proportional;
  double s = 0;
  for (std::size_t i = 0; i < drones.size(); ++i) {
    s += short_of_path ? w[i] : w[i] / total_w * length;
    proportional.push_back(std::min(s, length));
  }
  if (!short_of_path) proportional.back() = length;  // the shares' sum rounds short of 1
  DivisionResult result =
      finish_path(path, drones, proportional, home_cost, budgets, measure, limit);
  const double proportional_makespan = result.makespan_s;
  if (short_of_path && !std::isfinite(proportional_makespan)) {
    // A budget in metres flown beyond the drone's flight time limit: each drone the longest
    // piece it flies within its limits instead (what the fleet then leaves is unflown).
    std::vector<double> cuts =
        cuts_within(index, drones, measure, limit, std::numeric_limits<double>::max());
    result = finish_path(path, drones, cuts, home_cost, budgets, measure, limit);
  }
  // A proportional piece beyond a drone's limits is re-cut as the balance cuts (within them).
  const bool over_limits = !std::isfinite(proportional_makespan);
  if ((balance == Balance::makespan || over_limits) && !short_of_path) {
    // The smallest makespan whose greedy cuts reach the end of the path.
    double lo = 0, hi = proportional_makespan > 0 && std::isfinite(proportional_makespan)
                            ? proportional_makespan
                            : 1;
    // Measured times are costlier: 1e-6 of the makespan is far below what the balance can show.
    const double tolerance = measure ? 1e-6 : 1e-9;
    for (int guard = 0;
         guard < 64 && cuts_within(index, drones, measure, limit, hi).back() < length * (1 - 1e-12);
         ++guard)
      hi *= 2;
    for (int k = 0; k < 60 && hi - lo > tolerance * hi; ++k) {
      const double mid = (lo + hi) / 2;
      (cuts_within(index, drones, measure, limit, mid).back() >= length * (1 - 1e-12) ? hi : lo) =
          mid;
    }
    std::vector<double> cuts = cuts_within(index, drones, measure, limit, hi);
    cuts.back() = length;
    DivisionResult balanced = finish_path(path, drones, cuts, home_cost, budgets, measure, limit);
    // Measured times need not be monotone in a cut (a corner becomes a stop): never worse than
    // the proportional cuts.
    if (!measure || balanced.makespan_s <= result.makespan_s) result = std::move(balanced);
  }
  result.proportional_makespan_s = proportional_makespan;
  result.recut_within_limits = balance == Balance::capability && over_limits && !short_of_path;
  return result;
}

AreaProfile::AreaProfile(const std::vector<Ring>& rings, double angle_deg) {
  struct Edge {
    Point2 lo, hi;
  };
  std::vector<Edge> edges;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Point2 a = rotate(ring[i], -angle_deg), b = rotate(ring[(i + 1) % ring.size()], -angle_deg);
      if (a.y > b.y) std::swap(a, b);
      y_.push_back(a.y);
      y_.push_back(b.y);  // a vertex above both its edges is no edge's lower end

      if (a.y != b.y) edges.push_back({a, b});
    }
  std::sort(y_.begin(), y_.end());
  y_.erase(std::unique(y_.begin(), y_.end()), y_.end());
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo.y < b.lo.y; });
  cumulative_.push_back(0);
  std::vector<const Edge*> active;
  std::vector<std::pair<double, double>> crossings;  // (x, dx/dy) at the slab's middle
  std::size_t next = 0;
  for (std::size_t k = 0; k + 1 < y_.size(); ++k) {
    const double h = y_[k + 1] - y_[k], mid = (y_[k] + y_[k + 1]) / 2;
    while (next < edges.size() && edges[next].lo.y <= mid) active.push_back(&edges[next++]);
    std::erase_if(active, [mid](const Edge* e) { return e->hi.y <= mid; });
    crossings.clear();
    for (const Edge* e : active) {
      const double dxdy = (e->hi.x - e->lo.x) / (e->hi.y - e->lo.y);
      crossings.push_back({e->lo.x + dxdy * (mid - e->lo.y), dxdy});
    }
    std::sort(crossings.begin(), crossings.end());
    double width_mid = 0, slope = 0;
    for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) {  // even-odd: inside between pairs
      width_mid += crossings[i + 1].first - crossings[i].first;
      slope += crossings[i + 1].second - crossings[i].second;
    }
    width_.push_back(width_mid - slope * h / 2);
    slope_.push_back(slope);
    cumulative_.push_back(cumulative_.back() + width_mid * h);  // exact: the width is linear
  }
}

double AreaProfile::below(double y) const {
  if (y_.size() < 2 || y <= y_.front()) return 0.0;
  if (y >= y_.back()) return total();
  const auto k =
      static_cast<std::size_t>(std::upper_bound(y_.begin(), y_.end(), y) - y_.begin()) - 1;
  const double t = y - y_[k];
  return cumulative_[k] + width_[k] * t + slope_[k] * t * t / 2;
}

double AreaProfile::ordinate_for(double area) const {
  double lo = y_min(), hi = y_max();
  for (int k = 0; k < 200 && hi - lo > 1e-12 * (1 + std::abs(y_max() - y_min())); ++k) {
    const double mid = (lo + hi) / 2;
    (below(mid) < area ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

double area_below(const std::vector<Ring>& rings, double angle_deg, double y_cut) {
  double a = 0;
  for (const Ring& ring : rings)
    a += geometry::signed_area(clip_half(rotated(ring, -angle_deg), y_cut, true));
  return a;
}

Ring clip_band(const Ring& ring, double angle_deg, double y0, double y1) {
  const Ring band = clip_half(clip_half(rotated(ring, -angle_deg), y0, false), y1, true);
  Ring out;
  for (const Point2& p : band)
    if (out.empty() || !(out.back() == p)) out.push_back(rotate(p, angle_deg));
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

DivisionResult divide_region(const std::vector<Ring>& rings, double angle_deg,
                             const std::vector<DroneResource>& drones,
                             const BandSweep& sweep_band) {
  // Bands are cut from boustrophedon pieces: each stays one simple ring when clipped.
  const std::vector<Ring> pieces = geometry::boustrophedon_decomposition(rings, angle_deg).pieces;
  std::vector<Point2> vertices;
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const Ring& ring : rings)
    for (const Point2& p : ring) {
      vertices.push_back(p);
      y_min = std::min(y_min, rotate(p, -angle_deg).y);
      y_max = std::max(y_max, rotate(p, -angle_deg).y);
    }
  const std::vector<double> home_cost = home_costs(vertices, drones);
  std::vector<std::optional<double>> budgets;
  const std::vector<double> w = weights(drones, home_cost, budgets);
  const double total_w = std::accumulate(w.begin(), w.end(), 0.0);
  const AreaProfile profile(rings, angle_deg);
  const double total_area = profile.total();
  auto cut_at = [&](double area) { return profile.ordinate_for(area); };
  auto band = [&](double y0, double y1) {
    std::vector<Ring> out;
    for (const Ring& piece : pieces) {
      Ring clipped = clip_band(piece, angle_deg, y0, y1);
      if (clipped.size() >= 3 && geometry::signed_area(clipped) > 1e-9 * total_area)
        out.push_back(std::move(clipped));
    }
    return out;
  };
  auto result_for = [&](const std::vector<double>& cuts) {  // cuts: n - 1 ordinates
    DivisionResult r;
    std::vector<double> bounds{y_min};
    bounds.insert(bounds.end(), cuts.begin(), cuts.end());
    bounds.push_back(y_max);
    for (std::size_t i = 0; i < drones.size(); ++i) {
      DroneWork work;
      work.region = band(bounds[i], std::max(bounds[i], bounds[i + 1]));
      double a = 0;
      for (const Ring& piece : work.region) a += geometry::signed_area(piece);
      work.share = total_area > 0 ? a / total_area : 0;
      if (!work.region.empty()) work.path = sweep_band(work.region, drones[i]);
      work.home_cost_m = home_cost[i];
      work.budget_m = budgets[i];
      if (!work.path.points.empty())
        work.estimated_time_s =
            (geometry::distance(drones[i].home, work.path.points.front()) + work.path.length_m() +
             geometry::distance(work.path.points.back(), drones[i].home)) /
            drones[i].speed_m_s;
      r.makespan_s = std::max(r.makespan_s, work.estimated_time_s);
      r.drones.push_back(std::move(work));
    }
    return r;
  };

  std::vector<double> proportional;
  double cumulative = 0;
  for (std::size_t i = 0; i + 1 < drones.size(); ++i) {
    cumulative += w[i] / total_w;
    proportional.push_back(cut_at(cumulative * total_area));
  }
  DivisionResult result = result_for(proportional);
  result.proportional_makespan_s = result.makespan_s;
  return result;
}

}  // namespace swath::planning

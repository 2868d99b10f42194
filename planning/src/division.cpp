#include "swath/planning/division.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "swath/base/input_error.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;
using geometry::Ring;

// Sutherland-Hodgman against y <= limit (keep_below) or y >= limit, in the rotated frame.
Ring clip_half(const Ring& ring, double limit, bool keep_below) {
  Ring out;
  auto inside = [&](Point2 p) { return keep_below ? p.y <= limit : p.y >= limit; };
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    const bool in_a = inside(a), in_b = inside(b);
    if (in_a) out.push_back(a);
    if (in_a != in_b) out.push_back(a + (b - a) * ((limit - a.y) / (b.y - a.y)));
  }
  return out;
}

Ring rotated(const Ring& ring, double angle_deg) {
  Ring out;
  for (const Point2& p : ring) out.push_back(rotate(p, angle_deg));
  return out;
}

// Twice the distance from each drone's home to the farthest of `points` (paper:
// findFlyFromToHomeCost).
std::vector<double> home_costs(const std::vector<Point2>& points,
                               const std::vector<DroneResource>& drones) {
  std::vector<double> cost;
  for (const DroneResource& d : drones) {
    double far = 0;
    for (const Point2& p : points) far = std::max(far, geometry::distance(d.home, p));
    cost.push_back(2 * far);
  }
  return cost;
}

// Shares from the corrected capabilities; budgets where ranges are known.
std::vector<double> weights(const std::vector<DroneResource>& drones,
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

// Flight time of drone d over [s, e] of the path, straight home legs; +inf beyond its range.
double piece_time(const PathIndex& index, const DroneResource& d, double s, double e) {
  const double distance = geometry::distance(d.home, index.point(s)) + (e - s) +
                          geometry::distance(index.point(e), d.home);
  if (d.range_m && distance > *d.range_m * (1 + 1e-12))
    return std::numeric_limits<double>::infinity();
  return distance / d.speed_m_s;
}

// Greedy cuts that keep every drone within `makespan`: each takes the longest piece it can.
std::vector<double> cuts_within(const PathIndex& index, const std::vector<DroneResource>& drones,
                                double makespan) {
  std::vector<double> cuts;
  double s = 0;
  for (std::size_t i = 0; i < drones.size(); ++i) {
    double lo = s, hi = index.length();
    if (piece_time(index, drones[i], s, hi) <= makespan) {
      lo = hi;
    } else {
      for (int k = 0; k < 60 && hi - lo > 1e-9 * (1 + index.length()); ++k) {
        const double mid = (lo + hi) / 2;
        (piece_time(index, drones[i], s, mid) <= makespan ? lo : hi) = mid;
      }
    }
    s = lo;
    if (i + 1 < drones.size()) cuts.push_back(s);
  }
  cuts.push_back(s);  // how far the fleet gets
  return cuts;
}

DivisionResult finish_path(const SurveyPath& path, const std::vector<DroneResource>& drones,
                           std::vector<double> cuts, const std::vector<double>& home_cost,
                           const std::vector<std::optional<double>>& budgets) {
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
    w.estimated_time_s = e > s ? piece_time(index, drones[i], s, e) : 0;
    r.makespan_s = std::max(r.makespan_s, w.estimated_time_s);
    r.drones.push_back(std::move(w));
  }
  return r;
}

}  // namespace

DivisionResult divide_path(const SurveyPath& path, const std::vector<DroneResource>& drones,
                           Balance balance) {
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
  DivisionResult result = finish_path(path, drones, proportional, home_cost, budgets);
  const double proportional_makespan = result.makespan_s;
  if (balance == Balance::makespan && !short_of_path) {
    // The smallest makespan whose greedy cuts reach the end of the path.
    double lo = 0, hi = proportional_makespan > 0 ? proportional_makespan : 1;
    while (cuts_within(index, drones, hi).back() < length * (1 - 1e-12)) hi *= 2;
    for (int k = 0; k < 60 && hi - lo > 1e-9 * hi; ++k) {
      const double mid = (lo + hi) / 2;
      (cuts_within(index, drones, mid).back() >= length * (1 - 1e-12) ? hi : lo) = mid;
    }
    std::vector<double> cuts = cuts_within(index, drones, hi);
    cuts.back() = length;
    result = finish_path(path, drones, cuts, home_cost, budgets);
  }
  result.proportional_makespan_s = proportional_makespan;
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
                             const std::vector<DroneResource>& drones, Balance balance,
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
  auto band_time = [&](std::size_t i, double y0, double y1, bool estimate) {
    const std::vector<Ring> b = band(y0, y1);
    if (b.empty()) return 0.0;
    const SurveyPath p = sweep_band(b, drones[i], estimate);
    if (p.points.empty()) return 0.0;
    const double distance = geometry::distance(drones[i].home, p.points.front()) + p.length_m() +
                            geometry::distance(p.points.back(), drones[i].home);
    if (drones[i].range_m && distance > *drones[i].range_m)
      return std::numeric_limits<double>::infinity();
    return distance / drones[i].speed_m_s;
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
      if (!work.region.empty()) work.path = sweep_band(work.region, drones[i], false);
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
  const double proportional_makespan = result.makespan_s;
  if (balance == Balance::makespan && drones.size() > 1) {
    // Greedy bands within a makespan (each drone the tallest band it can fly in time), bisection
    // on the makespan; estimates use straight transits.
    auto cuts_within_time = [&](double makespan, std::vector<double>& cuts) {
      cuts.clear();
      double y0 = y_min;
      for (std::size_t i = 0; i < drones.size(); ++i) {
        double lo = y0, hi = y_max;
        if (band_time(i, y0, hi, true) <= makespan) {
          lo = hi;
        } else {
          for (int k = 0; k < 24; ++k) {
            const double mid = (lo + hi) / 2;
            (band_time(i, y0, mid, true) <= makespan ? lo : hi) = mid;
          }
        }
        if (i + 1 < drones.size()) cuts.push_back(lo);
        y0 = lo;
      }
      return y0 >= y_max - 1e-9 * (1 + std::abs(y_max));
    };
    std::vector<double> cuts;
    double lo = 0, hi = proportional_makespan > 0 ? proportional_makespan : 1;
    for (int guard = 0; !cuts_within_time(hi, cuts) && guard < 20; ++guard) hi *= 1.5;
    for (int k = 0; k < 24; ++k) {
      const double mid = (lo + hi) / 2;
      std::vector<double> trial;
      (cuts_within_time(mid, trial) ? hi : lo) = mid;
    }
    cuts_within_time(hi, cuts);
    DivisionResult balanced = result_for(cuts);
    if (balanced.makespan_s < result.makespan_s) result = std::move(balanced);
  }
  result.proportional_makespan_s = proportional_makespan;
  return result;
}

}  // namespace swath::planning

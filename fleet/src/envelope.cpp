#include "swath/fleet/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "swath/base/number_text.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/polygon.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::fleet {

namespace {

// On the boundary counts as inside: a fence's edge is still the fence's.
bool inside(const std::vector<std::array<double, 2>>& ring, double x_m, double y_m) {
  std::vector<geometry::Point2> r;
  r.reserve(ring.size());
  for (const auto& [x, y] : ring) r.push_back({x, y});
  return geometry::locate_point({x_m, y_m}, r) != geometry::Containment::outside;
}

}  // namespace

std::string LocalEnvelope::refusal_xy(double x_m, double y_m) const {
  if (!inclusions.empty()) {
    bool in = false;
    for (const auto& r : inclusions) in = in || inside(r, x_m, y_m);
    if (!in) return "outside the inclusion fence";
  }
  for (const auto& r : exclusions)
    if (inside(r, x_m, y_m)) return "inside an exclusion fence";
  return "";
}

namespace {

using Rings = std::vector<std::vector<std::array<double, 2>>>;

// Where (0..1, ends excluded) the segment a-b meets an edge of `rings`.
void crossings(const vehicle::Vec3& a, const vehicle::Vec3& b, const Rings& rings,
               std::vector<double>& out) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  for (const auto& ring : rings)
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const double ex = ring[i][0] - ring[j][0], ey = ring[i][1] - ring[j][1];
      const double den = dx * ey - dy * ex;
      if (std::abs(den) < 1e-12) continue;  // parallel: its ends are its neighbours' crossings
      const double wx = ring[j][0] - a.x, wy = ring[j][1] - a.y;
      const double t = (wx * ey - wy * ex) / den, u = (wx * dy - wy * dx) / den;
      if (t > 0 && t < 1 && u >= -1e-12 && u <= 1 + 1e-12) out.push_back(t);
    }
}

// Twice the signed area of p-q-r: > 0 when r lies left of p→q.
double turn(double px, double py, double qx, double qy, double rx, double ry) {
  return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

}  // namespace

// Between two crossings of fence edges a leg is wholly inside or wholly outside, so each piece's
// midpoint stands for the piece.
std::string LocalEnvelope::leg_refusal(const vehicle::Vec3& a, const vehicle::Vec3& b) const {
  if (std::string why = refusal_xy(a.x, a.y); !why.empty()) return why;
  if (std::string why = refusal_xy(b.x, b.y); !why.empty()) return why;
  std::vector<double> ts{0, 1};
  crossings(a, b, inclusions, ts);
  crossings(a, b, exclusions, ts);
  std::sort(ts.begin(), ts.end());
  for (std::size_t k = 1; k < ts.size(); ++k) {
    if (ts[k] - ts[k - 1] < 1e-9) continue;
    const double m = (ts[k] + ts[k - 1]) / 2;
    if (std::string why = refusal_xy(a.x + m * (b.x - a.x), a.y + m * (b.y - a.y)); !why.empty())
      return why;
  }
  return "";
}

std::string LocalEnvelope::triangle_refusal(const vehicle::Vec3& a, const vehicle::Vec3& b,
                                            const vehicle::Vec3& c) const {
  if (!fenced()) return "";
  for (const auto& [p, q] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}})
    if (std::string why = leg_refusal(*p, *q); !why.empty()) return why;
  // Sides inside a simple inclusion polygon keep the triangle inside it; an exclusion wholly
  // within the triangle is found by its vertices.
  for (const auto& ring : exclusions)
    for (const auto& [x, y] : ring) {
      const double ab = turn(a.x, a.y, b.x, b.y, x, y), bc = turn(b.x, b.y, c.x, c.y, x, y),
                   ca = turn(c.x, c.y, a.x, a.y, x, y);
      const bool boxed = x >= std::min({a.x, b.x, c.x}) && x <= std::max({a.x, b.x, c.x}) &&
                         y >= std::min({a.y, b.y, c.y}) && y <= std::max({a.y, b.y, c.y});
      if (boxed && ((ab >= 0 && bc >= 0 && ca >= 0) || (ab <= 0 && bc <= 0 && ca <= 0)))
        return "around an exclusion fence";
    }
  return "";
}

namespace {

// The router's area: inclusions counter-clockwise, exclusions clockwise (holes). Exclusions alone
// get an outer ring 10 km beyond them, so that a way round them exists near them.
std::vector<geometry::Ring> router_rings(const LocalEnvelope& e) {
  std::vector<geometry::Ring> rings;
  const auto add = [&](const std::vector<std::array<double, 2>>& ring, bool ccw) {
    geometry::Ring r;
    for (const auto& [x, y] : ring) r.push_back({x, y});
    if ((geometry::signed_area(r) > 0) != ccw) std::reverse(r.begin(), r.end());
    rings.push_back(std::move(r));
  };
  for (const auto& ring : e.inclusions) add(ring, true);
  if (e.inclusions.empty()) {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    for (const auto& ring : e.exclusions)
      for (const auto& [x, y] : ring)
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    const double m = 10000;
    add({{x0 - m, y0 - m}, {x1 + m, y0 - m}, {x1 + m, y1 + m}, {x0 - m, y1 + m}}, true);
  }
  for (const auto& ring : e.exclusions) add(ring, false);
  return rings;
}

}  // namespace

void LocalEnvelope::build_routes() {
  if (!fenced()) return;
  router = std::make_shared<const geometry::VisibilityRouter>(
      router_rings(*this), geometry::Routing::routed, kRouteCornerAllowance_m);
}

std::vector<vehicle::Vec3> LocalEnvelope::route(const vehicle::Vec3& a,
                                                const vehicle::Vec3& b) const {
  if (leg_refusal(a, b).empty()) return {b};
  if (!router) return {};
  const std::vector<geometry::Point2> path = router->path({a.x, a.y}, {b.x, b.y});
  // The router's own idea of inside (ring parity) is not the fence's (any inclusion, no
  // exclusion) where inclusions overlap: every leg is judged as the fence judges it.
  std::vector<vehicle::Vec3> stops;
  vehicle::Vec3 from = a;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const vehicle::Vec3 to = i + 1 == path.size() ? b : vehicle::Vec3{path[i].x, path[i].y, b.z};
    if (!leg_refusal(from, to).empty()) return {};
    stops.push_back(to);
    from = to;
  }
  return stops;
}

bool LocalEnvelope::reachable(const vehicle::Vec3& a, const vehicle::Vec3& b,
                              const vehicle::Vec3& home) const {
  if (!routes()) return triangle_refusal(a, b, home).empty();
  return !route(a, b).empty() && !route(b, home).empty();
}

std::string LocalEnvelope::refusal(const vehicle::Vec3& p) const {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return "not finite";
  if (p.z > ceiling_m + 1e-6)
    return "above the ceiling of " + base::shortest_text(ceiling_m) + " m";
  if (p.z > fence_max_altitude_m + 1e-6)
    return "above the fence's " + base::shortest_text(fence_max_altitude_m) + " m";
  return refusal_xy(p.x, p.y);
}

LocalEnvelope local_envelope(const Envelope& e, const geometry::GeoPoint& origin) {
  LocalEnvelope l;
  l.ceiling_m = e.ceiling_m;
  l.separation_m = e.separation_m;
  l.fence_max_altitude_m = e.fence.max_altitude_m;
  const geometry::LocalFrame frame(origin);
  for (const FencePolygon& p : e.fence.polygons) {
    std::vector<std::array<double, 2>> ring;
    for (const geometry::GeoPoint& g : p.ring_deg) {
      const geometry::Point2 q = frame.to_local(g);
      ring.push_back({q.x, q.y});
    }
    (p.inclusion ? l.inclusions : l.exclusions).push_back(std::move(ring));
  }
  return l;
}

Envelope envelope_of(const vehicle::FleetFile& file) {
  Envelope e;
  e.ceiling_m = file.ceiling_m.value_or(e.ceiling_m);
  e.separation_m = file.separation_m.value_or(e.separation_m);
  if (file.fence) {
    e.fence.polygons = file.fence->polygons;
    e.fence.max_altitude_m = file.fence->max_altitude_m.value_or(e.fence.max_altitude_m);
  }
  return e;
}

std::string layers_refusal(int drones, double base_m, double step_m, double ceiling_m,
                           double fence_height_m, bool separation_sets_step) {
  const double limit_m = std::min(ceiling_m, fence_height_m);
  const double top_m = base_m + step_m * static_cast<double>(std::max(0, drones - 1));
  if (top_m <= limit_m + 1e-9) return "";
  const int fit = base_m > limit_m ? 0 : static_cast<int>((limit_m - base_m) / step_m) + 1;
  const bool fence = fence_height_m < ceiling_m;
  return "a fleet of " + std::to_string(drones) + (drones == 1 ? " drone" : " drones") +
         " needs altitude layers up to " + base::shortest_text(top_m) + " m (" +
         base::shortest_text(base_m) + " m + " + base::shortest_text(step_m) + " m apart), above " +
         (fence ? "the fence's max_altitude_m of " : "the ceiling of ") +
         base::shortest_text(limit_m) + " m: at most " + std::to_string(fit) +
         (fit == 1 ? " drone fits" : " drones fit") + " (raise " +
         (fence ? "the fence's max_altitude_m" : "ceiling_m") +
         (separation_sets_step ? " or lower separation_m" : "") + " in the fleet file, or fly " +
         (fit == 1 ? "one drone" : "fewer drones") + ")";
}

// A vertex is at most 36 bytes of run_start ("[-20015086.796021,-20015086.796021],"): 20,000 of
// them fit a 1 MiB line with room for the drones.
std::string fence_size_refusal(const LocalEnvelope& e) {
  std::size_t vertices = 0;
  for (const auto* rings : {&e.inclusions, &e.exclusions})
    for (const auto& ring : *rings) vertices += ring.size();
  if (vertices <= kMaxFenceVertices) return "";
  return "fence: " + std::to_string(vertices) + " vertices; swath-fleet flies a fence of at most " +
         std::to_string(kMaxFenceVertices) +
         " (its polygons and exclusions together; the run's log carries them)";
}

}  // namespace swath::fleet

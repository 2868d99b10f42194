#pragma once
// The .plan read back from its bytes as QGroundControl uploads it, and plane geometry of the
// tests' own (closed-form segment distances, ray casting): an independent reader for the tests
// that check written missions (flight_true_test.cpp, safe_plans_test.cpp).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "swath/geometry/field.hpp"
#include "swath/geometry/polygon.hpp"

namespace swath::planning::plan_reader {

using geometry::Point2;
using geometry::Ring;
using nlohmann::json;

// ---- The test's own plane geometry -------------------------------------------------------------

inline double cross(Point2 o, Point2 a, Point2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}
inline double norm(Point2 v) {
  return std::hypot(v.x, v.y);
}

inline double point_segment_m(Point2 p, Point2 a, Point2 b) {
  const Point2 ab = b - a;
  const double len2 = ab.x * ab.x + ab.y * ab.y;
  double t = len2 > 0 ? ((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return norm(p - (a + ab * t));
}

inline bool segments_cross(Point2 a, Point2 b, Point2 c, Point2 d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 &&
         d4 != 0;
}

inline double segment_segment_m(Point2 a, Point2 b, Point2 c, Point2 d) {
  if (segments_cross(a, b, c, d)) return 0.0;
  return std::min({point_segment_m(a, c, d), point_segment_m(b, c, d), point_segment_m(c, a, b),
                   point_segment_m(d, a, b)});
}

inline bool inside(Point2 p, const Ring& ring) {  // ray casting, even-odd
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Point2 a = ring[i], b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

// Distance from the leg a-b to the zone (0 when the leg enters it).
inline double leg_zone_m(Point2 a, Point2 b, const Ring& zone) {
  if (inside(a, zone) || inside(b, zone)) return 0.0;
  double least = INFINITY;
  for (std::size_t i = 0; i < zone.size(); ++i)
    least = std::min(least, segment_segment_m(a, b, zone[i], zone[(i + 1) % zone.size()]));
  return least;
}

inline double ring_ring_m(const Ring& p, const Ring& q) {
  double least = INFINITY;
  for (std::size_t i = 0; i < p.size(); ++i)
    least = std::min(least, leg_zone_m(p[i], p[(i + 1) % p.size()], q));
  return least;
}

// ---- The .plan read back as QGroundControl uploads it ------------------------------------------

struct PlanItem {
  int command = 0;
  std::vector<double> params;  // NaN for null, as QGC sends it
  Point2 position;             // local metres (positional items)
  double altitude_m = 0.0;
};

struct ReadPlan {
  Point2 home;  // seq 0
  double cruise_m_s = 0.0;
  std::vector<PlanItem> items;
  std::vector<Ring> inclusions, exclusions;
  std::vector<Point2> rally;
};

inline Ring ring_of(const json& points, const geometry::LocalFrame& frame) {
  Ring ring;
  for (const json& p : points)
    ring.push_back(frame.to_local({p[0].get<double>(), p[1].get<double>(), 0}));
  return ring;
}

inline ReadPlan read_plan(const std::string& text, const geometry::LocalFrame& frame) {
  const json j = json::parse(text);
  ReadPlan out;
  const json& m = j.at("mission");
  const json& h = m.at("plannedHomePosition");
  out.home = frame.to_local({h[0].get<double>(), h[1].get<double>(), 0});
  out.cruise_m_s = m.at("cruiseSpeed").get<double>();
  for (const json& it : m.at("items")) {
    PlanItem item;
    item.command = it.at("command").get<int>();
    for (const json& v : it.at("params"))
      item.params.push_back(v.is_null() ? NAN : v.get<double>());
    if (it.contains("Altitude")) {
      item.position = frame.to_local({item.params.at(4), item.params.at(5), 0});
      item.altitude_m = it.at("Altitude").get<double>();
    }
    out.items.push_back(item);
  }
  for (const json& poly : j.at("geoFence").at("polygons"))
    (poly.at("inclusion").get<bool>() ? out.inclusions : out.exclusions)
        .push_back(ring_of(poly.at("polygon"), frame));
  for (const json& p : j.at("rallyPoints").at("points"))
    out.rally.push_back(frame.to_local({p[0].get<double>(), p[1].get<double>(), 0}));
  return out;
}

inline bool positional(int command) {
  return command == 16 || command == 21 || command == 22;
}

// The horizontal legs the mission commands: home, each positional item, home again on RTL.
inline std::vector<Point2> commanded_path(const ReadPlan& p) {
  std::vector<Point2> path{p.home};
  for (const PlanItem& it : p.items)
    if (positional(it.command) && it.command != 22)
      path.push_back(it.position);
    else if (it.command == 20)
      path.push_back(p.home);
  return path;
}

// The least distance of the legs from the zones, and where it is.
struct Closest {
  double distance_m = INFINITY;
  std::size_t leg = 0;
  Point2 from, to;
};

inline Closest least_clearance(const std::vector<Point2>& path, const std::vector<Ring>& zones) {
  Closest c;
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    for (const Ring& z : zones) {
      const double d = leg_zone_m(path[i], path[i + 1], z);
      if (d < c.distance_m) c = {d, i, path[i], path[i + 1]};
    }
  return c;
}

inline std::ostream& operator<<(std::ostream& os, const Closest& c) {
  return os << c.distance_m << " m on leg " << c.leg << " (" << c.from.x << ", " << c.from.y
            << ") -> (" << c.to.x << ", " << c.to.y << ")";
}

}  // namespace swath::planning::plan_reader

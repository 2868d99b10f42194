// The only translation unit that sees Boost.Geometry (its buffer and boolean operations).
#include "swath/geometry/offset.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "swath/geometry/predicates.hpp"

namespace swath::geometry {
namespace {

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint, /*clockwise=*/false, /*closed=*/true>;
using BMulti = bg::model::multi_polygon<BPolygon>;
using BLine = bg::model::linestring<BPoint>;
using BMultiLine = bg::model::multi_linestring<BLine>;

BPolygon polygon_of(const Ring& ring) {
  BPolygon p;
  for (const Point2& q : ring) p.outer().push_back({q.x, q.y});
  if (!ring.empty()) p.outer().push_back({ring.front().x, ring.front().y});
  bg::correct(p);  // orientation and closure as the type wants
  return p;
}

Ring ring_of(const bg::model::ring<BPoint, false, true>& r, bool counter_clockwise) {
  Ring out;
  for (const BPoint& p : r) out.push_back({p.x(), p.y()});
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  if ((signed_area(out) > 0) != counter_clockwise) std::reverse(out.begin(), out.end());
  return out;
}

// The union of `parts`, merged pairwise (a tree of unions: many small parts at O(k log k) unions,
// not one growing union per part).
BMulti united(std::vector<BMulti> parts) {
  if (parts.empty()) return {};
  while (parts.size() > 1) {
    std::vector<BMulti> next;
    for (std::size_t i = 0; i + 1 < parts.size(); i += 2) {
      BMulti both;
      bg::union_(parts[i], parts[i + 1], both);
      next.push_back(std::move(both));
    }
    if (parts.size() % 2) next.push_back(std::move(parts.back()));
    parts = std::move(next);
  }
  return std::move(parts.front());
}

// A 16-gon around the circle of radius r about c (its edges touch the circle).
BPolygon around_circle(Point2 c, double r) {
  constexpr int kSides = 16;
  const double reach = r / std::cos(std::numbers::pi / kSides);
  BPolygon p;
  for (int k = 0; k <= kSides; ++k) {
    const double a = 2 * std::numbers::pi * (k % kSides) / kSides;
    p.outer().push_back({c.x + reach * std::cos(a), c.y + reach * std::sin(a)});
  }
  bg::correct(p);
  return p;
}

// The area's corners sharper than 60 degrees (inside angle), on every ring: there a mitre limited
// to twice the distance does not hold the whole circle about the corner.
std::vector<Point2> sharp_corners(const BMulti& input) {
  std::vector<Point2> corners;
  const auto add = [&](const auto& ring) {  // closed; the area on the left of every edge
    const std::size_t n = ring.size() > 1 ? ring.size() - 1 : 0;
    for (std::size_t i = 0; i < n; ++i) {
      const BPoint& b = ring[(i + n - 1) % n];
      const BPoint& v = ring[i];
      const BPoint& a = ring[(i + 1) % n];
      const Point2 in{b.x() - v.x(), b.y() - v.y()}, out{a.x() - v.x(), a.y() - v.y()};
      const double cross = out.x * in.y - out.y * in.x;  // > 0: a left turn, a convex corner
      if (cross > 0 && dot(in, out) > 0.49 * std::sqrt(dot(in, in) * dot(out, out)))
        corners.push_back({v.x(), v.y()});
    }
  };
  for (const BPolygon& p : input) {
    add(p.outer());
    for (const auto& inner : p.inners()) add(inner);
  }
  return corners;
}

BMulti buffered(const BMulti& input, double distance) {
  // Points per circle only matter where a join falls back to round; mitres keep vertices few.
  const bg::strategy::buffer::distance_symmetric<double> by(distance);
  const bg::strategy::buffer::side_straight side;
  const bg::strategy::buffer::join_miter join(2.0);
  const bg::strategy::buffer::end_flat end;
  const bg::strategy::buffer::point_circle circle(16);
  BMulti out;
  bg::buffer(input, out, by, side, join, end, circle);
  // Growing, Boost pulls a mitre longer than the limit back to it, joined straight to the offset
  // edges: at a corner sharper than 60 degrees that cuts into the circle about the corner (a 10 m
  // clearance was 9.24 m from a 10-degree zone tip). A 16-gon about each such circle is added.
  // Shrinking (subtract's inset) needs none: there a mitre only keeps further from a corner.
  if (!(distance > 0)) return out;
  std::vector<BMulti> parts{std::move(out)};
  for (const Point2& c : sharp_corners(input)) parts.push_back({around_circle(c, distance)});
  return parts.size() == 1 ? std::move(parts.front()) : united(std::move(parts));
}

BMulti multi_of(const std::vector<Ring>& rings) {
  std::vector<BMulti> parts;
  for (const Ring& r : rings)
    if (r.size() >= 3) parts.push_back({polygon_of(r)});
  return united(std::move(parts));
}

// The areas of rings given as grow_keeping_holes() makes them (a counter-clockwise outer ring, then
// its clockwise holes), united; rings all counter-clockwise are multi_of()'s, the same union.
BMulti multi_with_holes(const std::vector<Ring>& rings) {
  std::vector<BMulti> parts;
  for (const Ring& r : rings) {
    if (r.size() < 3) continue;
    if (signed_area(r) < 0 && !parts.empty()) {
      BPolygon& p = parts.back().front();
      p.inners().emplace_back();
      for (const Point2& q : r) p.inners().back().push_back({q.x, q.y});
      p.inners().back().push_back({r.front().x, r.front().y});
      bg::correct(p);
    } else {
      parts.push_back({polygon_of(r)});
    }
  }
  return united(std::move(parts));
}

// Each polygon's outer ring counter-clockwise, followed by its holes clockwise.
std::vector<Ring> rings_with_holes(const BMulti& m) {
  std::vector<Ring> out;
  for (const BPolygon& p : m) {
    out.push_back(ring_of(p.outer(), true));
    for (const auto& inner : p.inners()) {
      Ring h = ring_of(inner, false);
      if (h.size() >= 3) out.push_back(std::move(h));
    }
  }
  return out;
}

// Squared distance from p to segment [a, b].
double segment_distance_sq(Point2 p, Point2 a, Point2 b) {
  const Point2 d = b - a;
  const double len = dot(d, d);
  const double t = len > 0 ? std::clamp(dot(p - a, d) / len, 0.0, 1.0) : 0.0;
  const Point2 q = a + d * t - p;
  return dot(q, q);
}

}  // namespace

std::vector<Ring> grow(const std::vector<Ring>& rings, double distance_m) {
  std::vector<Ring> out;
  const BMulti input = multi_of(rings);
  const BMulti grown = distance_m > 0 ? buffered(input, distance_m) : input;
  for (const BPolygon& p : grown) out.push_back(ring_of(p.outer(), true));
  return out;
}

std::vector<Ring> grow_each(const std::vector<Ring>& rings, double distance_m) {
  std::vector<BMulti> parts;
  for (const Ring& r : rings) {
    if (r.size() < 3) continue;
    const BMulti one{polygon_of(r)};
    parts.push_back(distance_m > 0 ? buffered(one, distance_m) : one);
  }
  std::vector<Ring> out;
  for (const BPolygon& p : united(std::move(parts))) out.push_back(ring_of(p.outer(), true));
  return out;
}

std::vector<Ring> grow_keeping_holes(const std::vector<Ring>& rings, double distance_m) {
  const BMulti input = multi_of(rings);
  return rings_with_holes(distance_m > 0 ? buffered(input, distance_m) : input);
}

std::vector<Ring> grow_simplified(const std::vector<Ring>& rings, double distance_m,
                                  double tolerance_m) {
  std::vector<Ring> simple;
  bool fewer = false;
  for (const Ring& r : rings) {
    simple.push_back(r);
    if (r.size() < 4 || !(tolerance_m > 0)) continue;
    BPolygon s;
    bg::simplify(polygon_of(r), s, tolerance_m);
    if (s.outer().size() < 4 || !bg::is_valid(s)) continue;
    Ring fewer_vertices = ring_of(s.outer(), true);
    if (fewer_vertices.size() >= r.size()) continue;
    simple.back() = std::move(fewer_vertices);
    fewer = true;
  }
  return fewer ? grow(simple, distance_m + tolerance_m) : grow(rings, distance_m);
}

std::vector<Ring> subtract(const Ring& outer, double inset_m, const std::vector<Ring>& obstacles) {
  BMulti area;
  area.push_back(polygon_of(outer));
  if (inset_m > 0) area = buffered(area, -inset_m);
  BMulti result;
  if (obstacles.empty()) {
    result = area;
  } else {
    bg::difference(area, multi_with_holes(obstacles), result);
  }
  std::vector<Ring> out;
  for (const BPolygon& p : result) {
    Ring o = ring_of(p.outer(), true);
    if (o.size() < 3 || std::abs(signed_area(o)) <= 0) continue;
    out.push_back(std::move(o));
    for (const auto& inner : p.inners()) {
      Ring h = ring_of(inner, false);
      if (h.size() >= 3) out.push_back(std::move(h));
    }
  }
  return out;
}

double least_distance(const std::vector<Point2>& path, const std::vector<Ring>& rings) {
  double best_sq = std::numeric_limits<double>::infinity();
  for (const Ring& ring : rings) {
    if (ring.size() < 3) continue;
    // A path point inside the area, or a path segment crossing its boundary: distance 0.
    for (const Point2& p : path)
      if (locate_point(p, ring) != Containment::outside) return 0.0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const Point2 a = path[i], b = path[i + 1];
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const Point2 c = ring[k], d = ring[(k + 1) % ring.size()];
        if (segments_intersect(a, b, c, d)) return 0.0;
        best_sq = std::min({best_sq, segment_distance_sq(a, c, d), segment_distance_sq(b, c, d),
                            segment_distance_sq(c, a, b), segment_distance_sq(d, a, b)});
      }
    }
    if (path.size() == 1)
      for (std::size_t k = 0; k < ring.size(); ++k)
        best_sq =
            std::min(best_sq, segment_distance_sq(path[0], ring[k], ring[(k + 1) % ring.size()]));
  }
  return std::sqrt(best_sq);
}

double length_inside(const std::vector<Point2>& path, const std::vector<Ring>& rings) {
  if (path.size() < 2 || rings.empty()) return 0.0;
  BLine line;
  for (const Point2& p : path) line.push_back({p.x, p.y});
  double total = 0;
  for (const Ring& r : rings) {
    if (r.size() < 3) continue;
    BMultiLine inside;
    bg::intersection(line, polygon_of(r), inside);
    total += static_cast<double>(bg::length(inside));
  }
  return total;
}

}  // namespace swath::geometry

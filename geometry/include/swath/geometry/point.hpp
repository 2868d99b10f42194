#pragma once
// Point value types shared by every swath library.

#include <cmath>

namespace swath::geometry {

/// A point in a local planar frame, in metres. In the east-north-up frame of a field, x is east
/// and y is north; rotated frames (sweep planning) reuse the type.
struct Point2 {
  double x = 0.0;
  double y = 0.0;

  friend bool operator==(const Point2&, const Point2&) = default;
  Point2 operator+(Point2 o) const { return {x + o.x, y + o.y}; }
  Point2 operator-(Point2 o) const { return {x - o.x, y - o.y}; }
  Point2 operator*(double s) const { return {x * s, y * s}; }
};

inline double dot(Point2 a, Point2 b) {
  return a.x * b.x + a.y * b.y;
}
/// z component of the 3-D cross product: > 0 when b is counter-clockwise of a.
inline double cross(Point2 a, Point2 b) {
  return a.x * b.y - a.y * b.x;
}
/// Euclidean distance (sqrt, not hypot: metres never overflow, and hypot is ~5x slower).
inline double distance(Point2 a, Point2 b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}
/// Distance from p to the box [lo, hi] (0 inside): distance()'s formula on the differences to the
/// box's nearest point, so never above distance(p, u) for any u in the box, bit for bit (rounding
/// is monotone in the differences, their squares, the sum and sqrt): a lower bound that the
/// router's search adds up as it adds distance() (visibility_search.cpp's groups of corners).
inline double distance_to_box(Point2 p, Point2 lo, Point2 hi) {
  const double dx = std::fmax(std::fmax(lo.x - p.x, 0.0), p.x - hi.x),
               dy = std::fmax(std::fmax(lo.y - p.y, 0.0), p.y - hi.y);
  return std::sqrt(dx * dx + dy * dy);
}

/// A WGS84 geodetic point. Latitude in [-90, 90] degrees, longitude in [-180, 180] degrees,
/// altitude in metres above the ellipsoid (0 where a file gives none).
struct GeoPoint {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;

  friend bool operator==(const GeoPoint&, const GeoPoint&) = default;
};

}  // namespace swath::geometry

#include "swath/geometry/local_frame.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>

namespace swath::geometry {

LocalFrame::LocalFrame(GeoPoint origin)
    : origin_(origin), frame_(origin.lat_deg, origin.lon_deg, 0.0) {}

Point2 LocalFrame::to_local(const GeoPoint& p) const {
  double x, y, z;
  frame_.Forward(p.lat_deg, p.lon_deg, 0.0, x, y, z);
  return {x, y};
}

GeoPoint LocalFrame::to_geo(Point2 p, double alt_m) const {
  // The ellipsoid point with these (east, north) lies z below the tangent plane; z is found by
  // fixed-point iteration (each step shrinks the error by ~(distance / earth radius)^2).
  double z = 0.0;
  double lat = 0.0, lon = 0.0, h = 0.0;
  for (int iteration = 0; iteration < 6; ++iteration) {
    frame_.Reverse(p.x, p.y, z, lat, lon, h);
    if (std::abs(h) < 1e-7) break;  // 0.1 µm: below this, doubles at Earth radius are noise
    z -= h;
  }
  return {lat, lon, alt_m};
}

double geodesic_distance_m(const GeoPoint& a, const GeoPoint& b) {
  double s12 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, s12);
  return s12;
}

namespace {

// Cuts of one edge at most (each into 2 to 1024 pieces): a bound for edges near a pole, where
// longitude and latitude bend hardest.
constexpr int kMaxEdgeSplits = 4;

// The position a share `t` along the line straight in longitude and latitude from a to b, the
// short way round in longitude (179.9 to -179.9 crosses the antimeridian, not Greenwich).
GeoPoint along_lonlat(const GeoPoint& a, const GeoPoint& b, double t) {
  double dlon = b.lon_deg - a.lon_deg;
  if (dlon > 180) dlon -= 360;
  if (dlon < -180) dlon += 360;
  double lon = a.lon_deg + t * dlon;
  if (lon > 180) lon -= 360;
  if (lon < -180) lon += 360;
  return {a.lat_deg + t * (b.lat_deg - a.lat_deg), lon, 0.0};
}

double chord_distance_m(Point2 p, Point2 a, Point2 b) {
  const Point2 ab = b - a;
  const double length2 = ab.x * ab.x + ab.y * ab.y;
  const double t =
      length2 > 0 ? std::clamp(((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / length2, 0.0, 1.0) : 0;
  return std::hypot(p.x - a.x - t * ab.x, p.y - a.y - t * ab.y);
}

// An edge spanning more longitude than this is taken as the frame's chord: about a pole (a square
// round it, its edges a quarter turn of longitude each) the lon/lat line is an arc round the pole
// that no one drawing the ring means, and a ring round a pole has no lon/lat reading at all.
constexpr double kMaxLongitudeSpan_deg = 10.0;

// How far the lon/lat-straight line from a to b strays from the chord A-B (their local
// positions): sampled at its quarters (the line bows smoothly, most near its middle).
double lonlat_departure_m(const LocalFrame& frame, const GeoPoint& a, const GeoPoint& b, Point2 A,
                          Point2 B) {
  const double span_deg = std::abs(along_lonlat(a, b, 1.0).lon_deg - a.lon_deg);
  if (std::min(span_deg, 360 - span_deg) > kMaxLongitudeSpan_deg) return 0;
  double most = 0;
  for (const double t : {0.25, 0.5, 0.75})
    most = std::max(most, chord_distance_m(frame.to_local(along_lonlat(a, b, t)), A, B));
  return most;
}

// Pieces an edge that strays `departure_m` is cut into: its bow grows with the square of its
// length, so n even pieces stray about departure / n² each (fewer points than halving, for the
// autopilot's fence storage); pieces still over are cut again.
int pieces_for(double departure_m, double tol_m) {
  return static_cast<int>(std::clamp(std::ceil(std::sqrt(departure_m / tol_m)), 2.0, 1024.0));
}

// How far an edge strays, for a ring as drawn (its ends in lon/lat) and a ring in the frame.
double edge_departure_m(const LocalFrame& frame, const GeoPoint& a, const GeoPoint& b) {
  return lonlat_departure_m(frame, a, b, frame.to_local(a), frame.to_local(b));
}

double edge_departure_m(const LocalFrame& frame, Point2 A, Point2 B) {
  return lonlat_departure_m(frame, frame.to_geo(A), frame.to_geo(B), A, B);
}

// The point a share `t` along the line the edge is straight in: lon/lat for a ring as drawn, the
// chord for a ring in the frame (its lon/lat lines are made to follow the chord).
GeoPoint along_edge(const GeoPoint& a, const GeoPoint& b, double t) {
  return along_lonlat(a, b, t);
}

Point2 along_edge(Point2 A, Point2 B, double t) {
  return A + (B - A) * t;
}

// The points strictly between a and b that make each piece's lon/lat line and chord agree.
template <class P>
void split_edge(const LocalFrame& frame, const P& a, const P& b, double tol_m, int depth,
                std::vector<P>& out) {
  const double departure_m = edge_departure_m(frame, a, b);
  if (depth >= kMaxEdgeSplits || departure_m <= tol_m) return;
  const int n = pieces_for(departure_m, tol_m);
  P from = a;
  for (int k = 1; k <= n; ++k) {
    const P to = k == n ? b : along_edge(a, b, static_cast<double>(k) / n);
    split_edge(frame, from, to, tol_m, depth + 1, out);
    if (k < n) out.push_back(to);
    from = to;
  }
}

}  // namespace

std::vector<GeoPoint> densify_lonlat_edges(const LocalFrame& frame,
                                           const std::vector<GeoPoint>& ring,
                                           std::vector<std::size_t>* from_vertex,
                                           double tolerance_m) {
  std::vector<GeoPoint> out;
  if (from_vertex) from_vertex->clear();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const std::size_t before = out.size();
    out.push_back(ring[i]);
    split_edge(frame, ring[i], ring[(i + 1) % ring.size()], tolerance_m, 0, out);
    for (std::size_t k = before + 1; k < out.size(); ++k) out[k].alt_m = ring[i].alt_m;
    if (from_vertex) from_vertex->resize(out.size(), i);
  }
  return out;
}

double largest_lonlat_departure_m(const LocalFrame& frame, const std::vector<GeoPoint>& ring) {
  double most = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    most = std::max(most, edge_departure_m(frame, ring[i], ring[(i + 1) % ring.size()]));
  }
  return most;
}

std::vector<Point2> densify_local_edges(const LocalFrame& frame, const std::vector<Point2>& ring,
                                        double tolerance_m) {
  std::vector<Point2> out;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    out.push_back(ring[i]);
    split_edge(frame, ring[i], ring[(i + 1) % ring.size()], tolerance_m, 0, out);
  }
  return out;
}

}  // namespace swath::geometry

namespace swath::geometry {

std::optional<AntimeridianEdge> edge_across_antimeridian(const std::vector<GeoPoint>& ring) {
  const auto wrapped = [](GeoPoint g) {
    if (g.lon_deg > 180) g.lon_deg -= 360;
    if (g.lon_deg < -180) g.lon_deg += 360;
    return g;
  };
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const GeoPoint a = wrapped(ring[i]), b = wrapped(ring[i + 1 < ring.size() ? i + 1 : 0]);
    // 180 itself is refused: an edge half the world long has no side the autopilot keeps.
    if (std::abs(b.lon_deg - a.lon_deg) >= 180) return AntimeridianEdge{i, a, b};
  }
  return std::nullopt;
}

}  // namespace swath::geometry

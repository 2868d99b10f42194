#include "swath/geometry/local_frame.hpp"

#include <gtest/gtest.h>
#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <vector>

#include "random_polygons.hpp"

namespace swath::geometry {
namespace {

TEST(LocalFrame, OriginIsZeroAndAxesPointEastAndNorth) {
  const LocalFrame f({47.4, 8.5, 0});
  const Point2 o = f.to_local({47.4, 8.5, 0});
  EXPECT_NEAR(o.x, 0.0, 1e-9);
  EXPECT_NEAR(o.y, 0.0, 1e-9);
  const Point2 north = f.to_local({47.41, 8.5, 0});
  EXPECT_NEAR(north.x, 0.0, 1e-6);
  EXPECT_NEAR(north.y, 1112.0, 2.0);  // ~111.2 km per degree of latitude
  const Point2 east = f.to_local({47.4, 8.51, 0});
  EXPECT_GT(east.x, 750.0);
  EXPECT_LT(east.x, 755.0);  // 111.3 km * cos(47.4°) / 100
}

TEST(LocalFrame, RoundTripBelowOneMillimetreOver20Kilometres) {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  for (double lat0 : {-67.0, -33.9, 0.0, 47.4, 78.2}) {
    const LocalFrame f({lat0, 10.0, 0});
    for (double azimuth = 0; azimuth < 360; azimuth += 30) {
      for (double s : {100.0, 5000.0, 20000.0}) {
        double lat, lon;
        g.Direct(lat0, 10.0, azimuth, s, lat, lon);
        const GeoPoint back = f.to_geo(f.to_local({lat, lon, 0}));
        double error_m;
        g.Inverse(lat, lon, back.lat_deg, back.lon_deg, error_m);
        EXPECT_LT(error_m, 1e-3) << lat0 << ' ' << azimuth << ' ' << s;
        EXPECT_LT(error_m, 1e-6) << "tighter than promised in the header";
      }
    }
  }
}

// A far home (--far-home, up to 1,000 km) still converts back to itself: the tangent plane is
// invertible well inside a hemisphere. At 10,000 km it is not (issue 16: a home moved 2,100 km).
TEST(LocalFrame, RoundTripHoldsAtTheFarHomeLimitAndGeodesicDistance) {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const LocalFrame f({47.4, 8.5, 0});
  for (double azimuth = 0; azimuth < 360; azimuth += 45) {
    double lat, lon;
    g.Direct(47.4, 8.5, azimuth, 1.0e6, lat, lon);
    const GeoPoint back = f.to_geo(f.to_local({lat, lon, 0}));
    EXPECT_LT(geodesic_distance_m({lat, lon, 0}, back), 1e-3) << azimuth;
    EXPECT_NEAR(geodesic_distance_m({47.4, 8.5, 0}, {lat, lon, 0}), 1.0e6, 1e-6);
  }
  double lat, lon;
  g.Direct(47.4, 8.5, 180, 1.05e7, lat, lon);  // beyond the horizon of the tangent plane
  EXPECT_GT(geodesic_distance_m({lat, lon, 0}, f.to_geo(f.to_local({lat, lon, 0}))), 1e5);
}

TEST(LocalFrame, PlanarDistancesMatchGeodesicsWithin1e5Relative) {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const LocalFrame f({52.0, -1.0, 0});
  for (double azimuth = 5; azimuth < 360; azimuth += 40) {
    double lat1, lon1, lat2, lon2, s12;
    g.Direct(52.0, -1.0, azimuth, 9000, lat1, lon1);
    g.Direct(52.0, -1.0, azimuth + 100, 9000, lat2, lon2);
    g.Inverse(lat1, lon1, lat2, lon2, s12);
    const double planar = distance(f.to_local({lat1, lon1, 0}), f.to_local({lat2, lon2, 0}));
    EXPECT_NEAR(planar / s12, 1.0, 1e-5) << azimuth;
  }
}

// ---- densify_local_edges and densify_lonlat_edges, checked by interpolating lon/lat here ----

// The point a share t along the line straight in latitude and longitude from a to b, the short way
// round in longitude (written here, not the library's, so that the tests check it).
GeoPoint lonlat_at(const GeoPoint& a, const GeoPoint& b, double t) {
  const double dlon_deg = std::remainder(b.lon_deg - a.lon_deg, 360.0);
  return {a.lat_deg + t * (b.lat_deg - a.lat_deg), a.lon_deg + t * dlon_deg, 0};
}

double off_line_m(Point2 p, Point2 a, Point2 b) {
  return std::abs(cross(b - a, p - a)) / distance(a, b);
}

// How far the lon/lat line between p and q, at its middle (where it bows most), lies off the
// frame's chord p-q.
double midpoint_departure_m(const LocalFrame& frame, const GeoPoint& p, const GeoPoint& q) {
  const Point2 middle = frame.to_local(lonlat_at(p, q, 0.5));
  return off_line_m(middle, frame.to_local(p), frame.to_local(q));
}

// Position of p along a-b in lon/lat, by projection in degrees (exact for a point on that line).
double share_along_lonlat(const GeoPoint& p, const GeoPoint& a, const GeoPoint& b) {
  const double dlat = b.lat_deg - a.lat_deg, dlon = std::remainder(b.lon_deg - a.lon_deg, 360.0);
  const double plon = std::remainder(p.lon_deg - a.lon_deg, 360.0);
  return ((p.lat_deg - a.lat_deg) * dlat + plon * dlon) / (dlat * dlat + dlon * dlon);
}

// The output cut at the input's vertices: per input edge, the points from its first vertex up to
// (not including) the next. Empty, with a failure, unless the input's vertices all stand in the
// output, the first first, in their order.
template <class P>
std::vector<std::vector<P>> runs_per_edge(const std::vector<P>& out, const std::vector<P>& ring) {
  std::vector<std::vector<P>> runs;
  std::size_t at = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (at >= out.size() || !(out[at] == ring[i])) {
      ADD_FAILURE() << "input vertex " << i << " is not output point " << at;
      return {};
    }
    runs.emplace_back(1, out[at++]);
    while (at < out.size() && !(i + 1 < ring.size() && out[at] == ring[i + 1]))
      runs.back().push_back(out[at++]);
  }
  return runs;
}

struct DensifyCase {
  double lat_deg, lon_deg, radius_m, tolerance_m;
  std::uint64_t seed;
};

// Random star-shaped rings, some off the frame's origin, at the latitudes and sizes fences and
// zones meet: 40 m (every edge short), 1.5 km, 6 km and 20 km across, and one on the antimeridian.
std::vector<DensifyCase> densify_cases() {
  std::vector<DensifyCase> cases;
  std::uint64_t seed = 11;
  for (const double lat_deg : {0.0, 47.0, 65.0, -70.0})
    for (const double radius_m : {40.0, 1500.0, 6000.0, 20000.0})
      for (const double tolerance_m : {kEdgeDepartureTolerance_m, kZoneEdgeDepartureTolerance_m})
        cases.push_back({lat_deg, 8.5, radius_m, tolerance_m, seed++});
  cases.push_back({47.0, 179.97, 6000.0, kEdgeDepartureTolerance_m, seed});
  return cases;
}

Ring random_ring(const DensifyCase& c) {
  test::Rng rng(c.seed);
  const Ring star = test::random_star_polygon(rng, 9, 0.3 * c.radius_m, c.radius_m);
  return test::transformed(star, 0.0, 0.5 * c.radius_m, -0.3 * c.radius_m);
}

std::string describe_case(const DensifyCase& c) {
  return "lat " + std::to_string(c.lat_deg) + " lon " + std::to_string(c.lon_deg) + " radius " +
         std::to_string(c.radius_m) + " m, tolerance " + std::to_string(c.tolerance_m) + " m";
}

// A fence swath writes: each chord gains points on itself (the frame's straight line, where swath
// planned) until the lon/lat line between neighbours, which an autopilot tests, keeps within the
// tolerance of it; an edge already within is kept as it is.
TEST(DensifyLocalEdges, PointsOnTheChordUntilEachLonLatLineKeepsToIt) {
  int edges_split = 0, edges_short = 0;
  for (const DensifyCase& c : densify_cases()) {
    SCOPED_TRACE(describe_case(c));
    const LocalFrame frame({c.lat_deg, c.lon_deg, 0});
    const Ring ring = random_ring(c);
    const Ring out = densify_local_edges(frame, ring, c.tolerance_m);
    const std::vector<Ring> runs = runs_per_edge(out, ring);
    ASSERT_EQ(runs.size(), ring.size());
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      Ring piece = runs[i];
      piece.push_back(b);
      double share_before = 0;
      for (std::size_t k = 1; k + 1 < piece.size(); ++k) {
        EXPECT_LT(off_line_m(piece[k], a, b), 1e-6) << "edge " << i << " point " << k;
        const double share = dot(piece[k] - a, b - a) / dot(b - a, b - a);
        EXPECT_GT(share, share_before) << "edge " << i << " point " << k;
        EXPECT_LT(share, 1.0) << "edge " << i << " point " << k;
        share_before = share;
      }
      for (std::size_t k = 0; k + 1 < piece.size(); ++k)
        EXPECT_LE(midpoint_departure_m(frame, frame.to_geo(piece[k]), frame.to_geo(piece[k + 1])),
                  c.tolerance_m + 1e-9)
            << "edge " << i << " piece " << k << " of " << piece.size() - 1;
      if (midpoint_departure_m(frame, frame.to_geo(a), frame.to_geo(b)) < 0.5 * c.tolerance_m) {
        EXPECT_EQ(runs[i].size(), 1u) << "edge " << i << " is short: kept as it is";
        ++edges_short;
      }
      edges_split += runs[i].size() > 1;
    }
    if (c.radius_m < 100) EXPECT_EQ(out, ring);
  }
  EXPECT_GT(edges_split, 100);  // the cases reach both kinds of edge
  EXPECT_GT(edges_short, 100);
}

// An area or zone as drawn: each lon/lat-straight edge gains points on itself until the frame's
// chords between neighbours keep within the tolerance of it; alt_m and from_vertex follow the edge.
TEST(DensifyLonLatEdges, PointsOnTheLonLatLineUntilEachChordKeepsToIt) {
  int edges_split = 0;
  for (const DensifyCase& c : densify_cases()) {
    SCOPED_TRACE(describe_case(c));
    const LocalFrame frame({c.lat_deg, c.lon_deg, 0});
    std::vector<GeoPoint> ring;
    for (const Point2 p : random_ring(c))
      ring.push_back(frame.to_geo(p, 10.0 + static_cast<double>(ring.size())));
    std::vector<std::size_t> from_vertex;
    const std::vector<GeoPoint> out =
        densify_lonlat_edges(frame, ring, &from_vertex, c.tolerance_m);
    const std::vector<std::vector<GeoPoint>> runs = runs_per_edge(out, ring);
    ASSERT_EQ(runs.size(), ring.size());
    ASSERT_EQ(from_vertex.size(), out.size());
    std::size_t at = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const GeoPoint a = ring[i], b = ring[(i + 1) % ring.size()];
      std::vector<GeoPoint> piece = runs[i];
      piece.push_back(b);
      double share_before = 0;
      for (std::size_t k = 1; k + 1 < piece.size(); ++k) {
        const double share = share_along_lonlat(piece[k], a, b);
        EXPECT_LT(distance(frame.to_local(piece[k]), frame.to_local(lonlat_at(a, b, share))), 1e-6)
            << "edge " << i << " point " << k;
        EXPECT_GT(share, share_before) << "edge " << i << " point " << k;
        EXPECT_LT(share, 1.0) << "edge " << i << " point " << k;
        EXPECT_EQ(piece[k].alt_m, a.alt_m);
        share_before = share;
      }
      for (std::size_t k = 0; k + 1 < piece.size(); ++k)
        EXPECT_LE(midpoint_departure_m(frame, piece[k], piece[k + 1]), c.tolerance_m + 1e-9)
            << "edge " << i << " piece " << k << " of " << piece.size() - 1;
      if (midpoint_departure_m(frame, a, b) < 0.5 * c.tolerance_m)
        EXPECT_EQ(runs[i].size(), 1u) << "edge " << i << " is short: kept as it is";
      for (std::size_t k = 0; k < runs[i].size(); ++k) EXPECT_EQ(from_vertex[at++], i);
      edges_split += runs[i].size() > 1;
    }
    if (c.radius_m < 100) EXPECT_EQ(out, ring);
  }
  EXPECT_GT(edges_split, 100);
}

}  // namespace
}  // namespace swath::geometry

#include "swath/geometry/local_frame.hpp"

#include <GeographicLib/Geodesic.hpp>

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

}  // namespace swath::geometry

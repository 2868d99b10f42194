#include "swath/geometry/local_frame.hpp"

#include <gtest/gtest.h>
#include <GeographicLib/Geodesic.hpp>

#include <cmath>

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

}  // namespace
}  // namespace swath::geometry

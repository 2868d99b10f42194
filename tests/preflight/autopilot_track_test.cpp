// ArduPilot's track between two waypoints (swath/geometry/autopilot_track.hpp): its bow on an
// east-west leg against the closed form on the ellipsoid, the cheap bound above the bow on random
// legs anywhere on Earth, the tracks straight in the autopilot's frame, and the check flying a
// long leg into a zone beside its chord that the straight leg clears.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "swath/base/number_text.hpp"
#include "swath/geometry/autopilot_track.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/missions/mission.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::preflight {
namespace {

using geometry::AutopilotTrack;
using geometry::GeoPoint;
using geometry::LocalFrame;
using geometry::Point2;

constexpr double kDeg = std::numbers::pi / 180;

// WGS84's meridional and prime-vertical radii of curvature at a latitude, metres.
std::pair<double, double> radii_m(double lat_deg) {
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double w = 1 - e2 * std::sin(lat_deg * kDeg) * std::sin(lat_deg * kDeg);
  return {a * (1 - e2) / std::pow(w, 1.5), a / std::sqrt(w)};
}

// A leg of length L through the origin, east-west in the tangent plane: its ends lie on one
// parallel, a little south (north in the south) of the origin's, and ArduPilot flies that
// parallel. Its middle lies M (phi0 - phi1) from the chord, with phi0 - phi1 = (L/2)^2 tan(phi) /
// (2 N): the bow is L^2 tan(phi) M / (8 N^2).
TEST(AutopilotTrack, TheBowOfAnEastWestLegIsTheClosedForm) {
  for (const double lat : {-60.0, 10.0, 47.0, 70.0, 80.0})
    for (const double length_m : {2000.0, 20000.0}) {
      const LocalFrame frame({lat, 8.0, 0.0});
      const AutopilotTrack track(frame, {0, 0});
      const auto [m, n] = radii_m(lat);
      const double expected =
          length_m * length_m * std::abs(std::tan(lat * kDeg)) * m / (8 * n * n);
      const double bow = track.bow_m({-length_m / 2, 0}, {length_m / 2, 0});
      EXPECT_NEAR(bow, expected, 0.01 * expected + 1e-6) << lat << " " << length_m;
      // The track's middle, under both conversions, is that far from the chord, equatorwards.
      for (const auto& points : track.tracks({-length_m / 2, 0}, {length_m / 2, 0}, 2)) {
        EXPECT_NEAR(points[1].x, 0.0, 1e-3 + 1e-6 * length_m);
        EXPECT_NEAR(points[1].y, lat > 0 ? -expected : expected, 0.01 * expected + 1e-6);
      }
    }
}

// ArduPilot's offsets of a point from the origin, degrees (the test's own, from the formula).
Point2 autopilot_offset(const GeoPoint& g, const GeoPoint& o, bool mean_latitude) {
  double dlon = g.lon_deg - o.lon_deg;
  dlon -= 360.0 * std::round(dlon / 360.0);
  const double scale =
      std::max(0.01, std::cos((mean_latitude ? (g.lat_deg + o.lat_deg) / 2 : o.lat_deg) * kDeg));
  return {dlon * scale, g.lat_deg - o.lat_deg};
}

// Random legs up to 50 km long, up to 40 km from a home up to 20 km from the frame's origin, at
// latitudes to 85 degrees either way and across the antimeridian: the cheap bound is at or above
// the bow, and each track's points lie evenly on the straight line in ArduPilot's frame.
TEST(AutopilotTrack, TheBoundHoldsAndTheTracksAreStraightInTheAutopilotsFrame) {
  std::mt19937 rng(20261130);
  std::uniform_real_distribution<double> lat(-85, 85), lon(-180, 180), unit(-1, 1);
  for (int trial = 0; trial < 400; ++trial) {
    const GeoPoint origin{lat(rng), trial % 4 == 0 ? 179.99 : lon(rng), 0.0};
    const LocalFrame frame(origin);
    const Point2 home{20000 * unit(rng), 20000 * unit(rng)};
    const AutopilotTrack track(frame, home);
    const Point2 a = home + Point2{40000 * unit(rng), 40000 * unit(rng)} * (1 / std::sqrt(2.0));
    const Point2 b = a + Point2{50000 * unit(rng), 50000 * unit(rng)} * (1 / std::sqrt(2.0));
    const double bow = track.bow_m(a, b);
    EXPECT_GE(track.bow_bound_m(a, b), bow) << trial;
    const auto tracks = track.tracks(a, b, 8);
    const GeoPoint o = frame.to_geo(home);
    for (const bool mean_latitude : {true, false}) {
      const std::vector<Point2>& points = tracks[mean_latitude ? 0 : 1];
      ASSERT_EQ(points.size(), 9u);
      EXPECT_EQ(points.front(), a);
      EXPECT_EQ(points.back(), b);
      const Point2 from = autopilot_offset(frame.to_geo(a), o, mean_latitude);
      const Point2 to = autopilot_offset(frame.to_geo(b), o, mean_latitude);
      for (int k = 1; k < 8; ++k) {
        const Point2 at = autopilot_offset(frame.to_geo(points[k]), o, mean_latitude);
        const Point2 expected = from + (to - from) * (k / 8.0);
        EXPECT_NEAR(at.x, expected.x, 1e-9) << trial << " " << k;
        EXPECT_NEAR(at.y, expected.y, 1e-9) << trial << " " << k;
      }
    }
  }
}

// Near a pole a track bends most away from its middle (a leg past the pole turns with the
// meridians): bow_m still finds its farthest point from the chord (against 512 points along each
// track), and the cheap bound keeps none there.
TEST(AutopilotTrack, NearAPoleTheBowIsTheFarthestPointOfTheTrack) {
  std::mt19937 rng(8946);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const double lat : {89.95, 89.46, -89.42, 88.0, -86.5}) {
    const LocalFrame frame({lat, 20.0, 0.0});
    const AutopilotTrack track(frame, {0, 0});
    for (int trial = 0; trial < 20; ++trial) {
      const Point2 a{3000 * unit(rng), 3000 * unit(rng)}, b{3000 * unit(rng), 3000 * unit(rng)};
      double farthest = 0;
      for (const auto& points : track.tracks(a, b, 512))
        for (const Point2 p : points) {
          const Point2 d = b - a;
          const double t = std::clamp(geometry::dot(p - a, d) / geometry::dot(d, d), 0.0, 1.0);
          farthest = std::max(farthest, geometry::distance(p, a + d * t));
        }
      const double bow = track.bow_m(a, b);
      EXPECT_GE(bow, 0.99 * farthest - 1e-6) << lat << " " << trial;
      EXPECT_GE(track.bow_bound_m(a, b), bow) << lat << " " << trial;
    }
  }
}

// A WPL 110 mission at 47 N: take off at home (the origin), fly to (-10 km, 1 km), then east to
// (10 km, 1 km), return to launch. ArduPilot flies the 20 km leg along a parallel, bowed 8.4 m
// south of the chord at its middle (the home legs pass a kilometre south of there).
std::string long_leg_mission(const LocalFrame& frame) {
  std::string out = "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47.000000000\t8.000000000\t0\t1\n";
  const auto item = [&](int index, int command, Point2 p) {
    const GeoPoint g = frame.to_geo(p);
    out += std::to_string(index) + "\t0\t3\t" + std::to_string(command) + "\t0\t0\t0\t0\t" +
           base::fixed_text(g.lat_deg, 9) + "\t" + base::fixed_text(g.lon_deg, 9) + "\t20\t1\n";
  };
  item(1, 22, {0, 0});
  item(2, 16, {-10000, 1000});
  item(3, 16, {10000, 1000});
  out += "4\t0\t3\t20\t0\t0\t0\t0\t0\t0\t0\t1\n";
  return out;
}

TEST(AutopilotTrack, TheCheckFliesALongLegIntoAZoneBesideItsChord) {
  const LocalFrame frame({47.0, 8.0, 0.0});
  const auto zone = [&](double y0, double y1) {
    std::vector<GeoPoint> ring;
    for (const Point2 p : {Point2{-100, y0}, Point2{100, y0}, Point2{100, y1}, Point2{-100, y1}})
      ring.push_back(frame.to_geo(p));
    return ring;
  };
  const missions::Mission m = missions::parse_mission(long_leg_mission(frame), "long.waypoints");
  // 6 m south of the chord: the straight leg clears it by more than the 5 m asked, the vehicle
  // flies 2.4 m into it.
  CheckOptions south;
  south.zones = {{"south", zone(970, 994)}};
  const Report in = verify({{m, 0.0, ""}}, south);
  ASSERT_FALSE(in.ok()) << report_text(in);
  EXPECT_EQ(in.violations.front().check, "no-fly zone");
  EXPECT_NE(in.violations.front().text.find("enters south"), std::string::npos)
      << in.violations.front().text;
  EXPECT_NE(in.violations.front().text.find("on the track ArduPilot flies"), std::string::npos);
  // 6 m north: ArduPilot passes about 14.4 m from it, PX4 (which flies the straight leg in its
  // own projection about home) 6 m: the check holds, at the least of the two.
  CheckOptions north;
  north.zones = {{"north", zone(1006, 1030)}};
  const Report clear = verify({{m, 0.0, ""}}, north);
  EXPECT_TRUE(clear.ok()) << report_text(clear);
  for (const Figure& f : clear.figures)
    if (f.check == "zones") EXPECT_NEAR(*f.value, 6.0, 1e-3);
}

}  // namespace
}  // namespace swath::preflight

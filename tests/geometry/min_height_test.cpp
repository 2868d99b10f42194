#include "swath/geometry/min_height.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "field_shapes.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/convex_hull.hpp"

namespace swath::geometry {
namespace {

double angle_gap_deg(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

TEST(MinHeight, RotatedRectangleIsItsShortSideAlongItsLongSide) {
  for (double theta : {0.0, 17.5, 45.0, 90.0, 123.0, 179.0}) {
    const Ring r = test::transformed({{0, 0}, {300, 0}, {300, 80}, {0, 80}}, theta, 1000, -500);
    const SweepDirection d = min_height_rotation(r);
    EXPECT_NEAR(d.height_m, 80.0, 1e-9) << theta;
    EXPECT_NEAR(angle_gap_deg(d.angle_deg, theta), 0.0, 1e-9) << theta;
    EXPECT_NEAR(height_at(r, theta + 90.0), 300.0, 1e-9);
  }
}

TEST(MinHeight, TriangleIsItsSmallestAltitude) {
  // Smallest altitude = 2 A / longest side, sweep lines parallel to the longest side.
  const Ring t{{0, 0}, {10, 0}, {3, 7}};
  const double longest = std::hypot(10.0, 0.0) > std::hypot(7.0, 7.0) ? 10.0 : std::hypot(7.0, 7.0);
  const SweepDirection d = min_height_rotation(t);
  EXPECT_NEAR(d.height_m, 2 * 35.0 / longest, 1e-12);
  EXPECT_NEAR(d.angle_deg, 0.0, 1e-12);
}

TEST(MinHeight, EqualsBruteForceOverHullEdges) {
  test::Rng rng(31);
  for (int k = 0; k < 300; ++k) {
    const Ring p = test::random_star_polygon(rng, 3 + k % 60, 10, 200);
    const Ring hull = convex_hull(p);
    double brute = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const Point2 e = hull[(i + 1) % hull.size()] - hull[i];
      double far = 0;
      for (const Point2& q : p)
        far = std::max(far, std::abs(cross(e, q - hull[i])) / std::hypot(e.x, e.y));
      brute = std::min(brute, far);
    }
    const SweepDirection d = min_height_rotation(p);
    EXPECT_NEAR(d.height_m, brute, 1e-9 * brute) << k;
    // The reported angle really gives the reported height (independent projection).
    EXPECT_NEAR(height_at(p, d.angle_deg), d.height_m, 1e-9 * brute) << k;
  }
}

double diameter(const Ring& p) {
  double d = 0;
  for (const Point2& a : p)
    for (const Point2& b : p) d = std::max(d, distance(a, b));
  return d;
}

TEST(MinHeightProperty, ExactNeverAboveTheTenthDegreeScanAndWithin0p2Percent) {
  // A scan misses the kink at the minimum by at most half a step, so its excess is at most
  // diameter * sin(0.05°): below 0.2 % of the height for field-like shapes (diameter < 2.3 x
  // height), checked on 1,000 such polygons; the bound itself is checked on thin ones too.
  test::Rng rng(1000);
  double worst = 0;
  for (int k = 0; k < 1000; ++k) {
    const Ring p =
        test::transformed(test::random_star_polygon(rng, 8 + k % 40, 60, 100), k * 0.37, 0, 0);
    const SweepDirection exact = min_height_rotation(p);
    const SweepDirection scan = min_height_scan(p, 0.1);
    EXPECT_LE(exact.height_m, scan.height_m * (1 + 1e-12)) << k;
    EXPECT_LE(scan.height_m, exact.height_m * 1.002) << k;
    worst = std::max(worst, scan.height_m / exact.height_m - 1);
  }
  RecordProperty("worst_relative_gap_0p1deg", std::to_string(worst));
  for (int k = 0; k < 300; ++k) {
    const Ring p =
        test::transformed(test::random_convex_polygon(rng, 3 + k % 10, 500, 5 + k), k * 1.1, 0, 0);
    const SweepDirection exact = min_height_rotation(p);
    const SweepDirection scan = min_height_scan(p, 0.1);
    EXPECT_LE(exact.height_m, scan.height_m * (1 + 1e-12)) << k;
    EXPECT_LE(scan.height_m - exact.height_m,
              diameter(p) * std::sin(0.05 * std::numbers::pi / 180) * (1 + 1e-9))
        << k;
  }
}

TEST(MinHeightProperty, FineScanConvergesOnTheExactHeight) {
  // A 0.001° scan can only miss the kink at the minimum by half a step: the gap is bounded by
  // diameter * sin(0.0005°) / height (~9e-6 relative for these shapes), and it shrinks with the
  // step. Both are checked; the angle agrees within the step.
  test::Rng rng(77);
  double worst = 0;
  for (int k = 0; k < 40; ++k) {
    const Ring p = test::random_star_polygon(rng, 5 + k % 10, 60, 100);
    const SweepDirection exact = min_height_rotation(p);
    const SweepDirection fine = min_height_scan(p, 0.001);
    const double bound = diameter(p) * std::sin(0.0005 * std::numbers::pi / 180);
    EXPECT_LE(exact.height_m, fine.height_m * (1 + 1e-12)) << k;
    EXPECT_LE(fine.height_m - exact.height_m, bound) << k;
    EXPECT_LE(angle_gap_deg(fine.angle_deg, exact.angle_deg), 0.001) << k;
    worst = std::max(worst, fine.height_m / exact.height_m - 1);
    const SweepDirection coarse = min_height_scan(p, 0.1);
    EXPECT_LE(fine.height_m, coarse.height_m * (1 + 1e-12)) << k;
  }
  EXPECT_LT(worst, 1e-5);
  RecordProperty("worst_relative_gap_0p001deg", std::to_string(worst));
}

TEST(MinHeight, BearingIsClockwiseFromNorth) {
  EXPECT_DOUBLE_EQ(line_bearing_deg(0.0), 90.0);     // east-west lines
  EXPECT_DOUBLE_EQ(line_bearing_deg(90.0), 0.0);     // north-south lines
  EXPECT_DOUBLE_EQ(line_bearing_deg(45.0), 45.0);    // NE-SW
  EXPECT_DOUBLE_EQ(line_bearing_deg(135.0), 135.0);  // NW-SE: bearing 135 (SE)
  EXPECT_DOUBLE_EQ(line_bearing_deg(30.0), 60.0);
}

}  // namespace
}  // namespace swath::geometry

namespace swath::geometry {
namespace {

// The split corpus's combs (seed 1): tooth-top corners lie on one hull line up to rounding. The
// calipers found 0 m on comb 9, and swath refused the field as "a line drawn as a polygon".
TEST(MinHeight, NearlyCollinearHullVerticesDoNotStopTheCalipers) {
  for (const test::CorpusShape& shape : test::split_corpus(1, 10)) {
    const std::vector<Point2>& ring = shape.area.outer;
    const SweepDirection exact = min_height_rotation(ring);
    const SweepDirection scan = min_height_scan(ring, 0.01);
    EXPECT_GT(exact.height_m, 0.5 * scan.height_m) << shape.family << ' ' << shape.index;
    EXPECT_LE(exact.height_m, scan.height_m + 1e-9) << shape.family << ' ' << shape.index;
    EXPECT_NEAR(exact.height_m, height_at(ring, exact.angle_deg), 1e-9);
  }
}

// The ring version (Melkman's hull) gives the sorted hull's height on simple rings.
TEST(MinHeight, SimpleRingVersionEqualsThePointSetVersion) {
  test::Rng rng(42);
  for (int k = 0; k < 300; ++k) {
    const Ring r = k % 2 ? test::random_star_polygon(rng, 3 + std::size_t(k % 200), 100, 400)
                         : test::random_field_polygon(rng, 5 + std::size_t(k % 300), 300);
    const SweepDirection a = min_height_rotation(r), b = min_height_of_simple_ring(r);
    EXPECT_NEAR(a.height_m, b.height_m, 1e-9 * a.height_m) << k;
    EXPECT_NEAR(height_at(r, b.angle_deg), b.height_m, 1e-9 * b.height_m) << k;
  }
}

}  // namespace
}  // namespace swath::geometry

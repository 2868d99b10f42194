// grow_simplified(): a fence for long outlines. Checked against its promise on noisy field
// outlines (fixed seeds): every point within the margin of the outline lies inside the result,
// and no result vertex lies further than 2 (margin + tolerance) + tolerance from it (distances by
// brute force over every edge); where simplifying drops no vertex, the result is grow()'s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "random_polygons.hpp"
#include "swath/geometry/offset.hpp"

namespace swath::geometry {
namespace {

// Even-odd crossing count: inside one of the rings.
bool inside_any(const std::vector<Ring>& rings, Point2 p) {
  for (const Ring& ring : rings) {
    bool odd = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
      if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
          p.x < ring[j].x + (p.y - ring[j].y) * (ring[i].x - ring[j].x) / (ring[i].y - ring[j].y))
        odd = !odd;
    if (odd) return true;
  }
  return false;
}

// Distance from p to the boundary of `ring`, by brute force over its edges.
double distance_to_boundary(const Ring& ring, Point2 p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], d = ring[(i + 1) % ring.size()] - a;
    const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
    best = std::min(best, distance(p, a + d * t));
  }
  return best;
}

// Distance from p to the closed area of `ring` (0 inside).
double distance_to(const Ring& ring, Point2 p) {
  return inside_any({ring}, p) ? 0 : distance_to_boundary(ring, p);
}

// A wedge of `angle` (radians) with its tip at `tip`, sides `length_m`, turned by `turn`
// (radians), counter-clockwise.
Ring wedge_at(Point2 tip, double angle, double length_m, double turn) {
  const auto at = [&](double a) {
    return tip + Point2{std::cos(turn + a), std::sin(turn + a)} * length_m;
  };
  return {tip, at(3.141592653589793 - angle / 2), at(3.141592653589793 + angle / 2)};
}

std::size_t vertices(const std::vector<Ring>& rings) {
  std::size_t n = 0;
  for (const Ring& r : rings) n += r.size();
  return n;
}

TEST(GrowSimplified, HoldsEveryPointWithinTheMarginAndStaysWithinItsBound) {
  test::Rng rng(1515);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int k = 0; k < 6; ++k) {
    const Ring field = test::random_field_polygon(rng, 800 + 400 * std::size_t(k), 300);
    const double margin_m = 20 + 80 * unit(rng), tolerance_m = std::min(5.0, 0.05 * margin_m);
    const std::vector<Ring> fence = grow_simplified({field}, margin_m, tolerance_m);
    const std::vector<Ring> exact = grow({field}, margin_m);
    // Far fewer vertices than growing every wiggle.
    EXPECT_LT(vertices(fence) * 4, vertices(exact)) << "field " << k;
    // Points at the margin (a hair inside it) off every edge's middle along its outward normal
    // and off every vertex in random directions: all inside.
    for (std::size_t i = 0; i < field.size(); ++i) {
      const Point2 a = field[i], b = field[(i + 1) % field.size()];
      const Point2 d = (b - a) * (1 / distance(a, b));
      const Point2 out{d.y, -d.x};  // right of a counter-clockwise ring's edge: outside
      const double turn = 2 * 3.141592653589793 * unit(rng);
      for (const Point2 p : {(a + b) * 0.5 + out * (margin_m * 0.999),
                             a + Point2{std::cos(turn), std::sin(turn)} * (margin_m * 0.999)})
        ASSERT_TRUE(inside_any(fence, p)) << "field " << k << " point " << p.x << ", " << p.y;
    }
    // No vertex further out than the bound.
    const double bound_m = 2 * (margin_m + tolerance_m) + tolerance_m + 1e-6;
    for (const Ring& r : fence)
      for (const Point2& v : r) ASSERT_LE(distance_to(field, v), bound_m) << "field " << k;
  }
}

// Wedges of 3 to 90 degrees, turned and scaled at random (fixed seed), with a second ring
// beside them: every point on the circle of 0.999 x the distance about each wedge's tip, and off
// its sides, lies inside the grown area (a mitre limited to twice the distance alone misses part
// of the circle at corners sharper than 60 degrees: 894 of 3,600 such points at 10 degrees).
TEST(Grow, HoldsTheWholeCircleAboutSharpCorners) {
  test::Rng rng(4040);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int k = 0; k < 40; ++k) {
    const double angle = (3 + 87 * unit(rng)) * 3.141592653589793 / 180;
    const double length_m = 20 + 200 * unit(rng), turn = 2 * 3.141592653589793 * unit(rng);
    const double distance_m = 1 + 30 * unit(rng);
    const Point2 tip{500 * unit(rng), 500 * unit(rng)};
    const Ring wedge = wedge_at(tip, angle, length_m, turn);
    const Ring beside{tip + Point2{1000, 0}, tip + Point2{1100, 0}, tip + Point2{1000, 100}};
    const std::vector<Ring> grown = grow({wedge, beside}, distance_m);
    for (int i = 0; i < 720; ++i) {
      const double a = 2 * 3.141592653589793 * i / 720;
      const Point2 p = tip + Point2{std::cos(a), std::sin(a)} * (0.999 * distance_m);
      ASSERT_TRUE(inside_any(grown, p))
          << "wedge " << k << " of " << angle * 180 / 3.14159 << " degrees, point " << i;
    }
    // No vertex further out than twice the distance.
    for (const Ring& r : grown)
      for (const Point2& v : r)
        ASSERT_LE(std::min(distance_to(wedge, v), distance_to(beside, v)), 2 * distance_m + 1e-6);
  }
}

// The inset area (subtract() shrinks by the boundary clearance with the same buffer) of wedges of
// 20 to 90 degrees: every vertex inside the wedge and at least the inset from its boundary. The
// 16-gons that grow() adds about sharp corners must not reach an inset area (they reached
// outside the field at its corners).
TEST(Subtract, InsetKeepsTheInsetFromEveryEdgeAtSharpCorners) {
  test::Rng rng(4041);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int k = 0; k < 20; ++k) {
    const double angle = (20 + 70 * unit(rng)) * 3.141592653589793 / 180;
    const Ring wedge = wedge_at({0, 0}, angle, 300, 2 * 3.141592653589793 * unit(rng));
    const double inset_m = 1 + 10 * unit(rng);
    const std::vector<Ring> inset = subtract(wedge, inset_m, {});
    ASSERT_FALSE(inset.empty()) << "wedge " << k;
    for (const Ring& r : inset)
      for (const Point2& v : r) {
        ASSERT_TRUE(inside_any({wedge}, v)) << "wedge " << k << ": " << v.x << ", " << v.y;
        // Within 1e-6 of the wedge's size: Boost's buffer rounds to a grid of the extent (its
        // points rescaled to integers), 2e-5 m short here.
        ASSERT_GE(distance_to_boundary(wedge, v), inset_m - 1e-6 * 300) << "wedge " << k;
      }
  }
}

TEST(GrowSimplified, IsGrowWhereNoVertexCanGo) {
  // A comb's corners are all needed at a tolerance below its 10 m teeth and gaps.
  const Ring comb = test::comb_polygon(6, 10, 40, 10);
  EXPECT_EQ(grow_simplified({comb}, 30, 1.5), grow({comb}, 30));
  const Ring square{{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  EXPECT_EQ(grow_simplified({square}, 30, 1.5), grow({square}, 30));
}

// Four bars that ring a field 250 m off (their union a frame with a pocket): grown keeping holes,
// the pocket stays free, and the field less the grown bars is the field whole; grow() fills the
// pocket (for fences), and the field less that is nothing, as the zones once "covered" it.
TEST(GrowKeepingHoles, ZonesThatRingAFieldLeaveItFree) {
  const Ring field{{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  const std::vector<Ring> bars{{{-300, -300}, {400, -300}, {400, -250}, {-300, -250}},
                               {{350, -300}, {400, -300}, {400, 400}, {350, 400}},
                               {{-300, 350}, {400, 350}, {400, 400}, {-300, 400}},
                               {{-300, -300}, {-250, -300}, {-250, 400}, {-300, 400}}};
  const std::vector<Ring> kept = grow_keeping_holes(bars, 5.0);
  ASSERT_EQ(kept.size(), 2u);  // the frame's outer ring, then its pocket
  EXPECT_GT(signed_area(kept[0]), 0);
  EXPECT_LT(signed_area(kept[1]), 0);
  EXPECT_NEAR(-signed_area(kept[1]), 590.0 * 590.0, 1.0);  // the pocket shrunk by 5 m each side
  const std::vector<Ring> left = subtract(field, 0, kept);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_NEAR(signed_area(left[0]), 100.0 * 100.0, 1e-6);
  EXPECT_TRUE(subtract(field, 0, grow(bars, 5.0)).empty());
  // A point in the pocket is free; one on a bar or within 5 m of it is not.
  EXPECT_FALSE(inside_any({kept[0]}, {50, 50}) != inside_any({kept[1]}, {50, 50}));
  EXPECT_TRUE(inside_any({kept[0]}, {-252, 50}) != inside_any({kept[1]}, {-252, 50}));
}

// Without a pocket the rings are grow()'s, and subtract() of them the same: plans without one keep
// their bytes.
TEST(GrowKeepingHoles, IsGrowWithoutAPocket) {
  std::mt19937 rng(2611);
  std::uniform_real_distribution<double> at(0, 500), size(5, 60);
  const Ring field{{0, 0}, {500, 0}, {500, 500}, {0, 500}};
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Ring> zones;
    for (int k = 0; k < 6; ++k) {
      const Point2 c{at(rng), at(rng)};
      const double h = size(rng);
      zones.push_back({c + Point2{-h, -h}, c + Point2{h, -h}, c + Point2{h, h}, c + Point2{-h, h}});
    }
    const std::vector<Ring> grown = grow(zones, 5.0);
    bool pocket = false;
    for (const Ring& r : grow_keeping_holes(zones, 5.0)) pocket = pocket || signed_area(r) < 0;
    if (pocket) continue;
    EXPECT_EQ(grow_keeping_holes(zones, 5.0), grown) << trial;
    EXPECT_EQ(subtract(field, 1.0, grown), subtract(field, 1.0, grow_keeping_holes(zones, 5.0)));
  }
}

}  // namespace
}  // namespace swath::geometry

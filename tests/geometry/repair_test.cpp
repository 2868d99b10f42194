#include "swath/geometry/repair.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "swath/geometry/classification.hpp"

namespace swath::geometry {
namespace {

TEST(EnclosedAreas, SimpleRingIsItself) {
  const auto pieces = enclosed_areas({{0, 0}, {0, 10}, {10, 10}, {10, 0}});  // clockwise input
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(signed_area(pieces[0]), 100.0);
}

TEST(EnclosedAreas, BowtieIsTwoTriangles) {
  const auto pieces = enclosed_areas({{0, 0}, {4, 4}, {4, 0}, {0, 4}});
  ASSERT_EQ(pieces.size(), 2u);
  for (const Ring& p : pieces) {
    EXPECT_DOUBLE_EQ(signed_area(p), 4.0);
    EXPECT_EQ(classify(Polygon{p, {}}).type, AreaType::convex);
  }
}

TEST(EnclosedAreas, PentagramIsItsOutline) {
  // {5/2} star: the union of the centre pentagon and the five points, one ten-vertex piece.
  Ring star;
  for (int k = 0; k < 5; ++k) {
    const double t = std::numbers::pi / 2 + 2 * std::numbers::pi * (2 * k) / 5;
    star.push_back({100 * std::cos(t), 100 * std::sin(t)});
  }
  const auto pieces = enclosed_areas(star);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].size(), 10u);
  // Closed form: area of a regular pentagram with circumradius R.
  const double r_inner = 100 * std::cos(2 * std::numbers::pi / 5) / std::cos(std::numbers::pi / 5);
  const double expected = 5 * 100 * r_inner * std::sin(std::numbers::pi / 5);
  EXPECT_NEAR(signed_area(pieces[0]), expected, 1e-9 * expected);
  EXPECT_EQ(classify(Polygon{pieces[0], {}}).type, AreaType::concave);
}

TEST(EnclosedAreas, FigureEightAndSpike) {
  const auto eight =
      enclosed_areas({{0, 0}, {2, 0}, {2, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 2}, {0, 2}});
  ASSERT_EQ(eight.size(), 2u);
  EXPECT_DOUBLE_EQ(signed_area(eight[0]) + signed_area(eight[1]), 8.0);
  // Back and forth along one line (10,10) -> (10,5) -> (10,20): the fold encloses nothing; what
  // remains is the trapezoid (0,0) (10,0) (10,20) (0,10).
  const auto folded = enclosed_areas({{0, 0}, {10, 0}, {10, 10}, {10, 5}, {10, 20}, {0, 10}});
  ASSERT_EQ(folded.size(), 1u);
  EXPECT_DOUBLE_EQ(signed_area(folded[0]), 150.0);
  EXPECT_EQ(folded[0].size(), 4u);
}

}  // namespace
}  // namespace swath::geometry

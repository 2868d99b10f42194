#include "swath/geometry/visibility.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace swath::geometry {
namespace {

// 100 x 100 square with a tall hole x in [40, 60], y in [20, 80].
VisibilityRouter square_with_hole() {
  return VisibilityRouter(
      {{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {{40, 20}, {40, 80}, {60, 80}, {60, 20}}});
}

TEST(VisibilityRouter, GoesAroundAHoleAlongTheShortestSide) {
  const VisibilityRouter r = square_with_hole();
  EXPECT_FALSE(r.visible({20, 50}, {80, 50}));
  const auto path = r.path({20, 50}, {80, 50});
  // Around either end of the hole: 2 x |(20,50)-(40,80)| + 20.
  EXPECT_NEAR(polyline_length(path), 2 * std::hypot(20.0, 30.0) + 20, 1e-9);
  ASSERT_EQ(path.size(), 4u);
  for (std::size_t i = 0; i + 1 < path.size(); ++i) EXPECT_TRUE(r.visible(path[i], path[i + 1]));
  // A clear leg stays straight; a leg along the boundary is inside.
  EXPECT_EQ(r.path({10, 10}, {90, 10}).size(), 2u);
  EXPECT_TRUE(r.visible({0, 0}, {100, 0}));
  EXPECT_TRUE(r.visible({40, 20}, {40, 80}));
}

TEST(VisibilityRouter, ContainsIsInsideTheClosedAreaNotAZeroLengthLeg) {
  const VisibilityRouter r = square_with_hole();
  EXPECT_TRUE(r.contains({20, 50}));
  EXPECT_TRUE(r.contains({0, 50}));      // on the outer boundary
  EXPECT_TRUE(r.contains({40, 50}));     // on the hole's boundary
  EXPECT_FALSE(r.contains({50, 50}));    // in the hole
  EXPECT_FALSE(r.contains({-60, -40}));  // outside, where a home is
  // The mistake this guards against: a leg of length 0 is "visible" wherever it is.
  EXPECT_TRUE(r.visible({-60, -40}, {-60, -40}));
}

TEST(VisibilityRouter, LengthOutsideCountsHolesAndTheOutside) {
  const VisibilityRouter r = square_with_hole();
  EXPECT_NEAR(r.length_outside({-10, 50}, {110, 50}), 10 + 20 + 10, 1e-9);
  EXPECT_NEAR(r.length_outside({20, 50}, {80, 50}), 20, 1e-9);
  EXPECT_NEAR(r.length_outside({50, -50}, {50, 150}), 50 + 60 + 50, 1e-9);
  // The diagonal crosses the hole from (40, 40) to (60, 60).
  EXPECT_NEAR(r.length_outside({5, 5}, {95, 95}), 20 * std::sqrt(2.0), 1e-9);
}

TEST(VisibilityRouter, UShapeRoutesOverTheNotchFloor) {
  // U opening upwards; from the top of one arm to the top of the other, around the notch corners.
  const VisibilityRouter r(
      {{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}}});
  const auto path = r.path({5, 25}, {25, 25});
  EXPECT_NEAR(polyline_length(path), 2 * std::hypot(5.0, 15.0) + 10, 1e-9);
}

TEST(VisibilityRouter, TooComplexAreasAreNotRouted) {
  const VisibilityRouter r(
      {{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}}}, 1);
  EXPECT_FALSE(r.routes());
  EXPECT_EQ(r.path({5, 25}, {25, 25}).size(), 2u);
  EXPECT_NEAR(r.length_outside({5, 25}, {25, 25}), 10, 1e-9);
}

}  // namespace
}  // namespace swath::geometry

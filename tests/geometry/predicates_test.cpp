#include "swath/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace swath::geometry {
namespace {

TEST(Orientation, ExactWhereNaiveDoubleArithmeticIsWrong) {
  // Kettner et al.'s classic: points near (0.5, 0.5) on the line y = x, moved by single ulps.
  const Point2 b{12, 12}, c{24, 24};
  int naive_wrong = 0;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      const Point2 a{0.5 + i * std::ldexp(1.0, -53), 0.5 + j * std::ldexp(1.0, -53)};
      // Exact truth: a is on the line iff ax == ay; left of b->c iff ay > ax.
      const Orientation expected = a.y > a.x   ? Orientation::counter_clockwise
                                   : a.y < a.x ? Orientation::clockwise
                                               : Orientation::collinear;
      EXPECT_EQ(orientation(b, c, a), expected) << i << ' ' << j;
      const double naive = (c.x - b.x) * (a.y - b.y) - (c.y - b.y) * (a.x - b.x);
      const Orientation naive_o = naive > 0   ? Orientation::counter_clockwise
                                  : naive < 0 ? Orientation::clockwise
                                              : Orientation::collinear;
      naive_wrong += naive_o != expected;
    }
  }
  EXPECT_GT(naive_wrong, 0) << "the example should defeat plain doubles";
}

TEST(SegmentsIntersect, CrossingTouchingOverlappingDisjoint) {
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 2}, {0, 2}, {2, 0}));
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {1, 5}));   // T touch
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {3, 0}));   // overlap
  EXPECT_FALSE(segments_intersect({0, 0}, {2, 0}, {3, 0}, {4, 0}));  // collinear apart
  EXPECT_FALSE(segments_intersect({0, 0}, {2, 2}, {0, 1}, {1, 2}));  // parallel
  const Point2 p = segments_common_point({0, 0}, {2, 2}, {0, 2}, {2, 0});
  EXPECT_DOUBLE_EQ(p.x, 1.0);
  EXPECT_DOUBLE_EQ(p.y, 1.0);
}

TEST(LocatePoint, InsideOutsideAndBoundaryOfAConcaveRing) {
  const std::vector<Point2> l{{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}};
  EXPECT_EQ(locate_point({5, 5}, l), Containment::inside);
  EXPECT_EQ(locate_point({5, 15}, l), Containment::inside);
  EXPECT_EQ(locate_point({15, 15}, l), Containment::outside);
  EXPECT_EQ(locate_point({15, 10}, l), Containment::on_boundary);
  EXPECT_EQ(locate_point({10, 10}, l), Containment::on_boundary);
  EXPECT_EQ(locate_point({25, 10}, l), Containment::outside);  // ray through a vertex
  EXPECT_EQ(locate_point({-1, 20}, l), Containment::outside);
}

}  // namespace
}  // namespace swath::geometry

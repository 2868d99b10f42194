// The farm-scale corpus's traced outlines (test::traced_outline, bench/field_corpus.cpp) are what
// they claim: simple (every pair of edges checked by brute force, not by the sweep that generated
// them), 0.3-3 km across plus their arms, hundreds of vertices mostly on nearly straight stretches
// a few metres apart, holes inside the outline, and the same outlines from the same seed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "field_shapes.hpp"

namespace swath::test {
namespace {

using geometry::Point2;
using geometry::Ring;

double cross(Point2 o, Point2 a, Point2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Whether closed segments [a, b] and [c, d] share a point (touching counts), in doubles: the
// generator keeps everything metres apart, so no case here is near degenerate.
bool segments_meet(Point2 a, Point2 b, Point2 c, Point2 d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  const auto on = [](Point2 p, Point2 q, Point2 r) {  // r on [p, q], given collinear
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  return (d1 == 0 && on(c, d, a)) || (d2 == 0 && on(c, d, b)) || (d3 == 0 && on(a, b, c)) ||
         (d4 == 0 && on(a, b, d));
}

// Every pair of edges of all rings that are not neighbours in one ring: none may meet.
bool brute_force_simple(const geometry::Polygon& p) {
  std::vector<Ring> rings{p.outer};
  rings.insert(rings.end(), p.holes.begin(), p.holes.end());
  for (std::size_t r = 0; r < rings.size(); ++r)
    for (std::size_t i = 0; i < rings[r].size(); ++i)
      for (std::size_t s = r; s < rings.size(); ++s)
        for (std::size_t j = s == r ? i + 1 : 0; j < rings[s].size(); ++j) {
          const std::size_t n = rings[r].size();
          if (s == r && (j == i + 1 || (i == 0 && j == n - 1))) continue;  // neighbours
          if (segments_meet(rings[r][i], rings[r][(i + 1) % n], rings[s][j],
                            rings[s][(j + 1) % rings[s].size()]))
            return false;
        }
  return true;
}

double shoelace(const Ring& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) a += cross({0, 0}, r[i], r[(i + 1) % r.size()]);
  return a / 2;
}

bool inside_by_ray(Point2 p, const Ring& r) {
  bool in = false;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    if ((r[i].y > p.y) != (r[j].y > p.y) &&
        p.x < (r[j].x - r[i].x) * (p.y - r[i].y) / (r[j].y - r[i].y) + r[i].x)
      in = !in;
  return in;
}

TEST(TracedOutline, SimpleTracedOutlinesOfFarmSize) {
  Rng rng(52);
  int with_holes = 0, many_vertices = 0;
  for (int k = 0; k < 40; ++k) {
    const geometry::Polygon p = traced_outline(rng);
    SCOPED_TRACE(k);
    ASSERT_TRUE(brute_force_simple(p));
    EXPECT_GT(shoelace(p.outer), 0);  // counter-clockwise
    double diameter = 0;
    for (const Point2& a : p.outer)
      for (const Point2& b : p.outer)
        diameter = std::max(diameter, std::hypot(a.x - b.x, a.y - b.y));
    EXPECT_GE(diameter, 300);
    EXPECT_LE(diameter, 3000 * std::numbers::sqrt2 * 1.4);  // 3 km squashed, plus an arm
    EXPECT_GE(p.outer.size(), 100u);
    many_vertices += p.outer.size() >= 300;
    // A GPS trace: most vertices turn by under 10 degrees, and half of the edges are under 15 m.
    int straight = 0;
    std::vector<double> edges;
    const std::size_t n = p.outer.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 a = p.outer[(i + n - 1) % n], b = p.outer[i], c = p.outer[(i + 1) % n];
      const double turn = std::abs(
          std::atan2(cross(a, b, c), (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y)));
      straight += turn < 10 * std::numbers::pi / 180;
      edges.push_back(std::hypot(c.x - b.x, c.y - b.y));
    }
    EXPECT_GE(straight, 0.8 * double(n));
    std::nth_element(edges.begin(), edges.begin() + std::ptrdiff_t(n / 2), edges.end());
    EXPECT_LT(edges[n / 2], 15.0);
    for (const Ring& h : p.holes) {
      EXPECT_LT(shoelace(h), 0);  // clockwise
      for (const Point2& v : h) EXPECT_TRUE(inside_by_ray(v, p.outer));
    }
    with_holes += !p.holes.empty();
  }
  EXPECT_GE(with_holes, 5);      // about 40 % have holes
  EXPECT_GE(many_vertices, 20);  // hundreds of vertices
}

TEST(TracedOutline, TheSameSeedGivesTheSameOutlines) {
  Rng a(7), b(7);
  for (int k = 0; k < 5; ++k) {
    const geometry::Polygon p = traced_outline(a), q = traced_outline(b);
    ASSERT_EQ(p.outer.size(), q.outer.size());
    for (std::size_t i = 0; i < p.outer.size(); ++i) {
      EXPECT_EQ(p.outer[i].x, q.outer[i].x);
      EXPECT_EQ(p.outer[i].y, q.outer[i].y);
    }
    EXPECT_EQ(p.holes.size(), q.holes.size());
  }
}

}  // namespace
}  // namespace swath::test

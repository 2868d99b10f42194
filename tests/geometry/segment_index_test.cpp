// The segment index only prunes: every query through it must answer exactly what the same exact
// predicates answer over all edges. Checked against brute force on random areas with holes (fixed
// seeds), with queries through vertices, along edges, on edges and across the grid's cells, and
// on integer grids full of collinear and touching edges.
#include "swath/geometry/segment_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>

#include "brute_area.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/visibility.hpp"

namespace swath::geometry {
namespace {

std::vector<Segment> edges_of(const std::vector<Ring>& rings) {
  std::vector<Segment> edges;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i)
      edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
  return edges;
}

// A field with `holes` holes: rectangles on a grid and small random stars (clockwise), some
// touching the rectangles' corners' rows and columns (equal coordinates).
std::vector<Ring> holey_area(test::Rng& rng, std::size_t n, int holes) {
  std::vector<Ring> rings{test::random_field_polygon(rng, n, 500)};
  for (int h = 0; h < holes; ++h) {
    const double x = -300 + 75.0 * (h % 8), y = -300 + 75.0 * (h / 8);
    if (h % 3 == 2) {
      Ring star = test::transformed(test::random_star_polygon(rng, 7, 5, 15), 0, x + 12, y + 10);
      std::reverse(star.begin(), star.end());
      rings.push_back(star);
    } else {
      rings.push_back({{x, y}, {x, y + 20}, {x + 25, y + 20}, {x + 25, y}});
    }
  }
  return rings;
}

// Query segments that stress the exact cases: between vertices (through others on the same row or
// column), along edges (inside them, beyond their ends), from points on edges, and at random.
std::vector<Segment> queries(test::Rng& rng, const std::vector<Ring>& rings, int count) {
  std::vector<Point2> vertices;
  for (const Ring& ring : rings) vertices.insert(vertices.end(), ring.begin(), ring.end());
  const std::vector<Segment> edges = edges_of(rings);
  std::uniform_real_distribution<double> unit(0, 1), coordinate(-650, 650);
  std::uniform_int_distribution<std::size_t> vertex(0, vertices.size() - 1),
      edge(0, edges.size() - 1);
  auto on_edge = [&](double t) {
    const Segment& e = edges[edge(rng)];
    return e.a + (e.b - e.a) * t;
  };
  std::vector<Segment> out;
  for (int k = 0; k < count; ++k) {
    switch (k % 7) {
      case 0:
        out.push_back({vertices[vertex(rng)], vertices[vertex(rng)]});
        break;
      case 1: {  // along an edge, part of it or beyond its ends
        const Segment& e = edges[edge(rng)];
        const double t0 = unit(rng) * 2 - 0.5, t1 = unit(rng) * 2 - 0.5;
        out.push_back({e.a + (e.b - e.a) * t0, e.a + (e.b - e.a) * t1});
        break;
      }
      case 2:
        out.push_back({on_edge(unit(rng)), on_edge(unit(rng))});
        break;
      case 3: {  // horizontal or vertical through a vertex
        const Point2 v = vertices[vertex(rng)];
        out.push_back(k % 2 ? Segment{{v.x - 400, v.y}, {v.x + 400, v.y}}
                            : Segment{{v.x, v.y - 400}, {v.x, v.y + 400}});
        break;
      }
      case 4:
        out.push_back({vertices[vertex(rng)], {coordinate(rng), coordinate(rng)}});
        break;
      case 5: {  // a point: zero length
        const Point2 p{coordinate(rng), coordinate(rng)};
        out.push_back({p, p});
        break;
      }
      default:
        out.push_back({{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}});
    }
  }
  return out;
}

// Points for containment: vertices, points on edges, points a rounding error off edges, random.
std::vector<Point2> points(test::Rng& rng, const std::vector<Ring>& rings, int count) {
  std::vector<Point2> out;
  for (const Segment& q : queries(rng, rings, count)) {
    out.push_back(q.a);
    out.push_back((q.a + q.b) * 0.5);
    out.push_back({std::nextafter(q.a.x, 1e9), q.a.y});
  }
  return out;
}

TEST(SegmentIndex, FindsEverySegmentAQueryMeetsAndEachRayCrossingOnce) {
  test::Rng rng(18);
  std::size_t rays_left = 0, rays_right = 0;  // near_ray()'s choices
  for (int area = 0; area < 12; ++area) {
    const std::vector<Ring> rings = area % 4 == 3
                                        ? std::vector<Ring>{test::random_grid_ring(rng, 40, 12),
                                                            test::random_grid_ring(rng, 12, 12)}
                                        : holey_area(rng, std::size_t(10) << area % 4, 50);
    const std::vector<Segment> edges = edges_of(rings);
    for (const double cells : {0.1, 4.0, 50.0}) {
      const SegmentIndex index(edges, cells);
      for (const Segment& q : queries(rng, rings, 700)) {
        std::vector<char> found(edges.size(), 0);
        index.near_segment(q.a, q.b, [&](std::uint32_t e) { found[e] = 1; });
        for (std::size_t e = 0; e < edges.size(); ++e) {
          if (segments_intersect(q.a, q.b, edges[e].a, edges[e].b)) {
            ASSERT_TRUE(found[e]) << "area " << area << " edge " << e;
          }
        }
        // The ray: the edges that hold p or cross it, each exactly once.
        std::vector<int> times(edges.size(), 0);
        index.near_ray_right(q.a, [&](std::uint32_t e) { ++times[e]; });
        for (std::size_t e = 0; e < edges.size(); ++e) {
          ASSERT_LE(times[e], 1);
          if (edge_and_ray(q.a, edges[e].a, edges[e].b) != EdgeAndRay::apart) {
            ASSERT_EQ(times[e], 1) << "area " << area << " edge " << e;
          }
        }
        // The ray to the left: the edges that hold p or cross it (as edge_and_ray sees them in
        // the mirror image), each exactly once.
        std::fill(times.begin(), times.end(), 0);
        index.near_ray_left(q.a, [&](std::uint32_t e) { ++times[e]; });
        const auto mirrored = [](Point2 x) { return Point2{-x.x, x.y}; };
        for (std::size_t e = 0; e < edges.size(); ++e) {
          ASSERT_LE(times[e], 1);
          if (edge_and_ray(mirrored(q.a), mirrored(edges[e].a), mirrored(edges[e].b)) !=
              EdgeAndRay::apart) {
            ASSERT_EQ(times[e], 1) << "area " << area << " edge " << e << " (left)";
          }
        }
        // near_ray(): one of the two rays, each of its edges exactly once (the rays walk each
        // row's edges sorted by how far they reach, from the farthest: every one reaching p).
        std::fill(times.begin(), times.end(), 0);
        std::vector<int> left_times(edges.size(), 0);
        const bool to_left = index.near_ray(
            q.a, [&](std::uint32_t e) { ++times[e]; }, [&](std::uint32_t e) { ++left_times[e]; });
        for (std::size_t e = 0; e < edges.size(); ++e) {
          ASSERT_EQ(to_left ? times[e] : left_times[e], 0);
          const int walked = to_left ? left_times[e] : times[e];
          ASSERT_LE(walked, 1);
          const EdgeAndRay where =
              to_left ? edge_and_ray(mirrored(q.a), mirrored(edges[e].a), mirrored(edges[e].b))
                      : edge_and_ray(q.a, edges[e].a, edges[e].b);
          if (where != EdgeAndRay::apart) {
            ASSERT_EQ(walked, 1) << "area " << area << " edge " << e << (to_left ? " (left)" : "");
          }
        }
        (to_left ? rays_left : rays_right) += 1;
        // The box around a point: every edge with a point in it.
        const double r = 1 + std::abs(q.b.x - q.a.x) / 50;
        std::fill(found.begin(), found.end(), 0);
        index.near_box(q.a - Point2{r, r}, q.a + Point2{r, r},
                       [&](std::uint32_t e) { found[e] = 1; });
        for (std::size_t e = 0; e < edges.size(); ++e) {
          if (distance_to_segment(q.a, edges[e].a, edges[e].b) <= r) {
            ASSERT_TRUE(found[e]);
          }
        }
      }
    }
  }
  // near_ray() takes both ways often.
  EXPECT_GT(rays_left, 5000u);
  EXPECT_GT(rays_right, 5000u);
}

TEST(SegmentIndex, RouterAnswersBitForBitAsOverAllEdges) {
  test::Rng rng(1818);
  for (int area = 0; area < 8; ++area) {
    const std::vector<Ring> rings =
        area % 4 == 3 ? std::vector<Ring>{test::random_grid_ring(rng, 30, 10)}
                      : holey_area(rng, std::size_t(12) << area % 4, 10 + 10 * area);
    const test::BruteArea brute(rings);
    const VisibilityRouter router(rings, Routing::measure_only);
    for (const Segment& q : queries(rng, rings, 1500)) {
      const double indexed = router.length_outside(q.a, q.b), all = brute.length_outside(q.a, q.b);
      ASSERT_EQ(indexed, all) << "area " << area << " (" << q.a.x << ", " << q.a.y << ") - ("
                              << q.b.x << ", " << q.b.y << ")";
      ASSERT_EQ(router.visible(q.a, q.b), brute.visible(q.a, q.b));
    }
    for (const Point2& p : points(rng, rings, 500))
      ASSERT_EQ(router.contains(p), brute.contains(p));
  }
}

// The shortcuts in orientation() and segments_intersect() against integer arithmetic (coordinates
// small integers, so every product is exact in doubles too): the truth for degenerate cases.
int sign_of_orientation(Point2 a, Point2 b, Point2 c) {
  const auto det =
      (std::int64_t(a.x) - std::int64_t(c.x)) * (std::int64_t(b.y) - std::int64_t(c.y)) -
      (std::int64_t(a.y) - std::int64_t(c.y)) * (std::int64_t(b.x) - std::int64_t(c.x));
  return det > 0 ? 1 : det < 0 ? -1 : 0;
}
bool between(Point2 a, Point2 b, Point2 p) {  // p collinear with [a, b]: on it?
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}
bool integer_segments_meet(Point2 a, Point2 b, Point2 c, Point2 d) {
  const int o1 = sign_of_orientation(a, b, c), o2 = sign_of_orientation(a, b, d);
  const int o3 = sign_of_orientation(c, d, a), o4 = sign_of_orientation(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && between(a, b, c)) || (o2 == 0 && between(a, b, d)) ||
         (o3 == 0 && between(c, d, a)) || (o4 == 0 && between(c, d, b));
}

TEST(SegmentIndex, PredicateShortcutsAgreeWithIntegerArithmetic) {
  test::Rng rng(7);
  std::uniform_int_distribution<int> small(-4, 4);
  auto point = [&] { return Point2{double(small(rng)), double(small(rng))}; };
  int meeting = 0;
  for (int k = 0; k < 200000; ++k) {
    const Point2 a = point(), b = point(), c = point(), d = point();
    ASSERT_EQ(int(orientation(a, b, c)), sign_of_orientation(a, b, c));
    const bool meet = integer_segments_meet(a, b, c, d);
    ASSERT_EQ(segments_intersect(a, b, c, d), meet)
        << a.x << "," << a.y << " " << b.x << "," << b.y << " " << c.x << "," << c.y << " " << d.x
        << "," << d.y;
    meeting += meet;
  }
  EXPECT_GT(meeting, 20000);  // the cases are not all one way
  // Shared coordinates off the integers (left == 0 in orientation's filter): the exact kernel.
  std::uniform_real_distribution<double> real(-1e3, 1e3);
  for (int k = 0; k < 100000; ++k) {
    Point2 a{real(rng), real(rng)}, b{real(rng), real(rng)}, c{real(rng), real(rng)};
    if (k % 3 == 0) c.x = a.x;
    if (k % 3 == 1) c.y = b.y;
    if (k % 5 == 0) c.y = a.y;
    if (k % 7 == 0) c.x = b.x;
    ASSERT_EQ(orientation(a, b, c), orientation_exact(a, b, c));
  }
}

}  // namespace
}  // namespace swath::geometry

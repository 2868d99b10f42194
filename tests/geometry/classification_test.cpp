#include "swath/geometry/classification.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "random_polygons.hpp"
#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/predicates.hpp"
#include "type_detection.hpp"

namespace swath::geometry {
namespace {

Polygon normalised(const Ring& outer, std::vector<Ring> holes = {}) {
  Polygon p{normalise_ring(outer, true).ring, {}};
  for (const Ring& h : holes) p.holes.push_back(normalise_ring(h, false).ring);
  return p;
}

TEST(Classify, ConvexEvenWithCollinearVertices) {
  const Classification c = classify(normalised({{0, 0}, {5, 0}, {10, 0}, {10, 10}, {0, 10}}));
  EXPECT_EQ(c.type, AreaType::convex);
  EXPECT_TRUE(c.reflex_vertices.empty());
  EXPECT_FALSE(c.crossing);
}

TEST(Classify, ConcaveReportsReflexVertex) {
  const Classification c =
      classify(normalised({{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}}));
  EXPECT_EQ(c.type, AreaType::concave);
  ASSERT_EQ(c.reflex_vertices.size(), 1u);
  EXPECT_EQ(c.reflex_vertices[0], (RingIndex{0, 3}));
}

TEST(Classify, BowtieCrossesAtItsCentre) {
  const Classification c = classify(Polygon{{{0, 0}, {4, 4}, {4, 0}, {0, 4}}, {}});
  EXPECT_EQ(c.type, AreaType::self_intersecting);
  ASSERT_TRUE(c.crossing);
  EXPECT_EQ(c.crossing->edge_a, (RingIndex{0, 0}));
  EXPECT_EQ(c.crossing->edge_b, (RingIndex{0, 2}));
  EXPECT_DOUBLE_EQ(c.crossing->point.x, 2.0);
  EXPECT_DOUBLE_EQ(c.crossing->point.y, 2.0);
}

TEST(Classify, TouchingCasesAreSelfIntersecting) {
  // Two squares meeting at one vertex visited twice.
  const Ring figure_eight{{0, 0}, {2, 0}, {2, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 2}, {0, 2}};
  EXPECT_EQ(classify(Polygon{figure_eight, {}}).type, AreaType::self_intersecting);
  // A vertex lying on a non-adjacent edge.
  const Polygon vertex_on_edge{{{0, 0}, {10, 0}, {10, 10}, {5, 0.0}, {0, 10}}, {}};
  const Classification c = classify(vertex_on_edge);
  EXPECT_EQ(c.type, AreaType::self_intersecting);
  ASSERT_TRUE(c.crossing);
  EXPECT_EQ(c.crossing->point, (Point2{5, 0}));
  // A spike: out and back along one line.
  EXPECT_EQ(classify(Polygon{{{0, 0}, {10, 0}, {10, 10}, {10, 5}, {10, 20}, {0, 10}}, {}}).type,
            AreaType::self_intersecting);
  // Vertical edges meeting end to start along one line but overlapping.
  EXPECT_EQ(classify(Polygon{{{0, 0}, {0, 10}, {0, 5}, {-5, 5}}, {}}).type,
            AreaType::self_intersecting);
}

TEST(Classify, HolesMakeAnAreaConcaveAndMustNotTouchTheBoundary) {
  const Ring square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const Classification inside = classify(normalised(square, {{{2, 2}, {4, 2}, {4, 4}, {2, 4}}}));
  EXPECT_EQ(inside.type, AreaType::concave);
  EXPECT_EQ(inside.reflex_vertices.size(), 4u);  // every corner of the hole
  EXPECT_EQ(classify(normalised(square, {{{0, 2}, {4, 2}, {4, 4}}})).type,
            AreaType::self_intersecting);
  const Classification crossing =
      classify(normalised(square, {{{8, 4}, {12, 4}, {12, 6}, {8, 6}}}));
  EXPECT_EQ(crossing.type, AreaType::self_intersecting);
  EXPECT_EQ(crossing.crossing->edge_a.ring, 0u);
  EXPECT_EQ(crossing.crossing->edge_b.ring, 1u);
  EXPECT_DOUBLE_EQ(crossing.crossing->point.x, 10.0);
  // Two holes overlapping each other.
  EXPECT_EQ(classify(normalised(square, {{{2, 2}, {5, 2}, {5, 5}, {2, 5}},
                                         {{{4, 4}, {7, 4}, {7, 7}, {4, 7}}}}))
                .type,
            AreaType::self_intersecting);
}

double segment_distance(Point2 p, Point2 a, Point2 b) {
  const Point2 d = b - a;
  const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return distance(p, a + d * t);
}

// The sweep and the paper's O(n²) TypeDetection agree on type and reflex vertices, and a reported
// crossing is a real one between two edges that are not neighbours.
void expect_agreement(const Polygon& p, const std::string& what) {
  const Classification fast = classify(p);
  const reference::TypeDetection slow = reference::type_detection_quadratic(p);
  ASSERT_EQ(fast.type, slow.type) << what;
  EXPECT_EQ(fast.reflex_vertices, slow.reflex_vertices) << what;
  if (fast.crossing) {
    const auto edge = [&](RingIndex e) {
      const Ring& r = ring_at(p, e.ring);
      return std::pair{r[e.index], r[(e.index + 1) % r.size()]};
    };
    const auto [a0, a1] = edge(fast.crossing->edge_a);
    const auto [b0, b1] = edge(fast.crossing->edge_b);
    EXPECT_TRUE(segments_intersect(a0, a1, b0, b1)) << what;
    const double scale =
        std::max({std::abs(a0.x), std::abs(a0.y), std::abs(b0.x), std::abs(b0.y), 1.0});
    EXPECT_LE(segment_distance(fast.crossing->point, a0, a1), 1e-12 * scale) << what;
    EXPECT_LE(segment_distance(fast.crossing->point, b0, b1), 1e-12 * scale) << what;
  }
}

TEST(ClassifyProperty, AgreesWithPaperTypeDetectionOnRandomStarPolygons) {
  test::Rng rng(2024);
  int concave = 0;
  for (int k = 0; k < 500; ++k) {
    const Polygon p = normalised(test::random_star_polygon(rng, 3 + k % 30, 10 + k % 50, 100));
    expect_agreement(p, "star " + std::to_string(k));
    concave += classify(p).type == AreaType::concave;
  }
  EXPECT_GT(concave, 300);
}

TEST(ClassifyProperty, AgreesOnRandomConvexPolygons) {
  test::Rng rng(7);
  for (int k = 0; k < 300; ++k) {
    const Polygon p = normalised(test::random_convex_polygon(rng, 3 + k % 50, 300, 40 + k));
    EXPECT_EQ(classify(p).type, AreaType::convex) << k;
    expect_agreement(p, "convex " + std::to_string(k));
  }
}

TEST(ClassifyProperty, AgreesOnDegenerateIntegerRings) {
  // Random vertex orders on small grids: crossings, touching vertices, overlapping collinear edges.
  test::Rng rng(99);
  int counts[3] = {0, 0, 0};
  for (int k = 0; k < 3000; ++k) {
    Ring ring = test::random_grid_ring(rng, 3 + k % 9, 3 + k % 6);
    const NormalisedRing n = normalise_ring(ring, true);
    if (convex_hull(n.ring).size() < 3) continue;  // all collinear: the reader refuses these
    const Polygon p{n.ring, {}};
    expect_agreement(p, "grid " + std::to_string(k));
    ++counts[static_cast<int>(classify(p).type)];
  }
  EXPECT_GT(counts[0], 50);
  EXPECT_GT(counts[1], 50);
  EXPECT_GT(counts[2], 500);
}

TEST(ClassifyProperty, AgreesWithHolesOnAGrid) {
  // Square holes on a grid inside a big square, some touching or overlapping each other.
  test::Rng rng(5);
  std::uniform_int_distribution<int> cell(1, 8);
  for (int k = 0; k < 400; ++k) {
    std::vector<Ring> holes;
    for (int h = 0; h < 1 + k % 5; ++h) {
      const double x = cell(rng), y = cell(rng);
      holes.push_back({{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}});
    }
    expect_agreement(normalised({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, holes),
                     "holes " + std::to_string(k));
  }
}

TEST(ClassifyProperty, CombsAreConcaveWithTwoReflexVerticesPerGap) {
  for (int teeth = 2; teeth < 40; ++teeth) {
    const Polygon p =
        normalised(test::transformed(test::comb_polygon(teeth, 3, 20, 5), teeth * 13.0, 50, 80));
    const Classification c = classify(p);
    EXPECT_EQ(c.type, AreaType::concave);
    EXPECT_EQ(c.reflex_vertices.size(), 2u * (teeth - 1));
  }
}

}  // namespace
}  // namespace swath::geometry

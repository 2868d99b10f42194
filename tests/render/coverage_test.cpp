// The coverage rasteriser against independent truth: a brute-force count of 64 x 64 sample points
// per pixel (even-odd point-in-polygon by ray crossing), the shoelace area, and closed-form areas
// of holes and unions.
#include "coverage_rasterizer.hpp"

#include "shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace swath::render::detail {
namespace {

using geometry::Point2;
using Ring = std::vector<Point2>;

constexpr int kSamples = 64;  // per pixel side for the brute force

struct Coverage {
  int width, height;
  std::vector<double> at;  // row-major
  double sum() const {
    double s = 0;
    for (double c : at) s += c;
    return s;
  }
};

Coverage rasterize(const std::vector<Ring>& rings, int width, int height, FillRule rule) {
  CoverageRasterizer r(width, height);
  for (const Ring& ring : rings) r.add_ring(ring);
  Coverage out{width, height, std::vector<double>(static_cast<std::size_t>(width) * height, 0.0)};
  r.rasterize(rule, [&](int y, int x_begin, std::span<const float> row) {
    ASSERT_GE(y, 0);
    ASSERT_LT(y, height);
    ASSERT_GE(x_begin, 0);
    ASSERT_LE(x_begin + static_cast<int>(row.size()), width);
    for (std::size_t i = 0; i < row.size(); ++i) out.at[y * width + x_begin + i] = row[i];
  });
  return out;
}

// Number of rings' edges crossed by a rightward ray from p (the crossing-number test).
int crossings(const std::vector<Ring>& rings, Point2 p) {
  int n = 0;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)) ++n;
    }
  return n;
}

double brute_force(const std::vector<Ring>& rings, int px, int py) {
  int inside = 0;
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i)
      inside += crossings(rings, {px + (i + 0.5) / kSamples, py + (j + 0.5) / kSamples}) & 1;
  return static_cast<double>(inside) / (kSamples * kSamples);
}

// Whether segment a-b meets the closed square [x, x+1] x [y, y+1] (Liang-Barsky clipping).
bool meets(Point2 a, Point2 b, int x, int y) {
  double t0 = 0, t1 = 1;
  const double d[2] = {b.x - a.x, b.y - a.y}, lo[2] = {x - a.x, y - a.y},
               hi[2] = {x + 1 - a.x, y + 1 - a.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (lo[k] > 0 || hi[k] < 0) return false;
      continue;
    }
    double ta = lo[k] / d[k], tb = hi[k] / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

int edges_meeting(const std::vector<Ring>& rings, int x, int y) {
  int n = 0;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i)
      n += meets(ring[i], ring[(i + 1) % ring.size()], x, y);
  return n;
}

// The brute force's own error in a pixel: per edge through it, at most half a sample in each of
// the 64 sample rows plus one row where the edge's kinks fall (1.5 / 64); exact where no edge
// passes. The rasteriser is exact, so this is the whole tolerance.
double tolerance(const std::vector<Ring>& rings, int x, int y) {
  return edges_meeting(rings, x, y) * 1.5 / kSamples + 1e-6;
}

// `mean_limit`: the mean error allowed, far inside the per-pixel bound; the brute force's own
// error grows with the edges through a pixel.
void expect_matches_brute_force(const std::vector<Ring>& rings, int width, int height,
                                double mean_limit = 3e-4) {
  const Coverage c = rasterize(rings, width, height, FillRule::even_odd);
  double worst_ratio = 0, sum_error = 0;
  int failures = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // A pixel no edge meets is wholly in or out: its centre says which.
      const double truth = edges_meeting(rings, x, y) == 0
                               ? crossings(rings, {x + 0.5, y + 0.5}) & 1
                               : brute_force(rings, x, y);
      const double got = c.at[y * width + x];
      const double error = std::abs(got - truth);
      sum_error += error;
      worst_ratio = std::max(worst_ratio, error / tolerance(rings, x, y));
      if (error > tolerance(rings, x, y) && ++failures <= 5)
        ADD_FAILURE() << "pixel (" << x << ", " << y << "): coverage " << got << ", brute force "
                      << truth << ", tolerance " << tolerance(rings, x, y);
    }
  EXPECT_EQ(failures, 0);
  EXPECT_LT(worst_ratio, 1.0);
  // On average far inside the bound: most pixels are exact (no edge), the others are off by
  // the brute force's own sampling.
  EXPECT_LT(sum_error / (width * height), mean_limit);
}

Ring random_polygon(std::mt19937& rng, int vertices, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Ring ring;
  for (int i = 0; i < vertices; ++i) ring.push_back({u(rng), u(rng)});
  return ring;
}

// Simple by construction: vertices at increasing angles round a centre.
Ring random_star(std::mt19937& rng, Point2 centre, int vertices, double r_min, double r_max) {
  std::uniform_real_distribution<double> radius(r_min, r_max), jitter(-0.4, 0.4);
  Ring ring;
  for (int i = 0; i < vertices; ++i) {
    const double t = 2 * std::numbers::pi * (i + jitter(rng)) / vertices;
    const double r = radius(rng);
    ring.push_back({centre.x + r * std::cos(t), centre.y + r * std::sin(t)});
  }
  return ring;
}

double shoelace(const Ring& ring) {
  double twice = 0;
  for (std::size_t i = 0; i < ring.size(); ++i)
    twice += geometry::cross(ring[i], ring[(i + 1) % ring.size()]);
  return std::abs(twice) / 2;
}

// Self-intersecting random polygons, even-odd, some vertices outside the image.
TEST(CoverageRasterizer, EveryPixelMatchesABruteForceSampleCount) {
  std::mt19937 rng(20261129);
  for (int trial = 0; trial < 6; ++trial) {
    SCOPED_TRACE("polygon " + std::to_string(trial));
    expect_matches_brute_force({random_polygon(rng, 7 + trial, -4, 36)}, 32, 32);
  }
}

TEST(CoverageRasterizer, TotalCoverageIsTheShoelaceArea) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Ring star = random_star(rng, {100, 80}, 5 + trial * 7, 10, 70);
    const Coverage c = rasterize({star}, 200, 160, FillRule::even_odd);
    EXPECT_NEAR(c.sum(), shoelace(star), 1e-6 * shoelace(star)) << "star " << trial;
    // Either orientation, either rule: the same simple polygon.
    Ring reversed(star.rbegin(), star.rend());
    EXPECT_NEAR(rasterize({reversed}, 200, 160, FillRule::nonzero).sum(), shoelace(star),
                1e-6 * shoelace(star));
  }
}

TEST(CoverageRasterizer, HolesAreCutOutWhateverTheirOrientation) {
  std::mt19937 rng(11);
  const Ring outer = random_star(rng, {20, 20}, 9, 14, 19);
  // The star holds the disc of radius 14 cos(36 degrees) = 11.3 round (20, 20); both holes lie in
  // it and apart. The round hole in either orientation.
  Ring hole;
  for (int k = 0; k < 40; ++k)
    hole.push_back({23.3 + 5 * std::cos(k * std::numbers::pi / 20),
                    23.7 + 5 * std::sin(k * std::numbers::pi / 20)});
  const Ring square_hole{{12.25, 12.5}, {16.75, 12.5}, {16.75, 16.1}, {12.25, 16.1}};
  for (bool reverse : {false, true}) {
    const Ring h = reverse ? Ring(hole.rbegin(), hole.rend()) : hole;
    const std::vector<Ring> rings{outer, h};
    const Coverage c = rasterize(rings, 40, 40, FillRule::even_odd);
    EXPECT_NEAR(c.sum(), shoelace(outer) - shoelace(hole), 1e-9 * shoelace(outer));
    expect_matches_brute_force(rings, 40, 40);
    // The hole's centre is empty, the ring between is full.
    EXPECT_EQ(c.at[23 * 40 + 23], 0.0);
  }
  // Two holes; the square one contains whole pixels and pixels cut in exactly known fractions.
  const Coverage c = rasterize({outer, hole, square_hole}, 40, 40, FillRule::even_odd);
  EXPECT_NEAR(c.sum(), shoelace(outer) - shoelace(hole) - 4.5 * 3.6, 1e-9 * shoelace(outer));
  EXPECT_EQ(c.at[13 * 40 + 13], 0.0);
  EXPECT_NEAR(c.at[13 * 40 + 12], 0.25, 1e-9);            // x 12..12.25 of the pixel is left
  EXPECT_NEAR(c.at[12 * 40 + 14], 0.5, 1e-9);             // y 12..12.5 is left
  EXPECT_NEAR(c.at[12 * 40 + 12], 1 - 0.75 * 0.5, 1e-9);  // the hole's corner
}

TEST(CoverageRasterizer, NonzeroFillsTheUnionOfOverlappingPieces) {
  // Two squares overlapping in a 3 x 4 rectangle, plus a triangle inside both: union area 2 x 64 -
  // 12 whatever the rule would make of the overlaps.
  const Ring a{{2.5, 2.5}, {10.5, 2.5}, {10.5, 10.5}, {2.5, 10.5}};
  const Ring b{{7.5, 6.5}, {15.5, 6.5}, {15.5, 14.5}, {7.5, 14.5}};
  const Ring t{{8, 7}, {10, 7}, {9, 9}};
  const Coverage u = rasterize({a, b, t}, 20, 20, FillRule::nonzero);
  EXPECT_NEAR(u.sum(), 2 * 64 - 12, 1e-9);
  for (double v : u.at) EXPECT_LE(v, 1.0);
  // Even-odd: the overlap is a hole, and the triangle inside it is filled again.
  const Coverage x = rasterize({a, b, t}, 20, 20, FillRule::even_odd);
  EXPECT_NEAR(x.sum(), 2 * 64 - 2 * 12 + 2, 1e-9);
}

// Hundreds of edges through a few pixels: rows measured on 64 sample lines (see the header), still
// within the brute force's own tolerance.
TEST(CoverageRasterizer, DenseSelfIntersectingPolygonsStayWithinTheBound) {
  std::mt19937 rng(99);
  const Ring dense = random_polygon(rng, 300, -1, 13);
  expect_matches_brute_force({dense}, 12, 12, 3e-3);
  // With a square whose left edge runs through the dense part: right of it the square's inside
  // carries on from the sampled run to the plain edges.
  const Ring square{{6.2, 0.5}, {23.5, 0.5}, {23.5, 11.5}, {6.2, 11.5}};
  expect_matches_brute_force({dense, square}, 24, 12, 3e-3);
}

// A 4,096-point series squeezed into a 100 x 20 picture (zigzags 0.024 px apart, 2 px wide): its
// stroke fills the band between y 5 and 15 and leaves the rest, in linear time.
TEST(Stroke, ADenseSeriesFillsItsBand) {
  std::vector<Point2> series;
  for (int i = 0; i < 4096; ++i) series.push_back({i * 100.0 / 4096, i % 2 == 0 ? 6.0 : 14.0});
  const Coverage c = rasterize(stroke(series, 2), 100, 20, FillRule::nonzero);
  for (int y = 0; y < 20; ++y)
    for (int x = 2; x < 98; ++x) {
      const double v = c.at[y * 100 + x];
      if (y >= 6 && y < 14) EXPECT_NEAR(v, 1.0, 1e-6) << x << ", " << y;
      if (y < 4 || y >= 16) EXPECT_EQ(v, 0.0) << x << ", " << y;
    }
}

// A horizontal edge inside a row (here A's top at y 5.5) covers nothing, but what lies between its
// ends in the rest of the row (B's bottom, y 5 to 5.25) must not see A's winding.
TEST(CoverageRasterizer, HorizontalEdgesInsideARow) {
  const Ring a{{2, 5.5}, {10, 5.5}, {10, 9}, {2, 9}};
  const Ring b{{5, 2}, {6, 2}, {6, 5.25}, {5, 5.25}};
  for (FillRule rule : {FillRule::even_odd, FillRule::nonzero}) {
    const Coverage c = rasterize({a, b}, 12, 12, rule);
    EXPECT_NEAR(c.sum(), 8 * 3.5 + 3.25, 1e-9);
    EXPECT_NEAR(c.at[5 * 12 + 5], 0.5 + 0.25, 1e-9);
    EXPECT_NEAR(c.at[5 * 12 + 3], 0.5, 1e-9);
  }
}

TEST(CoverageRasterizer, ShapesPartlyOrWhollyOutsideTheImage) {
  // A square from (-10, -10) to (5.5, 5.5): only its visible part counts.
  const Ring s{{-10, -10}, {5.5, -10}, {5.5, 5.5}, {-10, 5.5}};
  EXPECT_NEAR(rasterize({s}, 8, 8, FillRule::even_odd).sum(), 5.5 * 5.5, 1e-9);
  // Covering the whole image: every pixel full.
  const Ring big{{-1e4, -1e4}, {1e4, -1e4}, {1e4, 1e4}, {-1e4, 1e4}};
  const Coverage all = rasterize({big}, 8, 8, FillRule::even_odd);
  for (double v : all.at) EXPECT_NEAR(v, 1.0, 1e-9);
  // Wholly outside: nothing.
  const Ring away{{20, 1}, {30, 1}, {30, 5}};
  EXPECT_EQ(rasterize({away}, 8, 8, FillRule::even_odd).sum(), 0.0);
}

// A stroke is the union of its pieces: for a right-angle turn, the two bands (30 x 4 and 20 x 4
// px) less the 2 x 2 square they share inside the turn, plus the quarter disc of the round join
// outside it (its arc within 0.05 px: at most 0.05 px times the arc's length less). Both ways of
// turning, both fill rules give the same.
TEST(Stroke, ARightAngleTurnHasTheClosedFormArea) {
  const double r = 2, quarter = std::numbers::pi * r * r / 4, arc = std::numbers::pi * r / 2;
  for (const std::vector<Point2>& line : {std::vector<Point2>{{10, 10}, {40, 10}, {40, 30}},
                                          {{10, 30}, {40, 30}, {40, 10}},
                                          {{40, 30}, {40, 10}, {10, 10}}}) {
    const double area = rasterize(stroke(line, 2 * r), 50, 40, FillRule::nonzero).sum();
    EXPECT_LE(area, 30 * 4 + 20 * 4 - 4 + quarter + 1e-9);
    EXPECT_GE(area, 30 * 4 + 20 * 4 - 4 + quarter - 0.05 * arc);
  }
}

}  // namespace
}  // namespace swath::render::detail

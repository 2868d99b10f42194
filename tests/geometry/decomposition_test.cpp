#include "swath/geometry/decomposition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <stdexcept>

#include "decomposition_reference.hpp"
#include "field_shapes.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/sort_runs.hpp"

namespace swath::geometry {
namespace {

double total_area(const std::vector<Ring>& cells) {
  double a = 0;
  for (const Ring& c : cells) a += signed_area(c);
  return a;
}

// Crossings of the line through `p` at `angle_deg` with the ring (counted half-open).
int crossings(const Ring& ring, double angle_deg, double offset) {
  const double t = angle_deg * std::numbers::pi / 180;
  const Point2 normal{-std::sin(t), std::cos(t)};
  int count = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double a = dot(ring[i], normal) - offset,
                 b = dot(ring[(i + 1) % ring.size()], normal) - offset;
    if ((a < 0) != (b < 0)) ++count;
  }
  return count;
}

TEST(Boustrophedon, ConvexAndLShapeAreOneCell) {
  EXPECT_EQ(boustrophedon_cells({{{0, 0}, {10, 0}, {10, 5}, {0, 5}}}, 0).size(), 1u);
  const Ring l{{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}};
  EXPECT_EQ(boustrophedon_cells({l}, 0).size(), 1u);
  EXPECT_EQ(boustrophedon_cells({l}, 90).size(), 1u);
}

TEST(Boustrophedon, UShapeSplitsAtTheNotch) {
  // U opening upwards: base 30 x 10, arms 10 wide up to 30. Lanes across the arms: the base
  // continues into one arm, the other arm is a second cell.
  const Ring u{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}};
  const auto cells = boustrophedon_cells({u}, 0);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_DOUBLE_EQ(total_area(cells), 300 + 200 + 200);
  // Vertical lanes meet the U in one interval everywhere: one cell.
  EXPECT_EQ(boustrophedon_cells({u}, 90).size(), 1u);
}

TEST(Boustrophedon, HoleGivesTwoCells) {
  // Below, left of and above the hole as one cell; right of it the other.
  const std::vector<Ring> rings{{{0, 0}, {100, 0}, {100, 100}, {0, 100}},
                                {{40, 40}, {40, 60}, {60, 60}, {60, 40}}};
  for (double angle : {0.0, 90.0, 30.0}) {
    const auto cells = boustrophedon_cells(rings, angle);
    EXPECT_EQ(cells.size(), 2u) << angle;
    EXPECT_NEAR(total_area(cells), 10000 - 400, 1e-9) << angle;
  }
}

void expect_valid_decomposition(const Polygon& p, double angle, const std::string& what) {
  const auto cells = boustrophedon_cells(rings_of(p), angle);
  ASSERT_FALSE(cells.empty()) << what;
  EXPECT_NEAR(total_area(cells), area(p), 1e-7 * area(p)) << what;
  const double t = angle * std::numbers::pi / 180;
  const Point2 normal{-std::sin(t), std::cos(t)};
  for (const Ring& c : cells) {
    EXPECT_GT(signed_area(c), 0) << what;
    double lo = 1e300, hi = -1e300;
    for (const Point2& q : c) {
      lo = std::min(lo, dot(q, normal));
      hi = std::max(hi, dot(q, normal));
    }
    for (int k = 1; k < 20; ++k)
      EXPECT_LE(crossings(c, angle, lo + (hi - lo) * k / 20.0), 2) << what << " monotone";
  }
  // Points of the area lie in exactly one cell; points outside in none. Sampled over the area's
  // bounding box, so that a good share falls inside.
  test::Rng rng(1);
  Point2 box_lo{1e300, 1e300}, box_hi{-1e300, -1e300};
  for (const Point2& q : p.outer) {
    box_lo = {std::min(box_lo.x, q.x), std::min(box_lo.y, q.y)};
    box_hi = {std::max(box_hi.x, q.x), std::max(box_hi.y, q.y)};
  }
  std::uniform_real_distribution<double> ux(box_lo.x, box_hi.x), uy(box_lo.y, box_hi.y);
  int inside = 0;
  for (int k = 0; k < 400; ++k) {
    const Point2 q{ux(rng), uy(rng)};
    bool in_area = locate_point(q, p.outer) == Containment::inside;
    for (const Ring& h : p.holes)
      if (locate_point(q, h) != Containment::outside) in_area = false;
    int in_cells = 0;
    bool on_cell_boundary = false;
    for (const Ring& c : cells) {
      const Containment where = locate_point(q, c);
      in_cells += where == Containment::inside;
      on_cell_boundary |= where == Containment::on_boundary;
    }
    if (on_cell_boundary) continue;
    EXPECT_EQ(in_cells, in_area ? 1 : 0) << what << " at " << q.x << "," << q.y;
    inside += in_area;
  }
  EXPECT_GT(inside, 40) << what << ": too few samples inside to mean anything";
}

TEST(BoustrophedonProperty, RandomConcavePolygonsAtRandomAngles) {
  test::Rng rng(41);
  std::uniform_real_distribution<double> angle(0, 180);
  for (int k = 0; k < 150; ++k) {
    Polygon p{normalise_ring(test::random_star_polygon(rng, 4 + k % 40, 100, 500), true).ring, {}};
    expect_valid_decomposition(p, angle(rng), "star " + std::to_string(k));
    expect_valid_decomposition(p, 0.0, "star at 0 " + std::to_string(k));
  }
}

TEST(BoustrophedonProperty, CombsAndHoles) {
  test::Rng rng(43);
  std::uniform_real_distribution<double> u(0, 1);
  for (int teeth = 2; teeth < 12; ++teeth) {
    const Polygon comb{test::transformed(test::comb_polygon(teeth, 20, 200, 30), 0, -200, -100),
                       {}};
    expect_valid_decomposition(comb, 0, "comb across " + std::to_string(teeth));
    EXPECT_EQ(boustrophedon_cells(rings_of(comb), 0).size(), std::size_t(teeth))
        << "base + one tooth, the other teeth";
    EXPECT_EQ(boustrophedon_cells(rings_of(comb), 90).size(), 1u) << "lanes along the teeth";
    expect_valid_decomposition(comb, 37, "comb 37 " + std::to_string(teeth));
  }
  for (int k = 0; k < 60; ++k) {
    // 1..10 disjoint square holes on a grid inside a 1000 m square.
    Polygon p{{{-500, -500}, {500, -500}, {500, 500}, {-500, 500}}, {}};
    std::vector<int> used;
    for (int h = 0; h < 1 + k % 10; ++h) {
      const int cell = int(u(rng) * 25);
      if (std::find(used.begin(), used.end(), cell) != used.end()) continue;
      used.push_back(cell);
      const double x = -450 + 180 * (cell % 5) + 40 * u(rng),
                   y = -450 + 180 * (cell / 5) + 40 * u(rng);
      p.holes.push_back(
          normalise_ring(test::transformed({{0, 0}, {60, 0}, {60, 50}, {0, 50}}, 20 * u(rng), x, y),
                         false)
              .ring);
    }
    ASSERT_NE(classify(p).type, AreaType::self_intersecting);
    expect_valid_decomposition(p, 180 * u(rng), "holes " + std::to_string(k));
    expect_valid_decomposition(p, 0, "holes at 0 " + std::to_string(k));
  }
}

// The fast decomposition is the reference's bit for bit: the same pieces, the same cells of them
// and the same cells' rings (call it with ASSERT_NO_FATAL_FAILURE: it stops at the first
// difference).
void expect_same_decomposition(const Decomposition& fast, const Decomposition& truth) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  const auto same = [&](const Ring& a, const Ring& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (bits(a[i].x) != bits(b[i].x) || bits(a[i].y) != bits(b[i].y)) return false;
    return true;
  };
  ASSERT_EQ(fast.pieces.size(), truth.pieces.size());
  for (std::size_t i = 0; i < truth.pieces.size(); ++i)
    ASSERT_TRUE(same(fast.pieces[i], truth.pieces[i])) << "piece " << i;
  ASSERT_EQ(fast.cells, truth.cells);
  ASSERT_EQ(fast.cell_rings.size(), truth.cell_rings.size());
  for (std::size_t i = 0; i < truth.cell_rings.size(); ++i)
    ASSERT_TRUE(same(fast.cell_rings[i], truth.cell_rings[i])) << "cell " << i;
}

// The decomposition keeps its buffers and its chains' buffers between calls (the thread's): it must
// give, bit for bit, what it gave when it made them anew (the function as it was, kept in
// decomposition_reference.hpp): traced outlines (narrow arms, holes, nearly collinear vertices),
// combs (with edges along the cuts at 0 and 90 degrees), random fields with holes, at many
// directions one after another (so each call finds the buffers another area left).
TEST(BoustrophedonProperty, AsTheReferenceBitForBit) {
  test::Rng rng(5254);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t pieces = 0, cells = 0, refused = 0;
  for (int k = 0; k < 40; ++k) {
    Polygon area;
    if (k % 4 == 0) {
      area = test::traced_outline(rng);
    } else if (k % 4 == 1) {
      area.outer = test::transformed(
          test::comb_polygon(2 + k % 5, 20 + 30 * u(rng), 100 + 200 * u(rng), 30), 0, -100, -100);
    } else if (k % 4 == 2) {
      // Integer coordinates: at 0 and 90 degrees its edges lie along the cuts (equal ordinates).
      area.outer = test::comb_polygon(2 + k % 5, 20, 100 + 10 * (k % 7), 30);
    } else {
      area.outer = test::random_field_polygon(rng, 10 + std::size_t(u(rng) * 150), 300);
      for (int h = 0; h < 1 + k % 3; ++h) {
        const double x = -150 + 110.0 * h, y = -40 + 50 * u(rng);
        area.holes.push_back({{x, y}, {x + 30, y}, {x + 30, y + 30}, {x, y + 30}});
      }
    }
    const std::vector<Ring> rings = rings_of(area);
    for (int d = 0; d < 12; ++d) {
      const double angle = d < 3 ? 45.0 * d : d == 3 ? 90.0 : 180 * u(rng);
      Decomposition truth;
      try {
        truth = reference::boustrophedon_decomposition(rings, angle);
      } catch (const std::logic_error&) {  // e.g. a hole across the outline: the same answer
        EXPECT_THROW(boustrophedon_decomposition(rings, angle), std::logic_error) << k << " " << d;
        ++refused;
        continue;
      }
      SCOPED_TRACE(std::to_string(k) + " " + std::to_string(d));
      ASSERT_NO_FATAL_FAILURE(
          expect_same_decomposition(boustrophedon_decomposition(rings, angle), truth));
      pieces += truth.pieces.size();
      cells += truth.cells.size();
    }
  }
  EXPECT_GT(pieces, 2000u);
  EXPECT_GT(cells, 1000u);
  EXPECT_LT(refused, 12u);
  RecordProperty("refused", std::to_string(refused));
  RecordProperty("pieces", std::to_string(pieces));
  RecordProperty("cells", std::to_string(cells));
}

// Equal points (a vertex repeated, one outline's vertex on another ring's) are where the
// decomposition's own sort of the vertices must fall back to std::sort's order from ring order:
// the same answers as the reference, bit for bit, on traced outlines, combs and fields whose
// vertices are repeated here and there, at many directions.
TEST(BoustrophedonProperty, AsTheReferenceWithRepeatedPoints) {
  test::Rng rng(5255);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t answered = 0, refused = 0;
  for (int k = 0; k < 24; ++k) {
    Polygon area;
    if (k % 4 == 0) {
      area = test::traced_outline(rng);
    } else if (k % 4 == 1) {
      area.outer = test::comb_polygon(2 + k % 5, 20, 100 + 10 * (k % 7), 30);
    } else if (k % 4 == 2) {
      area.outer = test::random_field_polygon(rng, 10 + std::size_t(u(rng) * 150), 300);
    } else {
      // Holes in a row, each touching the next at a corner (clockwise squares, their sizes
      // random): two rings' vertices at one point, among enough others that std::sort's order
      // between them is not the rings' (no insertion sort).
      area.outer = test::random_field_polygon(rng, 60 + std::size_t(u(rng) * 100), 300);
      Point2 corner{-60 + 20 * u(rng), -60 + 20 * u(rng)};
      for (int h = 0; h < 2 + k % 3; ++h) {
        const double side = 10 + 20 * u(rng);
        area.holes.push_back({corner,
                              {corner.x, corner.y + side},
                              {corner.x + side, corner.y + side},
                              {corner.x + side, corner.y}});
        corner = {corner.x + side, corner.y + side};
      }
    }
    // Every few vertices one repeated (next to itself), some twice.
    Ring repeated;
    for (std::size_t i = 0; i < area.outer.size(); ++i) {
      repeated.push_back(area.outer[i]);
      if (u(rng) < 0.04) repeated.push_back(area.outer[i]);
      if (u(rng) < 0.01) repeated.push_back(area.outer[i]);
    }
    area.outer = repeated;
    const std::vector<Ring> rings = rings_of(area);
    for (int d = 0; d < 10; ++d) {
      const double angle = d < 3 ? 45.0 * d : d == 3 ? 90.0 : 180 * u(rng);
      Decomposition truth;
      try {
        truth = reference::boustrophedon_decomposition(rings, angle);
      } catch (const std::logic_error&) {
        EXPECT_THROW(boustrophedon_decomposition(rings, angle), std::logic_error) << k << " " << d;
        ++refused;
        continue;
      }
      SCOPED_TRACE(std::to_string(k) + " " + std::to_string(d));
      ASSERT_NO_FATAL_FAILURE(
          expect_same_decomposition(boustrophedon_decomposition(rings, angle), truth));
      ++answered;
    }
  }
  EXPECT_GT(answered, 50u);
  RecordProperty("refused", std::to_string(refused));
}

// sort_by_runs must give std::sort's order: random points in runs rising and falling (as a
// boundary's vertices and samples come), with equal ordinates, repeated points and runs of one;
// few runs (merged) and many (sorted whole). Points alike when equal, and points tagged with
// their place (equal points then differ: std::sort's own order between them must stay).
TEST(SortByRuns, GivesTheOrderOfASortOfAll) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(0, 1);
  struct Tagged {
    Point2 p;
    std::size_t tag;
  };
  const auto by_ordinate = [](Point2 p, Point2 q) {
    return p.y < q.y || (p.y == q.y && p.x < q.x);
  };
  const auto tagged_less = [&](const Tagged& a, const Tagged& b) { return by_ordinate(a.p, b.p); };
  int merged = 0, ties = 0;
  for (int k = 0; k < 400; ++k) {
    std::vector<Point2> points;
    const int runs = 1 + int(unit(rng) * (k % 2 == 0 ? 12 : 400));
    const bool distinct = k % 4 == 0;  // no two points equal: the merge stands
    for (int r = 0; r < runs; ++r) {
      const int n = int(unit(rng) * 40);
      const double y0 = std::floor(unit(rng) * 20), dy = std::floor(unit(rng) * 5 - 2) / 4;
      const double x0 = std::floor(unit(rng) * 20), dx = std::floor(unit(rng) * 5 - 2) / 4;
      for (int i = 0; i < n; ++i)
        points.push_back(
            distinct ? Point2{double(r) + i * 1e-3, y0 + r * 100 + dy * i + unit(rng) * 1e-9}
                     : Point2{x0 + dx * i, y0 + dy * i});
    }
    std::vector<Point2> truth = points;
    std::sort(truth.begin(), truth.end(), by_ordinate);
    std::vector<Point2> sorted = points;
    sort_by_runs(sorted, by_ordinate, true);
    ASSERT_EQ(sorted.size(), truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i)
      ASSERT_TRUE(sorted[i] == truth[i]) << "set " << k << " at " << i;
    std::vector<Tagged> tagged;
    for (std::size_t i = 0; i < points.size(); ++i) tagged.push_back({points[i], i});
    std::vector<Tagged> tagged_truth = tagged;
    std::sort(tagged_truth.begin(), tagged_truth.end(), tagged_less);
    sort_by_runs(tagged, tagged_less, false);
    for (std::size_t i = 0; i < tagged_truth.size(); ++i)
      ASSERT_EQ(tagged[i].tag, tagged_truth[i].tag) << "set " << k << " at " << i;
    merged += runs <= 12;
    for (std::size_t i = 0; i + 1 < truth.size(); ++i) ties += truth[i] == truth[i + 1];
  }
  EXPECT_GT(merged, 100);
  EXPECT_GT(ties, 100);  // equal points came up: the tagged sort's fallback was asked
}

}  // namespace
}  // namespace swath::geometry

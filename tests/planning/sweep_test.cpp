#include "swath/planning/sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "coverage_oracle.hpp"
#include "field_shapes.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/min_height.hpp"
#include "swath/planning/coverage.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;
using geometry::Polygon;

std::size_t fewest_lines_brute_force(double height, double spacing, double footprint) {
  for (std::size_t n = 1;; ++n)
    if ((double(n) - 1) * spacing + footprint >= height - 1e-9 * height) return n;
}

TEST(LineOffsets, CenteredUsesTheFewestLinesAndIsCentred) {
  test::Rng rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const double height = 1 + 500 * u(rng);
    const double spacing = 5 + 60 * u(rng);
    const double footprint = spacing * (1 + 2 * u(rng));
    const auto ys = line_offsets(10, 10 + height, spacing, footprint, LinePlacement::centered);
    ASSERT_EQ(ys.size(), fewest_lines_brute_force(height, spacing, footprint)) << k;
    EXPECT_NEAR(ys.front() - 10, 10 + height - ys.back(), 1e-9 * height) << "centred";
    EXPECT_LE(ys.front() - footprint / 2, 10 + 1e-9) << "bottom covered";
    EXPECT_GE(ys.back() + footprint / 2, 10 + height - 1e-9) << "top covered";
    for (std::size_t i = 1; i < ys.size(); ++i) EXPECT_NEAR(ys[i] - ys[i - 1], spacing, 1e-9);
  }
}

TEST(LineOffsets, PaperRuleAsAlgorithmTwo) {
  // Height 100, step 30: 15, 45, 75, then 75 + 30 >= 100 -> last at min(90, 100) = 90.
  EXPECT_EQ(line_offsets(0, 100, 30, 30, LinePlacement::paper),
            (std::vector<double>{15, 45, 75, 90}));
  // Height 100, step 40: 20, 60, then 60 + 40 >= 100 -> last at min(80, 100) = 80.
  EXPECT_EQ(line_offsets(0, 100, 40, 40, LinePlacement::paper), (std::vector<double>{20, 60, 80}));
  // Smaller than half a step: one line, clamped to the top.
  EXPECT_EQ(line_offsets(0, 10, 40, 40, LinePlacement::paper), (std::vector<double>{10}));
  // Height 60, step 30: the paper flies 15, 45 and 60; two lines at 15 and 45 already cover it.
  EXPECT_EQ(line_offsets(0, 60, 30, 30, LinePlacement::paper), (std::vector<double>{15, 45, 60}));
  EXPECT_EQ(line_offsets(0, 60, 30, 30, LinePlacement::centered), (std::vector<double>{15, 45}));
}

TEST(LineOffsetsProperty, CenteredNeverUsesMoreLinesThanPaper) {
  test::Rng rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int fewer = 0;
  for (int k = 0; k < 5000; ++k) {
    const double height = 500 * u(rng) + 0.1;
    const double spacing = 1 + 80 * u(rng);
    const double footprint = spacing * (1 + u(rng));
    const auto c = line_offsets(0, height, spacing, footprint, LinePlacement::centered).size();
    const auto p = line_offsets(0, height, spacing, footprint, LinePlacement::paper).size();
    EXPECT_LE(c, p) << height << ' ' << spacing << ' ' << footprint;
    fewer += c < p;
  }
  EXPECT_GT(fewer, 2500);
  RecordProperty("centered_fewer_of_5000", fewer);
}

TEST(PlanSweep, RectangleGivesFullWidthLines) {
  const Polygon rect{{{0, 0}, {200, 0}, {200, 100}, {0, 100}}, {}};
  SweepSettings s;
  s.angle_deg = 0;
  s.line_spacing_m = 25;
  s.footprint_width_m = 25;
  s.turnaround_m = 5;
  const Sweep sweep = plan_sweep(rect, s);
  ASSERT_EQ(sweep.lines.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(sweep.lines[i].start.x, -5, 1e-9);
    EXPECT_NEAR(sweep.lines[i].end.x, 205, 1e-9);
    EXPECT_NEAR(sweep.lines[i].start.y, 12.5 + 25.0 * double(i), 1e-9);
  }
  EXPECT_DOUBLE_EQ(sweep.height_m, 100);
}

TEST(PlanSweep, SegmentSpansTheWholeStripNotOnlyTheLineCrossing) {
  // Triangle with a slanted right edge: strip [0, 20] around y = 10 reaches x = 100 at y = 0.
  const Polygon tri{{{0, 0}, {100, 0}, {0, 100}}, {}};
  SweepSettings s;
  s.line_spacing_m = 20;
  s.footprint_width_m = 20;
  const Sweep sweep = plan_sweep(tri, s);
  ASSERT_EQ(sweep.lines.size(), 5u);
  EXPECT_NEAR(sweep.lines[0].end.x, 100, 1e-9);  // the line's own crossing would stop at 90
  EXPECT_NEAR(sweep.lines[4].end.x, 20, 1e-9);   // strip [80, 100] reaches x = 20 at y = 80
}

// The naive rule (segment = where the line itself crosses the area) leaves uncovered triangles at
// slanted edges; the oracle must see them, or the coverage property below proves nothing.
TEST(PlanSweep, CoverageOracleCatchesTheNaiveRule) {
  const Polygon tri{{{0, 0}, {300, 0}, {0, 300}}, {}};
  SweepSettings s;
  s.line_spacing_m = 30;
  s.footprint_width_m = 30;
  Sweep sweep = plan_sweep(tri, s);
  std::vector<SweepLine> naive;
  for (const SweepLine& l : sweep.lines)
    naive.push_back({{0, l.start.y}, {300 - l.start.y, l.start.y}});
  EXPECT_LT(test::sample_coverage(tri, naive, 30, 300).fraction(), 0.99);
  EXPECT_EQ(test::sample_coverage(tri, sweep.lines, 30, 300).fraction(), 1.0);
}

// plan_sweep() finds each edge's first strip by walking from the last edge's where the strips'
// tops ascend. It must give, bit for bit, what a search per edge gave (the function as it was,
// kept here): random fields with holes and grid rings full of horizontal edges, both segment
// rules, with and without protrusions filled, on the area's own grid and on given ordinates
// (ascending, repeated, or in any order: where a search is still made). It is also the reference
// for the protrusions' lanes: here each one's two sides are walked to on their own and all lanes
// walked to again once they are known (plan_sweep asks all sides in one walk and keeps the grid
// lanes' extents).
Sweep reference_plan_sweep(const geometry::Polygon& area, const SweepSettings& s) {
  Sweep sweep;
  sweep.angle_deg = std::fmod(std::fmod(s.angle_deg, 180.0) + 180.0, 180.0);

  // Work in a frame where the lines are horizontal. The buffers are the thread's, their capacity
  // kept: split plans sweep every piece of a decomposition at every direction (~18,000 sweeps of a
  // few vertices each at 100 vertices and 50 holes), and their allocations were a third of it.
  std::vector<geometry::Ring> rings;
  const std::size_t ring_count = geometry::ring_count(area);
  if (rings.size() < ring_count) rings.resize(ring_count);
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (std::size_t r = 0; r < ring_count; ++r) {
    geometry::Ring& ring = rings[r];
    ring.clear();
    for (const Point2& p : geometry::ring_at(area, r)) {
      ring.push_back(rotate(p, -sweep.angle_deg));
      y_min = std::min(y_min, ring.back().y);
      y_max = std::max(y_max, ring.back().y);
    }
  }
  sweep.height_m = y_max - y_min;
  std::vector<double> ys;
  if (s.ordinates.empty()) {
    ys = line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  } else {
    const auto inside = [&](double y) { return y >= y_min && y <= y_max; };
    ys.reserve(std::size_t(std::count_if(s.ordinates.begin(), s.ordinates.end(), inside)));
    for (double y : s.ordinates)
      if (inside(y)) ys.push_back(y);
    if (ys.empty()) ys.push_back((y_min + y_max) / 2);
  }

  // Strip k spans [lo, hi]: between the midpoints to its neighbours (strip rule) or the line's own
  // ordinate (inside rule). Both bounds increase with k, so an edge finds its first strip by
  // search.
  struct Strip {
    double lo, hi;
    double x_lo = std::numeric_limits<double>::infinity();
    double x_hi = -std::numeric_limits<double>::infinity();
    double y_at_x_lo = 0.0, y_at_x_hi = 0.0;  // where the extremes are reached
  };
  // Into `strips` (its capacity kept), for offsets[0, count).
  auto strips_for = [&](const double* offsets, std::size_t count, bool whole_strip,
                        std::vector<Strip>& strips) {
    strips.clear();
    for (std::size_t k = 0; k < count; ++k) {
      if (!whole_strip) {
        strips.push_back({offsets[k], offsets[k]});
      } else {
        strips.push_back({k == 0 ? y_min : (offsets[k - 1] + offsets[k]) / 2,
                          k + 1 == count ? y_max : (offsets[k] + offsets[k + 1]) / 2});
      }
    }
    // Each edge, clipped to every strip it meets, widens that strip's x extent.
    for (std::size_t r = 0; r < ring_count; ++r) {
      const geometry::Ring& ring = rings[r];
      for (std::size_t i = 0; i < ring.size(); ++i) {
        Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
        if (a.y > b.y) std::swap(a, b);
        auto x_at = [&](double y) {
          return b.y == a.y ? a.x : a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y);
        };
        auto strip = std::lower_bound(strips.begin(), strips.end(), a.y,
                                      [](const Strip& st, double y) { return st.hi < y; });
        for (; strip != strips.end() && strip->lo <= b.y; ++strip) {
          const double y0 = std::max(a.y, strip->lo);
          const double y1 = std::min(b.y, strip->hi);
          if (y0 > y1) continue;
          for (const auto& [x, y] : {std::pair{b.y == a.y ? a.x : x_at(y0), y0},
                                     std::pair{b.y == a.y ? b.x : x_at(y1), y1}}) {
            if (x < strip->x_lo) {
              strip->x_lo = x;
              strip->y_at_x_lo = y;
            }
            if (x > strip->x_hi) {
              strip->x_hi = x;
              strip->y_at_x_hi = y;
            }
          }
        }
      }
    }
  };
  std::vector<Strip> strips, whole, at;
  strips_for(ys.data(), ys.size(), s.segments == SegmentRule::strip, strips);
  if (s.segments == SegmentRule::inside && s.fill_protrusions && !ys.empty()) {
    strips_for(ys.data(), ys.size(), true, whole);
    const double slack = 0.02 * s.line_spacing_m;
    // The extreme may lie on an edge along the lanes, where the extent jumps: the lane goes just
    // off it, on the side that reaches out (never on the edge: it would run along the boundary).
    const double inset = std::min(1e-3 * s.line_spacing_m, (y_max - y_min) / 4);
    auto best_side = [&](double y, bool high) {
      const double sides[2] = {std::max(y - inset, y_min + inset),
                               std::min(y + inset, y_max - inset)};
      strips_for(sides, 2, false, at);
      return high ? (at[1].x_hi >= at[0].x_hi ? sides[1] : sides[0])
                  : (at[1].x_lo <= at[0].x_lo ? sides[1] : sides[0]);
    };
    // Only protrusions that no lane's footprint reaches already.
    auto seen = [&](double x, double y) {
      for (std::size_t j = 0; j < ys.size(); ++j)
        if (std::abs(y - ys[j]) <= s.footprint_width_m / 2 && x >= strips[j].x_lo - slack &&
            x <= strips[j].x_hi + slack)
          return true;
      return false;
    };
    std::vector<double> extra;
    for (std::size_t k = 0; k < ys.size(); ++k) {
      if (whole[k].x_hi > strips[k].x_hi + slack && !seen(whole[k].x_hi, whole[k].y_at_x_hi))
        extra.push_back(best_side(whole[k].y_at_x_hi, true));
      if (whole[k].x_lo < strips[k].x_lo - slack && !seen(whole[k].x_lo, whole[k].y_at_x_lo))
        extra.push_back(best_side(whole[k].y_at_x_lo, false));
    }
    if (!extra.empty()) {
      std::vector<double> more = ys;
      more.insert(more.end(), extra.begin(), extra.end());
      std::sort(more.begin(), more.end());
      more.erase(std::unique(more.begin(), more.end()), more.end());
      ys = std::move(more);
      strips_for(ys.data(), ys.size(), false, strips);
    }
  }
  sweep.lines.reserve(strips.size());
  for (std::size_t k = 0; k < strips.size(); ++k) {
    if (strips[k].x_lo > strips[k].x_hi) continue;
    sweep.lines.push_back({rotate({strips[k].x_lo - s.turnaround_m, ys[k]}, sweep.angle_deg),
                           rotate({strips[k].x_hi + s.turnaround_m, ys[k]}, sweep.angle_deg)});
  }
  return sweep;
}

// The fast sweep's lines are the reference's bit for bit: as many, each end the same bits (call it
// with ASSERT_NO_FATAL_FAILURE: it stops at the first difference).
void expect_same_lines(const Sweep& fast, const Sweep& truth) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  ASSERT_EQ(fast.lines.size(), truth.lines.size());
  for (std::size_t i = 0; i < truth.lines.size(); ++i)
    for (const auto& [p, q] : {std::pair{fast.lines[i].start, truth.lines[i].start},
                               std::pair{fast.lines[i].end, truth.lines[i].end}}) {
      ASSERT_EQ(bits(p.x), bits(q.x)) << "line " << i;
      ASSERT_EQ(bits(p.y), bits(q.y)) << "line " << i;
    }
}

TEST(SweepProperty, StripsWalkedToAsSearchedBitForBit) {
  test::Rng rng(5253);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  std::size_t lines = 0;
  for (int k = 0; k < 300; ++k) {
    Polygon area;
    if (k % 4 == 3) {
      area.outer = test::random_grid_ring(rng, 20, 10);  // coordinates 0 to 9
    } else {
      area.outer = test::random_field_polygon(rng, 10 + std::size_t(u(rng) * 200), 300);
      for (int h = 0; h < k % 3; ++h) {
        const double x = -150 + 120.0 * h, y = -40 + 50 * u(rng);
        area.holes.push_back({{x, y}, {x, y + 30}, {x + 40, y + 30}, {x + 40, y}});
      }
    }
    SweepSettings s;
    // Grid rings at 0 degrees, 1 or 2 m apart: vertices and horizontal edges on the ordinates.
    const bool grid = k % 4 == 3;
    s.angle_deg = grid || k % 5 == 0 ? 0.0 : 180 * u(rng);
    s.line_spacing_m = grid ? 1.0 + (k / 4) % 2 : 5 + 40 * u(rng);
    s.footprint_width_m = s.line_spacing_m * (1 + u(rng));
    s.turnaround_m = k % 2 ? 0.0 : 10 * u(rng);
    s.placement = k % 3 ? LinePlacement::centered : LinePlacement::paper;
    s.segments = k % 2 ? SegmentRule::inside : SegmentRule::strip;
    s.fill_protrusions = k % 4 != 1;
    if (k % 3 == 1) {  // given ordinates: a grid, some repeated, shuffled every fifth time
      for (double y = grid ? -2 : -400; y < 400; y += s.line_spacing_m) s.ordinates.push_back(y);
      for (int r = 0; r < 5; ++r) s.ordinates.push_back(s.ordinates[std::size_t(u(rng) * 20)]);
      std::sort(s.ordinates.begin(), s.ordinates.end());
      if (k % 5 == 0) std::shuffle(s.ordinates.begin(), s.ordinates.end(), rng);
    }
    const Sweep fast = plan_sweep(area, s), truth = reference_plan_sweep(area, s);
    ASSERT_EQ(bits(fast.angle_deg), bits(truth.angle_deg)) << k;
    ASSERT_EQ(bits(fast.height_m), bits(truth.height_m)) << k;
    ASSERT_NO_FATAL_FAILURE(expect_same_lines(fast, truth)) << "area " << k;
    lines += truth.lines.size();
  }
  EXPECT_GT(lines, 3000u);
}

// An edge within the last edge's strip, meeting no point strip, widens that strip without the
// walk to it: the same extents, bit for bit, as the reference where edges end exactly on the
// strips' bounds and on the lanes (integer rings, lanes 2 m apart on even or odd ordinates, so
// the whole strips' bounds fall on vertices too; holes, so that a ring's first edge lies anywhere),
// whole strips alone (strip rule), with their lanes' point strips in the same walk (protrusions
// filled) and point strips alone.
TEST(SweepProperty, EdgesEndingOnStripBoundsBitForBit) {
  test::Rng rng(5257);
  std::size_t lines = 0, on_bounds = 0;
  for (int k = 0; k < 900; ++k) {
    Polygon area;
    area.outer = test::random_grid_ring(rng, 4 + std::size_t(k % 40), 12);
    // Holes: a ring's first edge lies wherever it may, not where the last ring's ended.
    for (int h = 0; h < (k / 3) % 3; ++h)
      area.holes.push_back(test::random_grid_ring(rng, 3 + std::size_t(k % 7), 12));
    SweepSettings s;
    s.angle_deg = 0.0;
    s.line_spacing_m = k % 4 < 2 ? 2.0 : 4.0;
    s.footprint_width_m = s.line_spacing_m * (k % 2 ? 1.0 : 1.5);
    s.segments = k % 3 == 0 ? SegmentRule::strip : SegmentRule::inside;
    s.fill_protrusions = k % 3 == 1;
    for (double y = -4 + (k / 2) % 4; y < 16; y += s.line_spacing_m) s.ordinates.push_back(y);
    const Sweep fast = plan_sweep(area, s), truth = reference_plan_sweep(area, s);
    ASSERT_NO_FATAL_FAILURE(expect_same_lines(fast, truth)) << "area " << k;
    lines += truth.lines.size();
    for (std::size_t i = 0; i + 1 < s.ordinates.size(); ++i)
      for (const geometry::Ring& ring : geometry::rings_of(area))
        for (const Point2& v : ring) on_bounds += v.y == (s.ordinates[i] + s.ordinates[i + 1]) / 2;
  }
  EXPECT_GT(lines, 3000u);
  EXPECT_GT(on_bounds, 3000u);
  RecordProperty("lines", std::to_string(lines));
  RecordProperty("vertices_on_bounds", std::to_string(on_bounds));
}

// The split's own use: every piece of the boustrophedon decomposition of traced outlines (narrow
// arms, holes, nearly collinear vertices a few metres apart) at many directions, swept on the
// area's grid with protrusions filled. Many pieces get protrusion lanes (off the grid): their sides
// asked in one walk must choose and extend the lanes as the reference's walks two by two do.
TEST(SweepProperty, TracedPiecesAsTheReferenceBitForBit) {
  test::Rng rng(5252);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  std::size_t pieces = 0, off_grid = 0;
  for (int k = 0; k < 12; ++k) {
    const Polygon area = test::traced_outline(rng);
    const std::vector<geometry::Ring> rings = geometry::rings_of(area);
    for (int d = 0; d < 9; ++d) {
      SweepSettings s;
      s.angle_deg = d == 0 ? 0.0 : 180 * u(rng);
      s.line_spacing_m = 15 + 40 * u(rng);
      s.footprint_width_m = s.line_spacing_m * (1 + 0.5 * u(rng));
      s.turnaround_m = d % 2 ? 0.0 : 5 * u(rng);
      s.placement = d % 3 ? LinePlacement::centered : LinePlacement::paper;
      s.segments = SegmentRule::inside;
      s.fill_protrusions = true;
      double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
      for (const geometry::Ring& ring : rings)
        for (const Point2& p : ring) {
          y_min = std::min(y_min, rotate(p, -s.angle_deg).y);
          y_max = std::max(y_max, rotate(p, -s.angle_deg).y);
        }
      s.ordinates = line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
      for (const geometry::Ring& piece :
           geometry::boustrophedon_decomposition(rings, s.angle_deg).pieces) {
        if (piece.empty()) continue;
        const Polygon one{piece, {}};
        const Sweep fast = plan_sweep(one, s), truth = reference_plan_sweep(one, s);
        ASSERT_EQ(bits(fast.height_m), bits(truth.height_m)) << k << " " << d;
        ASSERT_NO_FATAL_FAILURE(expect_same_lines(fast, truth)) << k << " " << d << " " << pieces;
        for (std::size_t i = 0; i < truth.lines.size(); ++i) {
          const double y = rotate(truth.lines[i].start, -s.angle_deg).y;
          off_grid += std::none_of(s.ordinates.begin(), s.ordinates.end(),
                                   [&](double g) { return std::abs(g - y) < 1e-6; });
        }
        ++pieces;
      }
    }
  }
  EXPECT_GT(pieces, 500u);
  EXPECT_GT(off_grid, 300u);  // protrusion lanes: the batched sides are exercised
  RecordProperty("pieces", std::to_string(pieces));
  RecordProperty("off_grid_lanes", std::to_string(off_grid));
}

// Point strips (the inside rule's lanes, a reach's sides) are walked in blocks of edges, a block
// whose ordinates hold no lane's passed over: the same lanes bit for bit as the reference on small
// rings (fewer edges than a block, not a multiple of it), with lanes through vertices exactly (the
// ends of a block's range), integer grids with edges along the lanes, and holes.
TEST(SweepProperty, PointStripsWalkedInBlocksBitForBit) {
  test::Rng rng(5256);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t lines = 0, through_vertices = 0;
  for (int k = 0; k < 240; ++k) {
    Polygon area;
    const bool grid = k % 3 == 0;
    if (grid) {
      area.outer = test::random_grid_ring(rng, 3 + std::size_t(k % 20), 10);
    } else {
      area.outer =
          test::random_field_polygon(rng, 3 + std::size_t(u(rng) * (k % 2 ? 12 : 60)), 300);
      if (k % 3 == 2) area.holes.push_back({{-20, -20}, {-20, 20}, {20, 20}, {20, -20}});
    }
    SweepSettings s;
    // Whole degrees: the lanes' frame is rotate()'s at -angle_deg, so a vertex's ordinate there is
    // known exactly.
    s.angle_deg = grid ? 0.0 : double((k * 37) % 180);
    s.line_spacing_m = grid ? 1.0 : 5 + 40 * u(rng);
    s.footprint_width_m = s.line_spacing_m * (1 + u(rng));
    s.segments = SegmentRule::inside;
    s.fill_protrusions = k % 4 >= 2;
    if (k % 2 == 0) {  // lanes through every vertex, and a grid beside them
      for (const geometry::Ring* ring :
           {&area.outer, area.holes.empty() ? nullptr : &area.holes[0]})
        if (ring)
          for (const Point2& p : *ring) s.ordinates.push_back(rotate(p, -s.angle_deg).y);
      for (double y = -400; y < 400; y += s.line_spacing_m) s.ordinates.push_back(y);
      std::sort(s.ordinates.begin(), s.ordinates.end());
    }
    const Sweep fast = plan_sweep(area, s), truth = reference_plan_sweep(area, s);
    ASSERT_NO_FATAL_FAILURE(expect_same_lines(fast, truth)) << "area " << k;
    lines += truth.lines.size();
    for (const SweepLine& l : truth.lines)
      for (const Point2& v : area.outer)
        through_vertices += rotate(l.start, -s.angle_deg).y == rotate(v, -s.angle_deg).y;
  }
  EXPECT_GT(lines, 3000u);
  EXPECT_GT(through_vertices, 500u);
}

TEST(SweepProperty, FootprintsCoverRandomConvexPolygonsAtRandomAnglesSpacingsAndPlacements) {
  test::Rng rng(2718);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst_sampled = 1.0, worst_measured = 1.0;
  for (int k = 0; k < 120; ++k) {
    const Polygon area{
        test::random_convex_polygon(rng, 3 + k % 25, 100 + 400 * u(rng), 40 + 300 * u(rng)), {}};
    SweepSettings s;
    s.angle_deg = 180 * u(rng);
    s.line_spacing_m = 8 + 60 * u(rng);
    s.footprint_width_m = s.line_spacing_m * (1 + (k % 3 == 0 ? 0.0 : u(rng)));
    s.placement = k % 2 ? LinePlacement::paper : LinePlacement::centered;
    const Sweep sweep = plan_sweep(area, s);
    const test::SampledCoverage sampled =
        test::sample_coverage(area, sweep.lines, s.footprint_width_m, 250);
    EXPECT_GE(sampled.fraction(), 0.9999) << k;
    const CoverageMeasure measured =
        measure_coverage(area, sweep.lines, sweep.angle_deg, s.footprint_width_m);
    EXPECT_GE(measured.covered_fraction, 0.9999) << k;
    EXPECT_NEAR(measured.area_m2, geometry::area(area), 1e-9 * geometry::area(area)) << k;
    worst_sampled = std::min(worst_sampled, sampled.fraction());
    worst_measured = std::min(worst_measured, measured.covered_fraction);
  }
  RecordProperty("worst_sampled_coverage", std::to_string(worst_sampled));
  RecordProperty("worst_measured_coverage", std::to_string(worst_measured));
}

// measure_coverage() as it was before it kept its active edges in order and its merged swath
// between band changes: the reference its answers must equal bit for bit.
CoverageMeasure reference_measure_coverage(const Polygon& area, const std::vector<SweepLine>& lines,
                                           double angle_deg, double footprint_width_m, int rows) {
  using Interval = std::pair<double, double>;
  struct Edge {
    Point2 lo, hi;
  };
  auto merge = [](std::vector<Interval>& v) {
    std::sort(v.begin(), v.end());
    std::size_t k = 0;
    for (const Interval& i : v) {
      if (k > 0 && i.first <= v[k - 1].second) {
        v[k - 1].second = std::max(v[k - 1].second, i.second);
      } else {
        v[k++] = i;
      }
    }
    v.resize(k);
  };
  auto length = [](const std::vector<Interval>& v) {
    double s = 0;
    for (const Interval& i : v) s += i.second - i.first;
    return s;
  };
  auto overlap = [](const std::vector<Interval>& a, const std::vector<Interval>& b) {
    double s = 0;
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
      s += std::max(0.0, std::min(a[i].second, b[j].second) - std::max(a[i].first, b[j].first));
      if (a[i].second < b[j].second) {
        ++i;
      } else {
        ++j;
      }
    }
    return s;
  };
  std::vector<Edge> edges;
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (std::size_t r = 0; r < geometry::ring_count(area); ++r) {
    const geometry::Ring& ring = geometry::ring_at(area, r);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Point2 a = rotate(ring[i], -angle_deg), b = rotate(ring[(i + 1) % ring.size()], -angle_deg);
      if (a.y > b.y) std::swap(a, b);
      if (a.y == b.y) continue;
      edges.push_back({a, b});
      y_min = std::min(y_min, a.y);
      y_max = std::max(y_max, b.y);
    }
  }
  struct Band {
    double y0, y1, x0, x1;
    double y;
  };
  std::vector<Band> bands;
  for (const SweepLine& l : lines) {
    const Point2 a = rotate(l.start, -angle_deg), b = rotate(l.end, -angle_deg);
    const double y = (a.y + b.y) / 2;
    bands.push_back({y - footprint_width_m / 2, y + footprint_width_m / 2, std::min(a.x, b.x),
                     std::max(a.x, b.x), y});
    y_min = std::min(y_min, y - footprint_width_m / 2);
    y_max = std::max(y_max, y + footprint_width_m / 2);
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo.y < b.lo.y; });
  std::sort(bands.begin(), bands.end(), [](const Band& a, const Band& b) { return a.y0 < b.y0; });
  std::vector<double> events;
  for (const Edge& e : edges) {
    events.push_back(e.lo.y);
    events.push_back(e.hi.y);
  }
  for (const Band& b : bands) {
    events.push_back(b.y0);
    events.push_back(b.y1);
  }
  std::sort(events.begin(), events.end());
  events.erase(std::unique(events.begin(), events.end()), events.end());
  struct Sample {
    double y, weight;
    const Band* line;
  };
  std::vector<Sample> samples;
  const double total = y_max - y_min;
  for (std::size_t k = 0; k + 1 < events.size(); ++k) {
    const double h = events[k + 1] - events[k];
    if (h <= 0) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(rows * h / total)));
    for (int i = 0; i < n; ++i) samples.push_back({events[k] + (i + 0.5) * h / n, h / n, nullptr});
  }
  for (const Band& b : bands) samples.push_back({b.y, 0.0, &b});
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.y < b.y; });
  CoverageMeasure m;
  std::vector<const Edge*> active_edges;
  std::vector<const Band*> active_bands;
  std::size_t next_edge = 0, next_band = 0;
  std::vector<double> xs;
  std::vector<Interval> inside, swath;
  for (const Sample& sample : samples) {
    const double y = sample.y;
    while (next_edge < edges.size() && edges[next_edge].lo.y <= y)
      active_edges.push_back(&edges[next_edge++]);
    while (next_band < bands.size() && bands[next_band].y0 <= y)
      active_bands.push_back(&bands[next_band++]);
    std::erase_if(active_edges, [y](const Edge* e) { return e->hi.y <= y; });
    std::erase_if(active_bands, [y](const Band* b) { return b->y1 < y; });
    xs.clear();
    for (const Edge* e : active_edges)
      if (e->lo.y <= y && y < e->hi.y)
        xs.push_back(e->lo.x + (e->hi.x - e->lo.x) * (y - e->lo.y) / (e->hi.y - e->lo.y));
    std::sort(xs.begin(), xs.end());
    inside.clear();
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) inside.push_back({xs[i], xs[i + 1]});
    if (sample.line != nullptr) {
      const double line_length = sample.line->x1 - sample.line->x0;
      m.line_length_m += line_length;
      m.line_length_outside_m +=
          line_length - overlap(inside, {{sample.line->x0, sample.line->x1}});
      continue;
    }
    swath.clear();
    for (const Band* b : active_bands) swath.push_back({b->x0, b->x1});
    merge(swath);
    m.area_m2 += length(inside) * sample.weight;
    m.swath_area_m2 += length(swath) * sample.weight;
    m.covered_area_m2 += overlap(inside, swath) * sample.weight;
  }
  m.covered_fraction = m.area_m2 > 0 ? m.covered_area_m2 / m.area_m2 : 0.0;
  m.outside_fraction =
      m.swath_area_m2 > 0 ? (m.swath_area_m2 - m.covered_area_m2) / m.swath_area_m2 : 0.0;
  return m;
}

std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

// Bit for bit the reference's answers, on field-like and star-shaped areas (some with a hole),
// the sweep's own lines with some dropped (bands joining and leaving), lines past the area's
// ends, pieces of one lane (equal ordinates: the samples sorted by std::sort) or none (merged),
// and coarse to fine rows.
TEST(Coverage, MeasureEqualsTheReferenceBitForBit) {
  test::Rng rng(52);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 150; ++k) {
    Polygon area{k % 2 ? test::random_field_polygon(rng, 20 + k * 4, 300)
                       : test::random_star_polygon(rng, 5 + k, 80, 300),
                 {}};
    if (k % 3 == 0) {
      geometry::Ring hole = test::random_star_polygon(rng, 6 + k % 10, 10, 40);
      std::reverse(hole.begin(), hole.end());
      area.holes.push_back(hole);
    }
    SweepSettings s;
    s.angle_deg = 180 * u(rng);
    s.line_spacing_m = 10 + 40 * u(rng);
    s.footprint_width_m = s.line_spacing_m * (1 + 0.5 * u(rng));
    std::vector<SweepLine> lines;
    for (const SweepLine& l : plan_sweep(area, s).lines) {
      if (u(rng) < 0.15) continue;       // a gap in the swath
      if (k % 4 != 0 && u(rng) < 0.2) {  // the lane in two pieces, the second past the end
        const Point2 mid = (l.start + l.end) * 0.5, past = l.end + (l.end - l.start) * 0.1;
        lines.push_back({l.start, mid});
        lines.push_back({mid, past});
      } else {
        lines.push_back(l);
      }
    }
    for (const int rows : {16, 1024, 4096}) {
      const CoverageMeasure a =
          measure_coverage(area, lines, s.angle_deg, s.footprint_width_m, rows);
      const CoverageMeasure b =
          reference_measure_coverage(area, lines, s.angle_deg, s.footprint_width_m, rows);
      ASSERT_EQ(bits(a.area_m2), bits(b.area_m2)) << k << " rows " << rows;
      ASSERT_EQ(bits(a.covered_area_m2), bits(b.covered_area_m2)) << k << " rows " << rows;
      ASSERT_EQ(bits(a.swath_area_m2), bits(b.swath_area_m2)) << k << " rows " << rows;
      ASSERT_EQ(bits(a.covered_fraction), bits(b.covered_fraction)) << k << " rows " << rows;
      ASSERT_EQ(bits(a.outside_fraction), bits(b.outside_fraction)) << k << " rows " << rows;
      ASSERT_EQ(bits(a.line_length_m), bits(b.line_length_m)) << k << " rows " << rows;
      ASSERT_EQ(bits(a.line_length_outside_m), bits(b.line_length_outside_m))
          << k << " rows " << rows;
    }
  }
}

TEST(Coverage, MeasureAgreesWithTheOracleOnPartialCoverage) {
  // Half the lines dropped: both methods must report the same partial coverage.
  test::Rng rng(9);
  for (int k = 0; k < 20; ++k) {
    const Polygon area{test::random_convex_polygon(rng, 8, 300, 200), {}};
    SweepSettings s;
    s.angle_deg = 17.0 * k;
    s.line_spacing_m = 30;
    s.footprint_width_m = 30;
    Sweep sweep = plan_sweep(area, s);
    std::vector<SweepLine> half;
    for (std::size_t i = 0; i < sweep.lines.size(); i += 2) half.push_back(sweep.lines[i]);
    const double sampled = test::sample_coverage(area, half, 30, 400).fraction();
    const double measured = measure_coverage(area, half, sweep.angle_deg, 30).covered_fraction;
    EXPECT_NEAR(measured, sampled, 0.01) << k;
    EXPECT_LT(measured, 0.75);
  }
}

TEST(Coverage, OutsideFractionsOfASquareSweptWithOverhang) {
  // 100 x 100 square, 2 lines at y = 25, 75 with 60 m footprints, lines 10 m past both sides.
  const Polygon square{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {}};
  const std::vector<SweepLine> lines{{{-10, 25}, {110, 25}}, {{110, 75}, {-10, 75}}};
  const CoverageMeasure m = measure_coverage(square, lines, 0.0, 60);
  EXPECT_NEAR(m.covered_fraction, 1.0, 1e-9);
  EXPECT_NEAR(m.swath_area_m2, 120.0 * 110, 1e-6);  // y from -5 to 105
  EXPECT_NEAR(m.outside_fraction, (13200.0 - 10000) / 13200, 1e-12);
  EXPECT_NEAR(m.area_m2, 10000.0, 1e-9);
  EXPECT_NEAR(m.line_length_outside_m, 40.0, 1e-9);
  // A hole on a line's path counts as outside: 20 m beyond the sides plus 20 m over the hole.
  const Polygon holed{square.outer, {{{40, 40}, {40, 60}, {60, 60}, {60, 40}}}};
  const CoverageMeasure h = measure_coverage(holed, {{{-10, 50}, {110, 50}}}, 0.0, 10);
  EXPECT_NEAR(h.line_length_outside_m, 40.0, 1e-9);
  EXPECT_NEAR(h.line_length_m, 120.0, 1e-9);
}

TEST(OrderLines, ZigzagsFromTheRequestedCorner) {
  const Polygon rect{{{0, 0}, {200, 0}, {200, 100}, {0, 100}}, {}};
  SweepSettings s;
  s.line_spacing_m = 25;
  s.footprint_width_m = 25;
  const Sweep sweep = plan_sweep(rect, s);
  const auto sw = order_lines(sweep, StartCorner::sw);
  EXPECT_EQ(sw.front().start, (Point2{0, 12.5}));
  for (std::size_t i = 0; i + 1 < sw.size(); ++i) {
    // Alternating: each line starts at the end side of the previous one.
    EXPECT_NEAR(sw[i + 1].start.x, sw[i].end.x, 1e-9);
    EXPECT_NEAR(sw[i + 1].start.y - sw[i].end.y, 25, 1e-9);
  }
  EXPECT_EQ(order_lines(sweep, StartCorner::ne).front().start, (Point2{200, 87.5}));
  EXPECT_EQ(order_lines(sweep, StartCorner::se).front().start, (Point2{200, 12.5}));
  EXPECT_EQ(order_lines(sweep, StartCorner::nw).front().start, (Point2{0, 87.5}));
  // nearest_home: no other start corner gives shorter home legs, for homes all around the field.
  for (const Point2 home : {Point2{250, 150}, Point2{-80, 20}, Point2{90, -300}, Point2{100, 50}}) {
    const auto legs = [&](const std::vector<SweepLine>& v) {
      return geometry::distance(home, v.front().start) + geometry::distance(v.back().end, home);
    };
    const double best = legs(order_lines(sweep, StartCorner::nearest_home, home));
    for (StartCorner c : {StartCorner::sw, StartCorner::se, StartCorner::nw, StartCorner::ne})
      EXPECT_LE(best, legs(order_lines(sweep, c)) + 1e-9);
  }
}

TEST(LineWaypoints, EvenlySpacedWithEnds) {
  const auto pts = line_waypoints({{0, 0}, {100, 0}}, 30.0);
  ASSERT_EQ(pts.size(), 5u);  // 4 pieces of 25 m
  EXPECT_NEAR(pts[1].x, 25, 1e-12);
  EXPECT_EQ(pts.back(), (Point2{100, 0}));
  EXPECT_EQ(line_waypoints({{0, 0}, {100, 0}}, std::nullopt).size(), 2u);
}

}  // namespace
}  // namespace swath::planning

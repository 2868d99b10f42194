// LaneScan::at(y) looks only at the edges of y's bucket. It must answer exactly what the crossing
// rule answers over every edge: checked against that rule on random areas with holes (fixed
// seeds), integer grids full of horizontal and collinear edges, at directions along the edges,
// for ordinates through vertices, at the area's bottom and top, between and beyond; and at(ys),
// every ordinate at once, row by row the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "lane_scan.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::planning::detail {
namespace {

// The crossing rule over every edge: the truth.
std::vector<Span> all_edges_at(const LaneScan& scan, double y) {
  std::vector<double> xs;
  for (const auto& [a, b] : scan.edges())
    if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
  std::sort(xs.begin(), xs.end());
  std::vector<Span> out;
  for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
    if (xs[i + 1] - xs[i] > 1e-6) out.push_back({xs[i], xs[i + 1]});
  return out;
}

std::vector<Ring> scan_test_area(test::Rng& rng, int k) {
  if (k % 4 == 3) return {test::random_grid_ring(rng, 40, 12), test::random_grid_ring(rng, 12, 12)};
  std::vector<Ring> rings{test::random_field_polygon(rng, std::size_t(20) << (k % 4) * 3, 500)};
  for (int h = 0; h < 5 * (k % 3); ++h) {  // rectangles: horizontal edges at shared ordinates
    const double x = -300 + 75.0 * (h % 8), y = -300 + 75.0 * (h / 8);
    rings.push_back({{x, y}, {x, y + 20}, {x + 25, y + 20}, {x + 25, y}});
  }
  return rings;
}

TEST(LaneScan, BucketsAnswerAsEveryEdge) {
  test::Rng rng(2024);
  std::size_t spans = 0;
  for (int k = 0; k < 16; ++k) {
    const std::vector<Ring> rings = scan_test_area(rng, k);
    std::uniform_real_distribution<double> any_angle(0, 180);
    for (const double angle : {0.0, 90.0, 30.0, any_angle(rng)}) {
      const LaneScan scan(rings, angle);
      std::vector<double> ys{scan.y_min, scan.y_max, scan.y_min - 1, scan.y_max + 1,
                             (scan.y_min + scan.y_max) / 2};
      for (const auto& [a, b] : scan.edges()) {  // through every vertex, and a hair either side
        ys.push_back(a.y);
        ys.push_back(std::nextafter(a.y, -1e300));
        ys.push_back(std::nextafter(a.y, 1e300));
      }
      std::uniform_real_distribution<double> inside(scan.y_min, scan.y_max);
      for (int q = 0; q < 500; ++q) ys.push_back(inside(rng));
      for (const double y : ys) {
        const std::vector<Span> fast = scan.at(y), truth = all_edges_at(scan, y);
        ASSERT_EQ(fast.size(), truth.size()) << "area " << k << " angle " << angle << " y " << y;
        for (std::size_t i = 0; i < fast.size(); ++i) {
          ASSERT_EQ(fast[i].x0, truth[i].x0);
          ASSERT_EQ(fast[i].x1, truth[i].x1);
        }
        spans += truth.size();
      }
      // at() for every ordinate at once (increasing, repeats kept): the same spans, row by row.
      std::sort(ys.begin(), ys.end());
      const SpanRows rows = scan.at(ys);
      ASSERT_EQ(rows.size(), ys.size());
      for (std::size_t r = 0; r < ys.size(); ++r) {
        const std::vector<Span> truth = all_edges_at(scan, ys[r]);
        ASSERT_EQ(rows[r].size(), truth.size())
            << "area " << k << " angle " << angle << " y " << ys[r];
        for (std::size_t i = 0; i < truth.size(); ++i) {
          ASSERT_EQ(rows[r][i].x0, truth[i].x0);
          ASSERT_EQ(rows[r][i].x1, truth[i].x1);
        }
      }
    }
  }
  EXPECT_GT(spans, 50000u);  // the queries mostly cut the area
}

// SampleRows (lane_runs' samples by row) must find exactly the points a walk over every point
// finds: random points, most on shared rows (as the inside's samples), some on rows of their own
// (as the boundary's), abscissae repeated, sorted as lane_runs sorts them; boxes random and with
// edges exactly on points' coordinates, empty, and beyond every point; and runs_in(), long rows as
// runs, the same points; and any_order_in(), the points off long rows by bands, the same points.
TEST(SampleRows, BoxesFindWhatAWalkOverEveryPointFinds) {
  test::Rng rng(1818);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t found = 0;
  for (int k = 0; k < 40; ++k) {
    std::vector<Point2> points;
    const int rows = 1 + int(unit(rng) * 30);
    for (int i = 0, n = int(unit(rng) * 2000); i < n; ++i) {
      const double y = unit(rng) < 0.8 ? std::floor(unit(rng) * rows) * 2.5 : unit(rng) * 75;
      const double x = unit(rng) < 0.2 ? std::floor(unit(rng) * 10) : unit(rng) * 100 - 20;
      points.push_back({x, y});
    }
    std::sort(points.begin(), points.end(),
              [](Point2 p, Point2 q) { return p.y < q.y || (p.y == q.y && p.x < q.x); });
    const SampleRows index(points);
    // Bands for any_order_in(): thinner than the rows, about a box's height, taller than all.
    const double block_m = k % 3 == 0 ? 0.7 : k % 3 == 1 ? 9.0 : 500.0;
    const SampleRows banded(points, block_m);
    for (int q = 0; q < 200; ++q) {
      auto pick = [&](bool along_x) {
        if (!points.empty() && unit(rng) < 0.3) {
          const Point2 p = points[std::size_t(unit(rng) * double(points.size()))];
          return along_x ? p.x : p.y;
        }
        return unit(rng) * 120 - 30;
      };
      double y0 = pick(false), y1 = pick(false), x0 = pick(true), x1 = pick(true);
      if (unit(rng) < 0.9) {  // mostly proper boxes; the rest may be empty
        if (y1 < y0) std::swap(y0, y1);
        if (x1 < x0) std::swap(x0, x1);
      }
      std::vector<std::size_t> walk, searched;
      for (std::size_t i = 0; i < points.size(); ++i)
        if (points[i].y >= y0 && points[i].y <= y1 && points[i].x >= x0 && points[i].x <= x1)
          walk.push_back(i);
      index.each_in(y0, y1, x0, x1, [&](std::size_t i) { searched.push_back(i); });
      ASSERT_EQ(searched, walk) << "set " << k << ", box " << q;
      // runs_in(): the same points, runs (never empty, each on one row) and single points
      // together in increasing order; counted by +1/-1 at the runs' ends as SeenCount does.
      std::vector<std::size_t> by_runs;
      std::vector<int> steps(points.size() + 1, 0), counted(points.size(), 0);
      index.runs_in(
          y0, y1, x0, x1,
          [&](std::size_t first, std::size_t last) {
            ASSERT_LT(first, last);
            ASSERT_EQ(points[first].y, points[last - 1].y);
            for (std::size_t i = first; i < last; ++i) by_runs.push_back(i);
            ++steps[first];
            --steps[last];
          },
          [&](std::size_t i) {
            by_runs.push_back(i);
            ++counted[i];
          });
      ASSERT_EQ(by_runs, walk) << "set " << k << ", box " << q << " (runs)";
      // any_order_in(), by bands: the same points, each once, in some order.
      std::vector<std::size_t> any;
      banded.any_order_in(
          y0, y1, x0, x1,
          [&](std::size_t first, std::size_t last) {
            ASSERT_LT(first, last);
            for (std::size_t i = first; i < last; ++i) any.push_back(i);
          },
          [&](std::size_t i) { any.push_back(i); });
      std::sort(any.begin(), any.end());
      ASSERT_EQ(any, walk) << "set " << k << ", box " << q << " (bands of " << block_m << " m)";
      int running = 0;
      for (std::size_t i = 0; i < points.size(); ++i) {
        running += steps[i];
        const bool in_walk = std::binary_search(walk.begin(), walk.end(), i);
        ASSERT_EQ(counted[i] + running, in_walk ? 1 : 0) << "set " << k << ", point " << i;
      }
      found += walk.size();
    }
  }
  EXPECT_GT(found, 10000u);  // the boxes mostly hold points
}

// coverage_samples() writes the boundary's and the rows' samples in place, placing whole rows at
// once where no boundary sample lies on them. It must give, bit for bit, what the plain merge gave
// (kept here: every inside sample compared with the next boundary one): random fields with holes
// at random directions, and integer grids at 0 degrees with spacings whose sample rows fall on
// their vertices and horizontal edges (boundary samples on the rows).
void merged_samples(const LaneScan& scan, double spacing_m, std::vector<Point2>& samples) {
  double perimeter = 0;
  for (const auto& [a, b] : scan.edges()) perimeter += geometry::distance(a, b);
  double step = spacing_m;
  const double height = scan.y_max - scan.y_min;
  while (perimeter / (step / 8) + height / (step / 4) * (perimeter / 2) / (step / 4) > 2e5 &&
         step < 1e6 * spacing_m)
    step *= 1.5;
  std::vector<Point2> boundary;
  for (const auto& [a, b] : scan.edges()) {
    const int n = std::max(1, int(std::ceil(geometry::distance(a, b) / (step / 8))));
    for (int i = 0; i < n; ++i) boundary.push_back(a + (b - a) * (double(i) / n));
  }
  const auto by_ordinate = [](Point2 p, Point2 q) {
    return p.y < q.y || (p.y == q.y && p.x < q.x);
  };
  std::sort(boundary.begin(), boundary.end(), by_ordinate);
  std::vector<double> rows;
  for (double y = scan.y_min + step / 8; y < scan.y_max; y += step / 4) rows.push_back(y);
  samples.clear();
  std::size_t next = 0;
  bool in_order = true;
  for (const double y : rows)
    for (const Span& in : scan.at(y)) {
      const int n = std::max(1, int(std::ceil((in.x1 - in.x0) / (step / 4))));
      for (int i = 0; i < n; ++i) {
        const Point2 p{in.x0 + (in.x1 - in.x0) * (i + 0.5) / n, y};
        while (next < boundary.size() && !by_ordinate(p, boundary[next]))
          samples.push_back(boundary[next++]);
        in_order = in_order && (samples.empty() || !by_ordinate(p, samples.back()));
        samples.push_back(p);
      }
    }
  samples.insert(samples.end(), boundary.begin() + std::ptrdiff_t(next), boundary.end());
  if (!in_order) std::sort(samples.begin(), samples.end(), by_ordinate);
}

TEST(CoverageSamples, TheSamplesOfThePlainMergeBitForBit) {
  test::Rng rng(5252);
  std::uniform_real_distribution<double> any_angle(0, 180), unit(0, 1);
  std::size_t on_rows = 0, compared = 0;
  std::vector<Point2> fast, truth;
  for (int k = 0; k < 48; ++k) {
    const bool grid = k % 3 == 2;
    const std::vector<Ring> rings =
        grid ? std::vector<Ring>{test::random_grid_ring(rng, 30, 24)} : scan_test_area(rng, k);
    // Grids: rows at y_min + 1 + 2j (step 8: an eighth is 1, a quarter 2), on odd ordinates.
    const double angle = grid ? 0.0 : any_angle(rng);
    const double spacing = grid ? 8.0 : 5 + 40 * unit(rng);
    const LaneScan scan(rings, angle);
    fast.assign(3, Point2{1, 2});  // overwritten, whatever it held
    coverage_samples(scan, spacing, fast);
    merged_samples(scan, spacing, truth);
    ASSERT_EQ(fast.size(), truth.size()) << "area " << k;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(fast[i].x), std::bit_cast<std::uint64_t>(truth[i].x))
          << "area " << k << ", sample " << i;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(fast[i].y), std::bit_cast<std::uint64_t>(truth[i].y))
          << "area " << k << ", sample " << i;
    }
    compared += truth.size();
    if (grid)  // vertices (boundary samples) on a row
      for (const auto& [a, b] : scan.edges())
        on_rows += a.y > scan.y_min && a.y < scan.y_max && std::fmod(a.y - scan.y_min, 2) == 1;
  }
  EXPECT_GT(compared, 100000u);
  EXPECT_GT(on_rows, 100u);  // the grids do put boundary samples on the rows
}

// How many lanes longer than `min_length` of the rows at `ys` see `p` by the coverage check's test
// (the brute force: every lane asked); `by_widening` counts those among them that see it only
// through the ends' widening.
std::size_t long_lanes_seeing(const std::vector<double>& ys, const SpanRows& lanes, double half,
                              double min_length, Point2 p, std::size_t* by_widening = nullptr) {
  std::size_t seeing = 0;
  for (std::size_t r = 0; r < ys.size(); ++r)
    for (const Span& l : lanes[r])
      if (l.x1 - l.x0 > min_length && ys[r] - half <= p.y && p.y <= ys[r] + half &&
          l.x0 - kSeenAlongM <= p.x && p.x <= l.x1 + kSeenAlongM) {
        ++seeing;
        if (by_widening && (p.x < l.x0 || p.x > l.x1)) ++*by_widening;
      }
  return seeing;
}

// coverage_samples() with a LongLaneReach leaves out the samples a long lane sees: it must give,
// bit for bit and in the same order, every sample minus exactly those that some lane longer than
// the length sees by the coverage check's test, each lane asked (kept here: the brute force).
// Random fields with holes at random directions, lanes on random grids (footprints 1-3 spacings,
// slivers' lengths from none to most lanes), and integer grids at 0 degrees with lanes on integer
// ordinates, through vertices (boundary samples on the lanes' ends).
TEST(CoverageSamples, LeftOutAreExactlyThoseALongLaneSees) {
  test::Rng rng(5253);
  std::uniform_real_distribution<double> any_angle(0, 180), unit(0, 1);
  std::size_t kept = 0, left_out = 0;
  std::vector<Point2> fast, every, truth;
  for (int k = 0; k < 60; ++k) {
    const bool grid = k % 3 == 2;
    const std::vector<Ring> rings =
        grid ? std::vector<Ring>{test::random_grid_ring(rng, 30, 24)} : scan_test_area(rng, k);
    const double angle = grid ? 0.0 : any_angle(rng);
    const double spacing = grid ? 8.0 : 5 + 40 * unit(rng);
    const double footprint = grid ? 8.0 * (1 + k % 3) : spacing * (1 + 2 * unit(rng));
    const double min_length = k % 4 == 0 ? 0.0 : footprint * 4 * unit(rng);
    const LaneScan scan(rings, angle);
    std::vector<double> ys;
    for (double y = grid ? std::ceil(scan.y_min) : scan.y_min + spacing * unit(rng); y < scan.y_max;
         y += spacing)
      ys.push_back(y);
    const SpanRows lanes = scan.at(ys);
    const double half = seen_half_width_m(footprint);
    LongLaneReach reach(ys, lanes, half, min_length);
    fast.assign(3, Point2{1, 2});  // overwritten, whatever it held
    coverage_samples(scan, spacing, fast, &reach);
    coverage_samples(scan, spacing, every);
    truth.clear();
    for (const Point2& p : every)
      if (long_lanes_seeing(ys, lanes, half, min_length, p) == 0) truth.push_back(p);
    ASSERT_EQ(fast.size(), truth.size()) << "area " << k;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(fast[i].x), std::bit_cast<std::uint64_t>(truth[i].x))
          << "area " << k << ", sample " << i;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(fast[i].y), std::bit_cast<std::uint64_t>(truth[i].y))
          << "area " << k << ", sample " << i;
    }
    kept += truth.size();
    left_out += every.size() - truth.size();
  }
  EXPECT_GT(kept, 10000u);       // the test sees samples kept...
  EXPECT_GT(left_out, 100000u);  // ...and left out
}

// Lane rows for LongLaneReach's tests: a random spacing and footprint, the grid's rows over the
// scan and the lanes on them, and a random least length of a long lane.
struct LongLaneRows {
  std::vector<double> ys;
  SpanRows lanes;
  double spacing_m = 0, half_m = 0, min_length_m = 0;
};
LongLaneRows long_lane_rows(test::Rng& rng, const LaneScan& scan) {
  std::uniform_real_distribution<double> unit(0, 1);
  LongLaneRows rows;
  const double spacing = 5 + 40 * unit(rng), footprint = spacing * (1 + 2 * unit(rng));
  rows.spacing_m = spacing;
  for (double y = scan.y_min + spacing * unit(rng); y < scan.y_max; y += spacing)
    rows.ys.push_back(y);
  rows.lanes = scan.at(rows.ys);
  rows.half_m = seen_half_width_m(footprint);
  rows.min_length_m = footprint * 3 * unit(rng);
  return rows;
}

// LongLaneReach::at() must hold, at any ordinate asked in any order, the union of the long lanes'
// ranges over the rows within reach: checked point by point against every lane at random
// abscissae and ordinates, ascending and shuffled, and at the reach's edges: a lane's ends and
// half a footprint across, a rounding or less either side, and a micrometre past its ends (the
// ends' widening).
TEST(LongLaneReach, SeesWhatSomeLongLaneSees) {
  test::Rng rng(5255);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t seen_count = 0, asked = 0, widened = 0;
  for (int k = 0; k < 40; ++k) {
    const std::vector<Ring> rings = scan_test_area(rng, k);
    const LaneScan scan(rings, 180 * unit(rng));
    const auto [ys, lanes, spacing, half, min_length] = long_lane_rows(rng, scan);
    LongLaneReach reach(ys, lanes, half, min_length);
    std::vector<Point2> points;
    for (int i = 0; i < 3000; ++i) {
      const double y = scan.y_min - 10 + (scan.y_max - scan.y_min + 20) * unit(rng);
      points.push_back({-600 + 1200 * unit(rng), y});
    }
    for (std::size_t r = 0; r < ys.size(); r += 3)
      for (const Span& l : lanes[r])
        for (const double x : {l.x0, l.x1, l.x0 - 0.9e-6, l.x1 + 0.9e-6, l.x1 + 1.1e-6})
          for (const double y : {ys[r], ys[r] - half, ys[r] + half})
            for (const double dir : {-1.0, 0.0, 1.0})
              points.push_back({x, dir == 0 ? y : std::nextafter(y, dir * 1e300)});
    if (k % 2 == 0)
      std::sort(points.begin(), points.end(), [](Point2 a, Point2 b) { return a.y < b.y; });
    for (const Point2& p : points) {
      const bool truth = long_lanes_seeing(ys, lanes, half, min_length, p, &widened) > 0;
      ASSERT_EQ(reach.sees(p), truth) << "area " << k << " at " << p.x << ", " << p.y;
      seen_count += truth;
      ++asked;
    }
  }
  EXPECT_GT(seen_count, asked / 10);
  EXPECT_LT(seen_count, asked * 9 / 10);
  EXPECT_GT(widened, 1000u);  // points only the ends' widening lets a lane see
}

// LongLaneReach::sees_all() lets coverage_samples() pass over an edge's samples: where it says a
// box is seen whole, some long lane must see every point of it (the brute force over every lane,
// as above): checked at the box's corners, its middle, a rounding inside its corners and random
// points within, for small and long boxes at random places and boxes whose sides lie on a reach's
// edges (a lane's widened ends, half a footprint across, a rounding either side), points
// (degenerate boxes) among them, each told by the rows of its bottom, top or middle.
TEST(LongLaneReach, SeesAllOnlyWhatSomeLaneSeesAtEveryPoint) {
  test::Rng rng(5258);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t all_seen = 0, asked = 0, on_edges = 0;
  for (int k = 0; k < 40; ++k) {
    const std::vector<Ring> rings = scan_test_area(rng, k);
    const LaneScan scan(rings, 180 * unit(rng));
    const LongLaneRows rows = long_lane_rows(rng, scan);
    const auto& [ys, lanes, spacing, half, min_length] = rows;
    LongLaneReach reach(ys, lanes, half, min_length);
    const auto truth = [&rows](Point2 p) {
      return long_lanes_seeing(rows.ys, rows.lanes, rows.half_m, rows.min_length_m, p) > 0;
    };
    std::vector<std::pair<Point2, Point2>> boxes;
    for (int i = 0; i < 1500; ++i) {
      const Point2 p{-600 + 1200 * unit(rng),
                     scan.y_min - 10 + (scan.y_max - scan.y_min + 20) * unit(rng)};
      const double w = i % 3 == 0 ? 0.0 : spacing * (i % 3 == 1 ? 0.3 : 3.0) * unit(rng);
      const double h = i % 3 == 0 ? 0.0 : spacing * (i % 3 == 1 ? 0.3 : 3.0) * unit(rng);
      boxes.push_back({p, {p.x + w, p.y + h}});
    }
    const auto down = [](double v) { return std::nextafter(v, -1e300); };
    const auto up = [](double v) { return std::nextafter(v, 1e300); };
    for (std::size_t r = 0; r < ys.size(); r += 2)
      for (const Span& l : lanes[r]) {
        const double x0 = l.x0 - kSeenAlongM, x1 = l.x1 + kSeenAlongM;
        const double y0 = ys[r] - half, y1 = ys[r] + half, h = 0.4 * spacing * unit(rng);
        for (const double lo_x : {x0, down(x0), up(x0), (x0 + x1) / 2})
          for (const double hi_x : {x1, down(x1), up(x1), lo_x})
            for (const auto& [lo_y, hi_y] :
                 std::vector<std::pair<double, double>>{{y0, y0 + h},
                                                        {down(y0), y0 + h},
                                                        {up(y0), y0 + h},
                                                        {y1 - h, y1},
                                                        {y1 - h, up(y1)},
                                                        {y1 - h, down(y1)},
                                                        {y0, y1},
                                                        {y0, y0},
                                                        {y1, y1}})
              if (lo_x <= hi_x) boxes.push_back({{lo_x, lo_y}, {hi_x, hi_y}});
      }
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const auto& [lo, hi] = boxes[i];
      const double y = i % 3 == 0 ? lo.y : i % 3 == 1 ? hi.y : (lo.y + hi.y) / 2;
      ++asked;
      if (!reach.sees_all(lo, hi, y)) continue;
      ++all_seen;
      on_edges += i >= 1500;
      std::vector<Point2> points{lo,
                                 hi,
                                 {lo.x, hi.y},
                                 {hi.x, lo.y},
                                 (lo + hi) * 0.5,
                                 {up(lo.x), up(lo.y)},
                                 {down(hi.x), down(hi.y)}};
      for (int j = 0; j < 20; ++j)
        points.push_back({lo.x + (hi.x - lo.x) * unit(rng), lo.y + (hi.y - lo.y) * unit(rng)});
      for (Point2 p : points) {
        p = {std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y)};
        ASSERT_TRUE(truth(p)) << "area " << k << ", box " << i << " at " << p.x << ", " << p.y;
        ASSERT_TRUE(reach.sees(p)) << "area " << k << ", box " << i;
      }
    }
  }
  EXPECT_GT(all_seen, asked / 10);      // the test sees boxes seen whole...
  EXPECT_LT(all_seen, asked * 9 / 10);  // ...and not
  EXPECT_GT(on_edges, 1000u);           // among them boxes on a reach's edges
}

// edge_samples_box() must hold every sample a + (b - a) * (i / n) of an edge as coverage_samples()
// rounds it: edges of short and long lengths at coordinates from 0 and 1e-300 to 1e15, either
// sign, along the axes and not, with n from 1 to 64; and a box too narrow by a rounding misses
// some (the widening is needed).
TEST(EdgeSamplesBox, HoldsEveryRoundedSample) {
  test::Rng rng(5259);
  std::uniform_real_distribution<double> unit(0, 1), exponent(-300, 15);
  std::size_t checked = 0, outside_edge_box = 0;
  for (int k = 0; k < 20000; ++k) {
    const double scale = k % 5 == 0 ? 0.0 : std::pow(10.0, k % 5 == 1 ? exponent(rng) : 3.0);
    const auto coordinate = [&] { return (2 * unit(rng) - 1) * scale * (k % 7 == 0 ? 1 : 1e3); };
    Point2 a{coordinate(), coordinate()};
    Point2 b = k % 3 == 0 ? Point2{a.x + (2 * unit(rng) - 1) * 10, a.y + (2 * unit(rng) - 1) * 10}
                          : Point2{coordinate(), coordinate()};
    if (k % 11 == 0) b.y = a.y;  // along an axis
    const auto [lo, hi] = edge_samples_box(a, b);
    const int n = 1 + k % 64;
    for (int i = 0; i <= n; ++i) {
      const Point2 p = a + (b - a) * (double(i) / n);
      ASSERT_TRUE(p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y)
          << "edge " << k << ", sample " << i;
      outside_edge_box += p.x < std::min(a.x, b.x) || p.x > std::max(a.x, b.x) ||
                          p.y < std::min(a.y, b.y) || p.y > std::max(a.y, b.y);
      ++checked;
    }
  }
  EXPECT_GT(checked, 500000u);
  EXPECT_GT(outside_edge_box, 0u);  // rounding does put samples outside the edge's own box
}

// Turns::inside() passes over the edges away from a turn. It must answer what the full test
// answers over every edge of the area (kept here: the crossing test on each edge, then the middle
// on an edge or by crossings to the right): on random fields with holes at random directions and
// integer grids at 0 degrees (lane ends on vertices and along edges), for the turns lane_runs asks
// (the ends of lanes on neighbouring rows), turns a rounding or a tolerance off those ends, and
// random segments across the band.
TEST(Turns, AnswerWhatEveryEdgeAnswers) {
  test::Rng rng(5257);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto every_edge = [](const LaneScan& scan, Point2 a, Point2 b) {
    const double tolerance = 1e-9 * (1 + geometry::distance(a, b));
    for (const auto& [p, q] : scan.edges())
      if (geometry::segments_cross_clearly(a, b, p, q, tolerance)) return false;
    const Point2 m = (a + b) * 0.5;
    bool in = false;
    for (const auto& [p, q] : scan.edges()) {
      if (geometry::distance_to_segment(m, p, q) <= tolerance) return true;
      if ((p.y <= m.y) != (q.y <= m.y) && p.x + (m.y - p.y) * (q.x - p.x) / (q.y - p.y) > m.x)
        in = !in;
    }
    return in;
  };
  std::size_t asked = 0, inside = 0, on_edge = 0;
  for (int k = 0; k < 48; ++k) {
    const bool grid = k % 3 == 2;
    const std::vector<Ring> rings =
        grid ? std::vector<Ring>{test::random_grid_ring(rng, 30, 24)} : scan_test_area(rng, k);
    const LaneScan scan(rings, grid ? 0.0 : 180 * unit(rng));
    const double spacing = grid ? 4.0 : 5 + 40 * unit(rng);
    std::vector<double> ys;
    for (double y = grid ? std::ceil(scan.y_min) : scan.y_min + spacing * unit(rng); y < scan.y_max;
         y += spacing)
      ys.push_back(y);
    if (ys.size() < 2) continue;
    const SpanRows lanes = scan.at(ys);
    const Turns turns(scan, ys);
    const auto check = [&](Point2 a, Point2 b, std::size_t r) {
      const bool truth = every_edge(scan, a, b);
      ASSERT_EQ(turns.inside(a, b, r), truth) << "area " << k << " row " << r << ": " << a.x << ", "
                                              << a.y << " to " << b.x << ", " << b.y;
      ++asked;
      inside += truth;
      const Point2 m = (a + b) * 0.5;
      for (const auto& [p, q] : scan.edges())
        if (geometry::distance_to_segment(m, p, q) <= 1e-9 * (1 + geometry::distance(a, b))) {
          ++on_edge;
          break;
        }
    };
    for (std::size_t r = 0; r + 1 < ys.size(); ++r) {
      for (const Span& u : lanes[r])
        for (const Span& v : lanes[r + 1])
          for (const double d : {0.0, 1e-9, -1e-9, 1e-12}) {
            check({u.x0 + d, ys[r]}, {v.x0, ys[r + 1]}, r);
            check({u.x1, ys[r]}, {v.x1 - d, ys[r + 1]}, r);
            check({u.x0, ys[r]}, {std::nextafter(v.x1, 1e300), ys[r + 1]}, r);
          }
      for (int i = 0; i < 20; ++i)
        check({-600 + 1200 * unit(rng), ys[r]}, {-600 + 1200 * unit(rng), ys[r + 1]}, r);
    }
  }
  EXPECT_GT(asked, 20000u);
  EXPECT_GT(inside, asked / 10);  // the test sees turns inside, outside...
  EXPECT_LT(inside, asked * 9 / 10);
  EXPECT_GT(on_edge, 100u);  // ...and with their middle on an edge
}

// walk_lower_bound() (and walk_lower_bound_by()) must land where std::lower_bound lands, from any
// hint: ascending keys with repeats, values on keys, between, beyond both ends and NaN, hints
// anywhere (past the end too).
TEST(WalkLowerBound, LandsWhereTheSearchLands) {
  test::Rng rng(5254);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t far_walks = 0;
  for (int k = 0; k < 2000; ++k) {
    std::vector<double> keys(std::size_t(unit(rng) * 40));
    for (double& key : keys) key = std::floor(unit(rng) * 30) / 2;  // repeats
    std::sort(keys.begin(), keys.end());
    for (int q = 0; q < 20; ++q) {
      const double value = q == 0 ? std::numeric_limits<double>::quiet_NaN()
                           : q % 3 == 0 && !keys.empty()
                               ? keys[std::size_t(unit(rng) * double(keys.size()))]
                               : unit(rng) * 20 - 2.5;
      const auto hint = std::size_t(unit(rng) * double(keys.size() + 3));
      const auto truth =
          std::size_t(std::lower_bound(keys.begin(), keys.end(), value) - keys.begin());
      ASSERT_EQ(walk_lower_bound(keys.data(), keys.size(), value, hint), truth)
          << "set " << k << ", value " << value << ", hint " << hint;
      // The same walk over items by a key of theirs (sweep.cpp's strips by their tops).
      std::vector<std::pair<int, double>> items;
      for (const double key : keys) items.push_back({int(items.size()), key});
      ASSERT_EQ(walk_lower_bound_by(items.data(), items.size(), value, hint,
                                    [](const std::pair<int, double>& item) { return item.second; }),
                truth)
          << "set " << k << ", value " << value << ", hint " << hint;
      far_walks += hint > truth + 1 || hint + 1 < truth;
    }
  }
  EXPECT_GT(far_walks, 10000u);  // most walks go further than a step
}

}  // namespace
}  // namespace swath::planning::detail

// sweep_cells() bit for bit against sweep_decomposition() as it was before it took the
// decomposition by value (its pieces lent to the sweeps, its cells' rings moved) and turned the
// lanes' ends by one cosine and sine, kept here as the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "field_shapes.hpp"
#include "random_polygons.hpp"
#include "split_candidate.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/field.hpp"
#include "swath/geometry/turn.hpp"
#include "swath/planning/split.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;
using geometry::Ring;

// sweep_decomposition() as it was before it took the decomposition (its pieces lent to the sweeps,
// its cells' rings moved) and turned the lanes' ends by one cosine and sine: the reference
// sweep_cells() must equal bit for bit.
split_detail::Candidate reference_sweep_decomposition(const std::vector<geometry::Ring>& rings,
                                                      const geometry::Decomposition& d,
                                                      double angle, const SplitSettings& s) {
  split_detail::Candidate c;
  c.angle_deg = angle;
  // One lane grid for the whole area: lanes of neighbouring cells stay one spacing apart. Corners'
  // ordinates by turned_y (rotate()'s, the same values), here and for the pieces below.
  const geometry::Turn turned_y(-angle);
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const auto& ring : rings)
    for (const Point2& p : ring) {
      const double y = turned_y.y(p);
      y_min = std::min(y_min, y);
      y_max = std::max(y_max, y);
    }
  SweepSettings sweep_settings;
  sweep_settings.angle_deg = angle;
  sweep_settings.line_spacing_m = s.line_spacing_m;
  sweep_settings.footprint_width_m = s.footprint_width_m;
  sweep_settings.placement = s.placement;
  sweep_settings.turnaround_m = s.turnaround_m;
  sweep_settings.segments = SegmentRule::inside;
  sweep_settings.fill_protrusions = true;
  sweep_settings.ordinates =
      line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  // Lanes are placed per piece, so a piece thinner than the grid still gets one; cells (chains of
  // pieces) only group them for ordering.
  std::vector<std::vector<SweepLine>> piece_lines(d.pieces.size());
  geometry::Polygon piece;  // one, its capacity kept: copied into for each piece
  for (std::size_t k = 0; k < d.pieces.size(); ++k)
    if (!d.pieces[k].empty()) {
      piece.outer = d.pieces[k];
      piece_lines[k] = plan_sweep(piece, sweep_settings).lines;
    }
  // A lane on a cut between two pieces belongs to both: keep the longer one. Lanes sorted by
  // ordinate, so only neighbours in that order can coincide.
  struct Lane {
    double y, x0, x1;
    SweepLine* line;
    std::size_t piece;
  };
  std::vector<Lane> lanes;
  // Piece k's lines' ordinates (their starts', turned) from line_first[k] on, in its lines' order:
  // the cells' lines are sorted by them below (a removal below keeps a line's start).
  std::vector<double> line_y;
  std::vector<std::size_t> line_first{0};
  for (std::size_t k = 0; k < piece_lines.size(); ++k) {
    for (SweepLine& l : piece_lines[k]) {
      const Point2 p = rotate(l.start, -angle), q = rotate(l.end, -angle);
      lanes.push_back({p.y, std::min(p.x, q.x), std::max(p.x, q.x), &l, k});
      line_y.push_back(p.y);
    }
    line_first.push_back(line_y.size());
  }
  std::sort(lanes.begin(), lanes.end(), [](const Lane& u, const Lane& v) { return u.y < v.y; });
  for (std::size_t i = 0; i < lanes.size(); ++i)
    for (std::size_t j = i + 1;
         j < lanes.size() && lanes[j].y - lanes[i].y <= 1e-9 * (1 + std::abs(lanes[i].y)); ++j) {
      Lane& u = lanes[i];
      Lane& v = lanes[j];
      if (u.line->start == u.line->end || v.line->start == v.line->end) continue;
      if (std::min(u.x1, v.x1) <= std::max(u.x0, v.x0)) continue;  // side by side, not overlapping
      SweepLine& shorter = *(u.x1 - u.x0 < v.x1 - v.x0 ? u.line : v.line);
      shorter.end = shorter.start;  // marked for removal
    }
  // A piece no grid ordinate crosses (its lanes are the mid-height one and protrusion fills) that
  // the footprint of one grid lane of another piece sees whole gets no lane (docs/swath-plan.md,
  // slivers by coverage): e.g. the 4 cm wedge that an edge 0.004 degrees off the lanes leaves
  // beside a reflex vertex got two lanes 305 and 458 m long beside the grid lane that sees it.
  const double half = s.footprint_width_m / 2 + 1e-9;
  // A piece's least and greatest ordinate (a rotate() call per corner of every piece was most of
  // this function's own instructions); the whole corners only for the thin pieces asked below.
  std::vector<char> thin(d.pieces.size(), 0), covered(d.pieces.size(), 0);
  std::vector<std::pair<double, double>> span_y(d.pieces.size());  // a piece's least, greatest y
  for (std::size_t k = 0; k < d.pieces.size(); ++k) {
    if (d.pieces[k].empty()) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Point2& p : d.pieces[k]) {
      const double y = turned_y.y(p);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    span_y[k] = {lo, hi};
    const auto grid =
        std::lower_bound(sweep_settings.ordinates.begin(), sweep_settings.ordinates.end(), lo);
    thin[k] = grid == sweep_settings.ordinates.end() || *grid > hi;
  }
  std::vector<Point2> corners;  // a thin piece's, turned
  for (std::size_t k = 0; k < d.pieces.size(); ++k) {
    if (!thin[k] || piece_lines[k].empty()) continue;
    corners.clear();
    for (const Point2& p : d.pieces[k]) corners.push_back(rotate(p, -angle));
    // Only a lane within half a footprint of the piece's lowest and highest corners can see it
    // whole: the lanes (sorted by ordinate) in that window, widened well past rounding, are asked
    // (all lanes were, hundreds of thin pieces by thousands of lanes on 10,000-vertex areas).
    const auto [y_lo, y_hi] = span_y[k];
    const double slack = 1e-6 * (1 + std::abs(y_lo) + std::abs(y_hi) + half);
    const auto first = std::lower_bound(lanes.begin(), lanes.end(), y_hi - half - slack,
                                        [](const Lane& l, double y) { return l.y < y; });
    for (auto it = first; it != lanes.end() && it->y <= y_lo + half + slack; ++it) {
      const Lane& lane = *it;
      if (thin[lane.piece] || lane.line->start == lane.line->end) continue;
      const double x0 = lane.x0 + s.turnaround_m - 1e-6, x1 = lane.x1 - s.turnaround_m + 1e-6;
      if (std::all_of(corners.begin(), corners.end(), [&](Point2 q) {
            return std::abs(q.y - lane.y) <= half && q.x >= x0 && q.x <= x1;
          })) {
        covered[k] = 1;
        break;
      }
    }
  }
  for (std::size_t k = 0; k < d.pieces.size(); ++k)
    if (covered[k]) piece_lines[k].clear();
  // A cell's lines by ordinate: sorted with their ordinates beside them (not turned again for
  // every comparison), the same comparisons in the same order, so the same order of equal ones.
  std::vector<std::pair<double, SweepLine>> by_y;
  for (std::size_t cell = 0; cell < d.cells.size(); ++cell) {
    by_y.clear();
    for (const std::size_t k : d.cells[cell])
      for (std::size_t i = 0; i < piece_lines[k].size(); ++i) {
        const SweepLine& l = piece_lines[k][i];
        if (!(l.start == l.end)) by_y.push_back({line_y[line_first[k] + i], l});
      }
    std::sort(by_y.begin(), by_y.end(),
              [](const auto& u, const auto& v) { return u.first < v.first; });
    if (by_y.empty()) continue;
    Sweep sweep;
    sweep.angle_deg = angle;
    sweep.lines.reserve(by_y.size());
    for (const auto& [y, l] : by_y) sweep.lines.push_back(l);
    c.cells.push_back(d.cell_rings[cell]);
    c.sweeps.push_back(std::move(sweep));
  }
  return c;
}

// sweep_cells() on traced outlines (narrow arms, holes), the split corpus's combs and fields with
// holes at many directions, with and without a turnaround: the same cells and lanes, bit for bit,
// as the reference above on the same decomposition.
TEST(SplitSurvey, SweepCellsAsTheReferenceBitForBit) {
  std::vector<test::CorpusShape> shapes;
  for (test::CorpusShape& shape : test::split_corpus(78, 2))
    if (shape.family == "holes" || shape.family == "comb") shapes.push_back(std::move(shape));
  test::Rng rng(7778);
  for (int k = 0; k < 4; ++k) shapes.push_back({"traced", k, test::traced_outline(rng)});
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  const auto same = [&](Point2 p, Point2 q) {
    return bits(p.x) == bits(q.x) && bits(p.y) == bits(q.y);
  };
  std::size_t lines = 0;
  for (const test::CorpusShape& shape : shapes) {
    const std::vector<Ring> rings = geometry::rings_of(shape.area);
    for (const double turnaround_m : {0.0, 25.0}) {
      SplitSettings s;
      s.line_spacing_m = shape.family == "traced" ? 43.5 : 30;
      s.footprint_width_m = shape.family == "traced" ? 145 : 45;
      s.turnaround_m = turnaround_m;
      for (int k = 0; k < 20; ++k) {
        const double angle = 9.0 * k + 0.37;
        const split_detail::Candidate fast = split_detail::sweep_cells(rings, angle, s);
        const geometry::Decomposition d = geometry::boustrophedon_decomposition(rings, angle);
        const split_detail::Candidate truth = reference_sweep_decomposition(rings, d, angle, s);
        ASSERT_EQ(bits(fast.angle_deg), bits(truth.angle_deg));
        ASSERT_EQ(fast.cells.size(), truth.cells.size()) << shape.family << " at " << angle;
        ASSERT_EQ(fast.sweeps.size(), truth.sweeps.size()) << shape.family << " at " << angle;
        for (std::size_t c = 0; c < truth.cells.size(); ++c) {
          ASSERT_EQ(fast.cells[c].size(), truth.cells[c].size());
          for (std::size_t i = 0; i < truth.cells[c].size(); ++i)
            ASSERT_TRUE(same(fast.cells[c][i], truth.cells[c][i])) << c << " " << i;
          ASSERT_EQ(fast.sweeps[c].lines.size(), truth.sweeps[c].lines.size())
              << shape.family << " " << shape.index << " at " << angle << " cell " << c;
          for (std::size_t i = 0; i < truth.sweeps[c].lines.size(); ++i) {
            ASSERT_TRUE(same(fast.sweeps[c].lines[i].start, truth.sweeps[c].lines[i].start))
                << shape.family << " " << shape.index << " at " << angle << " cell " << c;
            ASSERT_TRUE(same(fast.sweeps[c].lines[i].end, truth.sweeps[c].lines[i].end))
                << shape.family << " " << shape.index << " at " << angle << " cell " << c;
          }
          lines += truth.sweeps[c].lines.size();
        }
      }
    }
  }
  EXPECT_GT(lines, 10000u);
  RecordProperty("lines", std::to_string(lines));
}

}  // namespace
}  // namespace swath::planning

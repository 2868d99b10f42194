// The runs' side of the direction search (split_runs.hpp): estimates asked in order of their lower
// bounds choose the candidates every estimate chooses, and the runs' bound is below their estimate.
#include "split_runs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <tuple>

#include "field_shapes.hpp"
#include "split_candidate.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/cell_order.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;
using geometry::Ring;
using split_detail::best_of_each_kind;
using split_detail::estimates_by_bound;

std::vector<std::tuple<int, double, std::size_t>> tagged(const std::vector<int>& kinds,
                                                         const std::vector<double>& estimates) {
  std::vector<std::tuple<int, double, std::size_t>> out;
  for (std::size_t i = 0; i < kinds.size(); ++i) out.push_back({kinds[i], estimates[i], i});
  return out;
}

// Random candidates of two kinds with two bounds below their estimates (some equal to them, some
// estimates tied, as directions with the same runs are), on one thread and on three: the
// candidates chosen from the estimates asked by bound are those chosen from every estimate, in
// the same order; the ones asked keep their own estimate; and most are not asked.
TEST(SplitRuns, EstimatesAskedByBoundChooseTheSameCandidates) {
  std::mt19937_64 rng(5252);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t asked_total = 0, total = 0;
  for (int round = 0; round < 400; ++round) {
    const std::size_t n = 1 + std::size_t(round % 60);
    std::vector<int> kinds(n);
    std::vector<double> estimates(n), bounds(n), tighter(n);
    for (std::size_t i = 0; i < n; ++i) {
      kinds[i] = unit(rng) < 0.3 ? 0 : 1;
      // Few distinct values: ties between estimates, and between bounds and estimates.
      estimates[i] =
          round % 3 == 0 ? 1000 + 10 * std::floor(unit(rng) * 6) : 1000 + 900 * unit(rng);
      const double slack = unit(rng);
      // Some bounds a few 1e-13 above their estimate, as rounding leaves a sum of the same
      // lengths in another order: the skip's margin must keep them (with ties, one left out
      // would change the choice).
      tighter[i] = slack < 0.2 ? estimates[i] * (1 + 1e-13 * std::floor(unit(rng) * 4))
                               : estimates[i] * (1 - 0.1 * slack);
      bounds[i] = unit(rng) < 0.5 ? tighter[i] : tighter[i] * (1 - 0.3 * unit(rng));
    }
    const std::size_t per_kind = std::size_t(round % 5);  // 0: none refined
    const auto every = best_of_each_kind(tagged(kinds, estimates), per_kind);
    for (const unsigned threads : {1u, 3u, 0u}) {  // 0: one thread, no tighter bound
      std::atomic<std::size_t> asked{0};
      std::function<double(std::size_t)> tighter_bound;
      if (threads > 0) tighter_bound = [&](std::size_t i) { return tighter[i]; };
      const std::vector<double> found = estimates_by_bound(
          kinds, bounds, per_kind, std::max(threads, 1u), tighter_bound, [&](std::size_t i) {
            ++asked;
            return estimates[i];
          });
      ASSERT_EQ(found.size(), n);
      std::size_t finite = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (std::isinf(found[i])) continue;
        EXPECT_EQ(found[i], estimates[i]) << round << " " << i;
        ++finite;
      }
      EXPECT_EQ(finite, asked.load()) << round;
      EXPECT_EQ(best_of_each_kind(tagged(kinds, found), per_kind), every)
          << "round " << round << ", " << threads << " threads";
      if (threads == 1 && per_kind > 0) {
        asked_total += asked;
        total += n;
      }
    }
  }
  // Not vacuous: most estimates are left out once the first few are known.
  EXPECT_LT(double(asked_total), 0.5 * double(total));
  RecordProperty("asked_fraction", std::to_string(double(asked_total) / double(total)));
}

// What the skip relies on: the runs' straight lower bounds (order_lower_bound(), and the cheaper
// internal_lower_bound() below it) are below their
// estimate (the nearest neighbour's tour on the same problem), up to rounding far below the 1e-9
// margin the skip allows for it, at every direction of the split corpus's shapes, home inside and
// out.
TEST(SplitRuns, TheRunsBoundIsBelowTheirEstimate) {
  double ratio_sum = 0, closest = 0;
  int n = 0;
  for (const test::CorpusShape& shape : test::split_corpus(5252, 3)) {
    const std::vector<Ring> rings = geometry::rings_of(shape.area);
    SplitSettings s;
    s.line_spacing_m = 26.1;
    s.footprint_width_m = 87;
    std::vector<Point2> samples;
    for (int k = 0; k < 24; ++k) {
      const double angle = 7.5 * k + 0.37;
      const Point2 home = k % 2 ? Point2{-700, 300} : shape.area.outer.front();
      samples.clear();
      split_detail::Candidate c = split_detail::sweep_runs(rings, angle, s, false, samples);
      if (c.cells.empty()) continue;
      CellOrderProblem problem = split_detail::problem_for(c, home, split_detail::straight_m);
      problem.distance_at_least_straight = true;
      const double bound = order_lower_bound(problem);
      const double estimate = nearest_neighbour_order(problem).length_m;
      ASSERT_LE(bound, estimate * (1 + 1e-12))
          << shape.family << " " << shape.index << " at " << angle;
      // The cheaper bound, below the other (it leaves out the transits).
      ASSERT_LE(split_detail::internal_lower_bound(problem), bound)
          << shape.family << " " << shape.index << " at " << angle;
      ratio_sum += bound / estimate;
      closest = std::max(closest, bound / estimate);
      ++n;
    }
  }
  ASSERT_GT(n, 300);
  EXPECT_GT(ratio_sum / n, 0.5);  // not vacuous: most of the estimate
  RecordProperty("mean_bound_over_estimate", std::to_string(ratio_sum / n));
  RecordProperty("closest", std::to_string(closest));
}

}  // namespace
}  // namespace swath::planning

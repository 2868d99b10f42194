// The local search reuses the layers of its variant table before the first position a move
// changes, gives up on a move once a lower bound shows it cannot win, and nearest neighbour skips
// cells whose least internal length cannot win. Orders must be the ones the plain search gives,
// bit for bit: checked against that search written out (every candidate order's table from the
// start, every cell asked) on random problems (fixed seeds) with crossings, ties (cells on a
// grid, equal lengths) and cells of one to four variants.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <random>
#include <set>

#include "swath/planning/cell_order.hpp"

#include "cell_order_shared.hpp"

namespace swath::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::uint64_t order_bit(std::size_t cell) {
  return cell < 63 ? std::uint64_t{1} << cell : 0;
}

// The plain search: the truth.
struct PlainSearch {
  const CellOrderProblem& p;
  double cost(const CellVariant& from, std::size_t to_cell, const CellVariant& to,
              std::uint64_t unflown) const {
    const double d = p.distance(from.exit, to.entry);
    if (!p.crossed) return d;
    (void)to_cell;
    return d * (1 + p.crossing_weight * std::popcount(p.crossed(from.exit, to.entry) & unflown));
  }
  CellOrder variants(const std::vector<std::size_t>& order) const {
    const std::size_t n = order.size();
    std::vector<std::vector<double>> c(n);
    std::vector<std::vector<std::size_t>> from(n);
    std::vector<std::uint64_t> after(n + 1, 0);
    for (std::size_t k = n; k-- > 0;) after[k] = after[k + 1] | order_bit(order[k]);
    for (std::size_t k = 0; k < n; ++k) {
      const auto& vs = p.cells[order[k]];
      c[k].assign(vs.size(), kInf);
      from[k].assign(vs.size(), 0);
      for (std::size_t v = 0; v < vs.size(); ++v) {
        if (k == 0) {
          c[k][v] = p.distance(p.home, vs[v].entry) + vs[v].internal_m;
          continue;
        }
        const auto& before = p.cells[order[k - 1]];
        for (std::size_t u = 0; u < before.size(); ++u) {
          const double x =
              c[k - 1][u] + cost(before[u], order[k], vs[v], after[k + 1]) + vs[v].internal_m;
          if (x < c[k][v]) {
            c[k][v] = x;
            from[k][v] = u;
          }
        }
      }
    }
    std::size_t best = 0;
    double best_cost = kInf;
    for (std::size_t v = 0; v < c[n - 1].size(); ++v) {
      const double x = c[n - 1][v] + p.distance(p.cells[order[n - 1]][v].exit, p.home);
      if (x < best_cost) {
        best_cost = x;
        best = v;
      }
    }
    CellOrder out;
    out.visits.resize(n);
    for (std::size_t k = n; k-- > 0;) {
      out.visits[k] = {order[k], best};
      best = from[k][best];
    }
    out.objective_m = best_cost;
    return out;
  }
  std::vector<std::size_t> nearest() const {
    const std::size_t n = p.cells.size();
    std::vector<std::size_t> order;
    std::vector<char> used(n, 0);
    geometry::Point2 at = p.home;
    for (std::size_t k = 0; k < n; ++k) {
      double best = kInf;
      std::size_t best_cell = 0, best_variant = 0;
      for (std::size_t c = 0; c < n; ++c) {
        if (used[c]) continue;
        for (std::size_t v = 0; v < p.cells[c].size(); ++v) {
          const double x = p.distance(at, p.cells[c][v].entry) + p.cells[c][v].internal_m;
          if (x < best) {
            best = x;
            best_cell = c;
            best_variant = v;
          }
        }
      }
      used[best_cell] = 1;
      order.push_back(best_cell);
      at = p.cells[best_cell][best_variant].exit;
    }
    return order;
  }
  // One move of the search, written out: a block of `len` cells from i to j (move 0), a swap
  // (1), a reversal of i..j (2); empty where it does not apply.
  static std::vector<std::size_t> moved(const std::vector<std::size_t>& order, int move,
                                        std::size_t i, std::size_t j, std::size_t len) {
    const std::size_t n = order.size();
    std::vector<std::size_t> c;
    if (move == 0) {
      if (i + len > n || (j >= i && j < i + len) || j + len > n) return c;
      c = order;
      const std::vector<std::size_t> block(c.begin() + std::ptrdiff_t(i),
                                           c.begin() + std::ptrdiff_t(i + len));
      c.erase(c.begin() + std::ptrdiff_t(i), c.begin() + std::ptrdiff_t(i + len));
      c.insert(c.begin() + std::ptrdiff_t(j), block.begin(), block.end());
    } else if (j > i) {
      c = order;
      if (move == 1)
        std::swap(c[i], c[j]);
      else
        std::reverse(c.begin() + std::ptrdiff_t(i), c.begin() + std::ptrdiff_t(j) + 1);
    }
    return c;
  }
  void local_search(std::vector<std::size_t>& order, CellOrder& best, std::size_t reach,
                    std::size_t& budget) const {
    const std::size_t n = order.size();
    for (bool improved = true; improved && budget > 0;) {
      improved = false;
      for (std::size_t i = 0; i < n && budget > 0; ++i)
        for (std::size_t j = i >= reach ? i - reach : 0;
             j < std::min(n, i + reach + 1) && budget > 0; ++j)
          for (int kind = 0; kind < 5 && budget > 0; ++kind) {
            const std::vector<std::size_t> candidate =
                moved(order, kind < 3 ? 0 : kind - 2, i, j, kind < 3 ? std::size_t(kind) + 1 : 1);
            if (candidate.empty() || i == j) continue;
            --budget;
            const CellOrder tried = variants(candidate);
            if (tried.objective_m < best.objective_m - 1e-9) {
              best = tried;
              order = candidate;
              improved = true;
            }
          }
    }
  }
  CellOrder heuristic() const {
    const std::size_t n = p.cells.size();
    std::vector<std::size_t> order = nearest();
    CellOrder best = variants(order);
    const std::size_t reach = n <= 24 ? n : 8;
    std::size_t budget = 200000 / n;
    local_search(order, best, reach, budget);
    std::mt19937 kicks(static_cast<std::uint32_t>(n));
    for (int kick = 0; kick < 24 && budget > 0 && n >= 8; ++kick) {
      std::size_t cut[3];
      for (std::size_t& c : cut) c = 1 + kicks() % (n - 1);
      std::sort(cut, cut + 3);
      if (cut[0] == cut[1] || cut[1] == cut[2]) continue;
      std::vector<std::size_t> candidate(order.begin(), order.begin() + std::ptrdiff_t(cut[0]));
      for (const auto& [from, to] :
           {std::pair{cut[1], cut[2]}, std::pair{cut[0], cut[1]}, std::pair{cut[2], n}})
        candidate.insert(candidate.end(), order.begin() + std::ptrdiff_t(from),
                         order.begin() + std::ptrdiff_t(to));
      CellOrder tried = variants(candidate);
      local_search(candidate, tried, reach, budget);
      if (tried.objective_m < best.objective_m - 1e-9) {
        best = tried;
        order = candidate;
      }
    }
    return best;
  }
};

CellOrderProblem random_problem(std::mt19937_64& rng, std::size_t n, bool grid, bool crossings) {
  std::uniform_real_distribution<double> coordinate(-500, 500), length(0, 2000);
  std::uniform_int_distribution<int> cell_on_grid(-5, 5), variants(1, 4);
  CellOrderProblem p;
  p.home = {-600, -600};
  auto point = [&] {
    return grid ? geometry::Point2{100.0 * cell_on_grid(rng), 100.0 * cell_on_grid(rng)}
                : geometry::Point2{coordinate(rng), coordinate(rng)};
  };
  for (std::size_t c = 0; c < n; ++c) {
    std::vector<CellVariant> cell;
    const double internal = grid ? 500.0 * double(1 + c % 3) : length(rng);
    for (int v = variants(rng); v > 0; --v) cell.push_back({point(), point(), internal + 10 * v});
    p.cells.push_back(cell);
  }
  p.distance = [](geometry::Point2 a, geometry::Point2 b) { return geometry::distance(a, b); };
  if (crossings)  // a fixed pseudo-random set of cells per transit
    p.crossed = [](geometry::Point2 a, geometry::Point2 b) {
      const auto h = std::hash<double>{}(a.x * 3 + b.y) ^ std::hash<double>{}(a.y - 7 * b.x);
      return std::uint64_t(h) & (std::uint64_t(h) >> 7) & 0x7fffffffffffffffull;
    };
  return p;
}

TEST(CellOrderSearch, HeuristicAndNearestNeighbourAreBitForBitThePlainSearch) {
  std::mt19937_64 rng(18);
#ifdef SWATH_SANITIZED
  const int problems = 8;  // 13 to 34 cells; CI's sanitized pass looks for memory errors
#else
  const int problems = 24;
#endif
  for (int k = 0; k < problems; ++k) {
    const CellOrderProblem p = random_problem(rng, 13 + std::size_t(k) * 3, k % 3 == 0, k % 2 == 0);
    const PlainSearch plain{p};
    const CellOrder fast = heuristic_cell_order(p), truth = plain.heuristic();
    ASSERT_EQ(fast.objective_m, truth.objective_m) << "problem " << k;
    ASSERT_EQ(fast.visits.size(), truth.visits.size());
    for (std::size_t i = 0; i < truth.visits.size(); ++i) {
      ASSERT_EQ(fast.visits[i].cell, truth.visits[i].cell) << "problem " << k << " at " << i;
      ASSERT_EQ(fast.visits[i].variant, truth.visits[i].variant);
    }
    const CellOrder quick = nearest_neighbour_order(p);
    const CellOrder quick_truth = plain.variants(plain.nearest());
    ASSERT_EQ(quick.objective_m, quick_truth.objective_m) << "problem " << k;
    for (std::size_t i = 0; i < quick_truth.visits.size(); ++i) {
      ASSERT_EQ(quick.visits[i].cell, quick_truth.visits[i].cell);
      ASSERT_EQ(quick.visits[i].variant, quick_truth.visits[i].variant);
    }
  }
}

// With transits never shorter than straight ones (routed paths), the local search first bounds a
// move's cost from below without asking the metric (straight lengths for transits not yet
// asked, lengths without their penalty where the crossings are not yet known) and drops the moves
// that bound shows cannot win. Orders must still be the plain search's bit for bit: problems
// with and without crossings, on a grid (ties) and spread, transits straight (the bound within
// rounding of the cost) and Manhattan (longer). A bound that dropped a winning move would change
// the order or the objective.
TEST(CellOrderSearch, BoundedMovesKeepThePlainSearch) {
  std::mt19937_64 rng(1826);
#ifdef SWATH_SANITIZED
  const int problems = 4;
#else
  const int problems = 16;
#endif
  int routed_like = 0;
  for (int k = 0; k < problems; ++k) {
    CellOrderProblem p = random_problem(rng, 9 + std::size_t(k) * 2, k % 4 == 1, k % 2 == 0);
    if (k % 3 != 0) {  // longer than straight, as routed transits around holes are
      p.distance = [](geometry::Point2 a, geometry::Point2 b) {
        return std::abs(a.x - b.x) + std::abs(a.y - b.y);
      };
      ++routed_like;
    }
    p.distance_at_least_straight = true;
    const CellOrder fast = heuristic_cell_order(p), truth = PlainSearch{p}.heuristic();
    ASSERT_EQ(fast.objective_m, truth.objective_m) << "problem " << k;
    ASSERT_EQ(fast.visits.size(), truth.visits.size());
    for (std::size_t i = 0; i < truth.visits.size(); ++i) {
      ASSERT_EQ(fast.visits[i].cell, truth.visits[i].cell) << "problem " << k << " at " << i;
      ASSERT_EQ(fast.visits[i].variant, truth.visits[i].variant);
    }
  }
  EXPECT_GT(routed_like, 0);
}

// Nearest neighbour with transits never shorter than straight ones looks only at cells near
// enough to win (a grid over the entries, the straight distance as a bound): the same order as
// the plain search's every cell, on problems of 1 to ~700 cells spread over a square, on one line
// (a grid one bucket high), clustered in a corner with a few far away, on a coarse grid full of
// equal costs (ties go to the lower cell, then variant), with internal lengths from 0 to far
// longer than the transits, home inside and far outside; straight transits and longer ones
// (Manhattan, as routed paths around holes are longer). The local search that starts from it
// (heuristic_cell_order) gives the same order as without the bound.
TEST(CellOrderSearch, NearestNeighbourOnTheEntriesGridIsThePlainOne) {
  std::mt19937_64 rng(1818);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> variants(1, 4), step(-6, 6);
#ifdef SWATH_SANITIZED
  // The sanitized pass looks for memory errors, not orders: up to 64 cells (the searches' time at
  // 150 to 700 cells was most of this test's 20 s there), the local search compared up to 7 (its
  // kicks on 13 to 34 cells are compared above).
  const std::size_t sizes[] = {1, 2, 3, 7, 20, 64};
  constexpr std::size_t kSearchedUpTo = 7;
#else
  const std::size_t sizes[] = {1, 2, 3, 7, 20, 64, 150, 400, 700};
  constexpr std::size_t kSearchedUpTo = 64;
#endif
  constexpr int kSizes = sizeof(sizes) / sizeof(sizes[0]);
  int checked = 0;
  for (int layout = 0; layout < 5; ++layout)
    for (const std::size_t n : sizes)
      for (int internal_kind = 0; internal_kind < 3; ++internal_kind) {
        CellOrderProblem p;
        p.home = layout % 2 ? geometry::Point2{-5000, 3000} : geometry::Point2{10, -20};
        auto point = [&]() -> geometry::Point2 {
          switch (layout) {
            case 0:  // spread over a square
              return {1000 * unit(rng), 1000 * unit(rng)};
            case 1:  // on one line
              return {2000 * unit(rng), 250};
            case 2:  // a cluster and a few far away
              return unit(rng) < 0.9 ? geometry::Point2{5 * unit(rng), 5 * unit(rng)}
                                     : geometry::Point2{3000 * unit(rng), -4000 * unit(rng)};
            default:  // a coarse grid: equal entries and equal costs
              return {50.0 * step(rng), 50.0 * step(rng)};
          }
        };
        for (std::size_t c = 0; c < n; ++c) {
          std::vector<CellVariant> cell;
          for (int v = variants(rng); v > 0; --v) {
            const double internal = internal_kind == 0   ? 0.0
                                    : internal_kind == 1 ? 100.0 * double(c % 4)
                                                         : 20000 * unit(rng);
            cell.push_back({point(), point(), internal});
          }
          p.cells.push_back(cell);
        }
        for (const bool manhattan : {false, true}) {
          if (manhattan)
            p.distance = [](geometry::Point2 a, geometry::Point2 b) {
              return std::abs(a.x - b.x) + std::abs(a.y - b.y);
            };
          else
            p.distance = [](geometry::Point2 a, geometry::Point2 b) {
              return geometry::distance(a, b);
            };
          p.distance_at_least_straight = false;
          const std::vector<std::size_t> truth = PlainSearch{p}.nearest();
          const CellOrder plain = nearest_neighbour_order(p);
          const CellOrder plain_search = n <= kSearchedUpTo ? heuristic_cell_order(p) : CellOrder{};
          p.distance_at_least_straight = true;
          const CellOrder fast = nearest_neighbour_order(p);
          ASSERT_EQ(fast.visits.size(), truth.size());
          for (std::size_t i = 0; i < truth.size(); ++i) {
            ASSERT_EQ(fast.visits[i].cell, truth[i])
                << "layout " << layout << ", " << n << " cells, internal " << internal_kind
                << (manhattan ? ", Manhattan" : "") << ", at " << i;
            ASSERT_EQ(fast.visits[i].cell, plain.visits[i].cell);
            ASSERT_EQ(fast.visits[i].variant, plain.visits[i].variant);
          }
          ASSERT_EQ(fast.objective_m, plain.objective_m);
          if (n <= kSearchedUpTo) {
            const CellOrder fast_search = heuristic_cell_order(p);
            ASSERT_EQ(fast_search.objective_m, plain_search.objective_m);
            ASSERT_EQ(fast_search.visits.size(), plain_search.visits.size());
            for (std::size_t i = 0; i < n; ++i) {
              ASSERT_EQ(fast_search.visits[i].cell, plain_search.visits[i].cell);
              ASSERT_EQ(fast_search.visits[i].variant, plain_search.visits[i].variant);
            }
          }
          ++checked;
        }
      }
  EXPECT_EQ(checked, 5 * kSizes * 3 * 2);
}

// The nearest neighbour on the entries' grid asks only the entries near enough to win: with a
// routed-like metric (some pairs up to 60 % longer than straight: the bounds loose) the same order
// and variants as the plain nearest neighbour, ties included (a coarse grid with Manhattan
// transits: equal costs from entries at unequal straight distances, where the lower cell then
// variant must win), and fewer transits asked than the brute force.
TEST(CellOrderSearch, NearestNeighbourOnTheGridKeepsTheTiesWithRoutedLikeTransits) {
  std::mt19937_64 rng(5253);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> variants(1, 4), step(-5, 5);
  std::size_t asked_fast = 0, asked_plain = 0;
  for (int k = 0; k < 60; ++k) {
    const bool grid = k % 2 == 1;
    const std::size_t n = 5 + std::size_t(k) * 4;
    CellOrderProblem p;
    p.home = {0, 0};
    const auto point = [&]() -> geometry::Point2 {
      if (grid) return {40.0 * step(rng), 40.0 * step(rng)};
      return {1000 * unit(rng), 1000 * unit(rng)};
    };
    for (std::size_t c = 0; c < n; ++c) {
      std::vector<CellVariant> cell;
      for (int v = variants(rng); v > 0; --v)
        cell.push_back({point(), point(), grid ? 100.0 : 300 * unit(rng)});
      p.cells.push_back(cell);
    }
    auto count = std::make_shared<std::size_t>(0);
    p.distance = [count, grid](geometry::Point2 a, geometry::Point2 b) {
      ++*count;
      if (grid) return std::abs(a.x - b.x) + std::abs(a.y - b.y);  // equal costs, unequal bounds
      const auto h = std::uint64_t(std::llround(a.x * 3 + a.y * 5 + b.x * 11 + b.y * 23));
      const std::uint64_t mixed = h * 0x9E3779B97F4A7C15ull >> 40;
      return geometry::distance(a, b) * (1 + (mixed % 2 ? 0.0 : 0.6 * double(mixed % 100) / 100));
    };
    p.distance_at_least_straight = false;
    const CellOrder plain = nearest_neighbour_order(p);
    const std::vector<std::size_t> truth = PlainSearch{p}.nearest();
    *count = 0;
    p.distance_at_least_straight = true;
    const CellOrder fast = nearest_neighbour_order(p);
    asked_fast += *count;
    asked_plain += n * (n + 1) / 2;  // the brute force's asks, at least
    ASSERT_EQ(fast.visits.size(), truth.size()) << k;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      ASSERT_EQ(fast.visits[i].cell, truth[i]) << "problem " << k << " at " << i;
      ASSERT_EQ(fast.visits[i].cell, plain.visits[i].cell);
      ASSERT_EQ(fast.visits[i].variant, plain.visits[i].variant) << "problem " << k << " at " << i;
    }
    ASSERT_EQ(fast.objective_m, plain.objective_m) << k;
  }
  EXPECT_LT(asked_fast, asked_plain);
}

}  // namespace
}  // namespace swath::planning

namespace swath::planning {
namespace {

// Beyond 2,048 variants in all the search keeps only the transitions it asks for (hashed), not a
// table of every pair: a star-shaped field of 18,000 one-lane runs asked for ~5 * 10^9 entries
// and ran out of memory. The orders are still the plain search's, bit for bit (1,000 cells,
// ~2,500 variants, with crossings), and 20,000 cells order in bounded memory with the objective
// the order's own evaluation gives.
TEST(CellOrderSearch, ManyVariantsKeepOnlyTheTransitionsAsked) {
  std::mt19937_64 rng(1827);
  for (const bool crossings : {false, true}) {
    const CellOrderProblem p = random_problem(rng, 1000, false, crossings);
    std::size_t variants = 0;
    for (const auto& cell : p.cells) variants += cell.size();
    ASSERT_GT(variants, 2048u);
    const PlainSearch plain{p};
    const CellOrder fast = heuristic_cell_order(p), truth = plain.heuristic();
    ASSERT_EQ(fast.objective_m, truth.objective_m) << crossings;
    ASSERT_EQ(fast.visits.size(), truth.visits.size());
    for (std::size_t i = 0; i < truth.visits.size(); ++i) {
      ASSERT_EQ(fast.visits[i].cell, truth.visits[i].cell) << crossings << " at " << i;
      ASSERT_EQ(fast.visits[i].variant, truth.visits[i].variant);
    }
  }
  CellOrderProblem many = random_problem(rng, 20000, false, false);
  many.distance_at_least_straight = true;
  const CellOrder order = heuristic_cell_order(many);
  ASSERT_EQ(order.visits.size(), many.cells.size());
  std::vector<char> seen(many.cells.size(), 0);
  for (const CellVisit& v : order.visits) seen.at(v.cell) += 1;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(many.cells.size()));
  EXPECT_DOUBLE_EQ(order.length_m, evaluate_order(many, order.visits).length_m);
}

}  // namespace
}  // namespace swath::planning

namespace swath::planning {
namespace {

// first_least() (the least of values some of which are only bounded from below until asked, and
// the first index giving it) against the plain scan over the exact values: random values of one
// to four entries with ties, infinities, bounds equal to the value or below it, some known from
// the start. The answer must be the scan's (value and index); every entry not asked must be one
// that could not change it.
TEST(CellOrderSearch, FirstLeastIsThePlainScan) {
  std::mt19937_64 rng(5218);
  std::uniform_int_distribution<int> count_of(1, 4), level(0, 5), coin(0, 3);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t skipped = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::size_t count = std::size_t(count_of(rng));
    double exact[4], value[4];
    bool known[4];
    for (std::size_t u = 0; u < count; ++u) {
      // Few levels, so that ties are common; some infinite.
      exact[u] = level(rng) == 5 ? cell_order_detail::kInf : 10.0 * level(rng);
      known[u] = coin(rng) == 0;
      const int bound = coin(rng);  // the bound: exact, a little below, far below, zero
      value[u] = known[u] || bound == 0 ? exact[u]
                 : bound == 1           ? exact[u] - 5 * unit(rng)
                 : bound == 2           ? exact[u] / 4
                                        : 0.0;
    }
    std::pair<double, std::size_t> truth{cell_order_detail::kInf, 0};
    for (std::size_t u = 0; u < count; ++u)
      if (exact[u] < truth.first) truth = {exact[u], u};
    bool asked[4] = {false, false, false, false};
    const auto got = cell_order_detail::first_least(count, value, known, [&](std::size_t u) {
      EXPECT_FALSE(asked[u]) << "asked twice";
      asked[u] = true;
      return exact[u];
    });
    ASSERT_EQ(got.first, truth.first) << "trial " << trial;
    ASSERT_EQ(got.second, truth.second) << "trial " << trial;
    for (std::size_t u = 0; u < count; ++u)
      if (!known[u] && !asked[u]) ++skipped;
  }
  EXPECT_GT(skipped, 1000u);  // the bounds decided often: the check above saw skips
}

// The bounds the lazy searches decide by never exceed what they bound: for every transit and leg
// home of random problems (straight transits, where a bound is within rounding of the transit,
// and longer ones; with and without crossings), before and after it is asked, and least_through()
// over a layer never above the least of the exact sums (least_layer(), a layer at once, the same
// as least_through() variant by variant, before and after the transits are asked). An unsound
// bound would skip a transit that wins.
TEST(CellOrderSearch, TransitBoundsNeverExceedTheTransits) {
  std::mt19937_64 rng(5220);
  std::uniform_real_distribution<double> before_m(0, 3000);
  for (int k = 0; k < 8; ++k) {
    CellOrderProblem p = random_problem(rng, 6 + std::size_t(k), k % 4 == 1, k % 2 == 0);
    if (k % 4 >= 2)
      p.distance = [](geometry::Point2 a, geometry::Point2 b) {
        return std::abs(a.x - b.x) + std::abs(a.y - b.y);
      };
    p.distance_at_least_straight = true;
    cell_order_detail::Transit t(p);
    ASSERT_TRUE(t.bounded());
    const std::size_t n = p.cells.size();
    for (std::size_t c = 0; c < n; ++c)
      for (std::size_t v = 0; v < p.cells[c].size(); ++v) {
        const double low_in = t.low_from_home(c, v), low_out = t.low_to_home(c, v);
        ASSERT_FALSE(t.from_home_known(c, v));
        ASSERT_LE(low_in, p.distance(p.home, p.cells[c][v].entry));
        ASSERT_LE(low_out, p.distance(p.cells[c][v].exit, p.home));
        ASSERT_EQ(t.from_home(c, v), p.distance(p.home, p.cells[c][v].entry));
        ASSERT_TRUE(t.from_home_known(c, v));
        ASSERT_EQ(t.low_from_home(c, v), t.from_home(c, v));
      }
    for (std::size_t c1 = 0; c1 < n; ++c1)
      for (std::size_t c2 = 0; c2 < n; ++c2) {
        if (c1 == c2) continue;
        const std::uint64_t unflown = rng();
        // least_layer(): least_through() for every variant at once, with the first u (from the
        // bounds' tables, kept up to date as transits are asked: checked before and after).
        const auto same_layer = [&] {
          double before[4], layer[4];
          std::uint8_t came[4];
          for (double& b : before) b = before_m(rng);
          t.least_layer(before, c1, p.cells[c1].size(), c2, unflown, layer, came);
          for (std::size_t v2 = 0; v2 < p.cells[c2].size(); ++v2) {
            std::size_t u = 9;
            ASSERT_EQ(layer[v2], t.least_through(before, c1, p.cells[c1].size(), c2, v2, unflown,
                                                 p.cells[c2][v2].internal_m, &u));
            ASSERT_EQ(came[v2], u);
          }
        };
        same_layer();
        for (std::size_t v2 = 0; v2 < p.cells[c2].size(); ++v2) {
          double before[4];
          for (double& b : before) b = before_m(rng);
          const std::size_t count = p.cells[c1].size();
          const double internal = p.cells[c2][v2].internal_m;
          const double low_layer = t.least_through(before, c1, count, c2, v2, unflown, internal);
          double exact_layer = cell_order_detail::kInf;
          for (std::size_t v1 = 0; v1 < count; ++v1) {
            double low = 0;
            const bool known = t.cost_if_known(c1, v1, c2, v2, unflown, low);
            const double cost = t.cost(c1, v1, c2, v2, unflown);
            ASSERT_LE(low, cost) << "problem " << k;
            if (known) ASSERT_EQ(low, cost);
            ASSERT_TRUE(t.cost_if_known(c1, v1, c2, v2, unflown, low));
            ASSERT_EQ(low, cost);
            exact_layer = std::min(exact_layer, before[v1] + cost + internal);
          }
          ASSERT_LE(low_layer, exact_layer) << "problem " << k;
          ASSERT_EQ(t.least_through(before, c1, count, c2, v2, unflown, internal), exact_layer);
        }
        same_layer();
      }
  }
}

// A metric as a router's: the shortest way round a wall (a segment; the path bends at one of its
// ends where the straight leg crosses it), so never below the straight length and equal to it
// wherever the wall is not in the way (the bound then within rounding of the transit). The
// searches leave transits unasked where the straight bounds already decide (fill()'s layers,
// cannot_win()'s cheapest ways, the legs home): the same orders as the plain search's, bit for
// bit, on spread problems, on a grid and with variants repeated (ties), with and without
// crossings, and fewer transits asked than by the same search with the bounds unused (the same
// start: nearest neighbour on the grid; every transit a fill or a move looks at asked).
TEST(CellOrderSearch, TransitsRoundAWallAskedOnlyWhereTheBoundsCannotDecide) {
  std::mt19937_64 rng(5219);
  const auto crosses = [](geometry::Point2 a, geometry::Point2 b, geometry::Point2 c,
                          geometry::Point2 d) {
    const auto side = [](geometry::Point2 p, geometry::Point2 q, geometry::Point2 r) {
      const double s = geometry::cross(q - p, r - p);
      return (s > 0) - (s < 0);
    };
    return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
  };
#ifdef SWATH_SANITIZED
  const int problems = 4;
#else
  const int problems = 12;
#endif
  for (int k = 0; k < problems; ++k) {
    CellOrderProblem p = random_problem(rng, 10 + std::size_t(k) * 3, k % 3 != 0, k % 2 == 0);
    if (k % 3 == 2)  // variants repeated whole: equal costs through them, the first must win
      for (auto& cell : p.cells)
        for (std::size_t v = 1; v < cell.size(); ++v)
          if (rng() % 2) cell[v] = cell[rng() % v];
    const geometry::Point2 w0{-300.0 + 20 * k, -50}, w1{250, 350.0 - 10 * k};
    std::set<std::array<double, 4>>* asked = nullptr;
    p.distance = [&](geometry::Point2 a, geometry::Point2 b) {
      if (asked) asked->insert({a.x, a.y, b.x, b.y});
      if (!crosses(a, b, w0, w1)) return geometry::distance(a, b);
      return std::min(geometry::distance(a, w0) + geometry::distance(w0, b),
                      geometry::distance(a, w1) + geometry::distance(w1, b));
    };
    const CellOrder truth = PlainSearch{p}.heuristic();
    p.distance_at_least_straight = true;
    std::set<std::array<double, 4>> eager, lazy;
    asked = &eager;
    cell_order_detail::Transit every(p, true, false);
    ASSERT_FALSE(every.bounded());
    const CellOrder plain = cell_order_detail::heuristic_cell_order(p, every);
    asked = &lazy;
    const CellOrder fast = heuristic_cell_order(p);
    asked = nullptr;
    for (const CellOrder* o : {&plain, &fast}) {
      ASSERT_EQ(o->objective_m, truth.objective_m) << "problem " << k;
      ASSERT_EQ(o->visits.size(), truth.visits.size());
      for (std::size_t i = 0; i < truth.visits.size(); ++i) {
        ASSERT_EQ(o->visits[i].cell, truth.visits[i].cell) << "problem " << k << " at " << i;
        ASSERT_EQ(o->visits[i].variant, truth.visits[i].variant);
      }
    }
    EXPECT_LT(lazy.size(), eager.size()) << "problem " << k;
  }
}

// Cells as a split's sweeps make them: a run of one lane flown either way (its exit the other
// variant's entry), a cell of two lanes with four variants whose ends are the lanes' ends, a few
// ends shared between cells and one at home. A metric symmetric bit for bit (the way round a
// wall, as a router's: the same sums either way) and crossings of the pair of ends.
CellOrderProblem runs_problem(std::mt19937_64& rng, std::size_t n, bool crossings) {
  std::uniform_real_distribution<double> coordinate(-500, 500);
  CellOrderProblem p;
  p.home = {-600, -600};
  std::vector<geometry::Point2> ends;
  const auto point = [&] {
    if (!ends.empty() && rng() % 8 == 0) return ends[rng() % ends.size()];
    if (rng() % 40 == 0) return p.home;
    ends.push_back({coordinate(rng), coordinate(rng)});
    return ends.back();
  };
  for (std::size_t c = 0; c < n; ++c) {
    const geometry::Point2 a0 = point(), b0 = point();
    const double lane0 = geometry::distance(a0, b0);
    if (rng() % 3 != 0) {
      p.cells.push_back({{a0, b0, lane0}, {b0, a0, lane0}});
      continue;
    }
    const geometry::Point2 a1 = point(), b1 = point();
    const double inside = lane0 + geometry::distance(a1, b1) + 50;
    p.cells.push_back({{a0, a1, inside}, {b0, b1, inside}, {a1, a0, inside}, {b1, b0, inside}});
  }
  const geometry::Point2 w0{-300, -50}, w1{250, 350};
  const auto side = [](geometry::Point2 o, geometry::Point2 q, geometry::Point2 r) {
    const double x = geometry::cross(q - o, r - o);
    return (x > 0) - (x < 0);
  };
  p.distance = [=](geometry::Point2 a, geometry::Point2 b) {
    if (side(a, b, w0) * side(a, b, w1) >= 0 || side(w0, w1, a) * side(w0, w1, b) >= 0)
      return geometry::distance(a, b);
    return std::min(geometry::distance(a, w0) + geometry::distance(w0, b),
                    geometry::distance(a, w1) + geometry::distance(w1, b));
  };
  if (crossings)
    p.crossed = [](geometry::Point2 a, geometry::Point2 b) {
      if (std::pair{b.x, b.y} < std::pair{a.x, a.y}) std::swap(a, b);
      const auto h = std::hash<double>{}(a.x * 3 + b.y) ^ std::hash<double>{}(a.y - 7 * b.x);
      return std::uint64_t(h) & (std::uint64_t(h) >> 7) & 0x7fffffffffffffffull;
    };
  p.distance_at_least_straight = true;
  return p;
}

// With a symmetric metric a transit's answer is written into its twins (the same pair of points
// either way round, the legs from and to home at one point): every entry the table then holds is
// the metric's own answer (asked here of the metric afresh for every entry, ends and legs home),
// after a search and after transits asked at random.
TEST(CellOrderSearch, SymmetricTransitsSharedWithTheirTwinsAreTheMetricsAnswers) {
  std::mt19937_64 rng(5252);
  for (int k = 0; k < 12; ++k) {
    CellOrderProblem p = runs_problem(rng, 8 + std::size_t(k) * 4, k % 2 == 0);
    p.symmetric = true;
    cell_order_detail::Transit t(p);
    if (k % 3 == 0) {
      (void)cell_order_detail::heuristic_cell_order(p, t);
    } else {
      for (int ask = 0; ask < 60; ++ask) {
        const std::size_t c1 = rng() % p.cells.size(), c2 = rng() % p.cells.size();
        const std::size_t v1 = rng() % p.cells[c1].size(), v2 = rng() % p.cells[c2].size();
        if (rng() % 4 == 0)
          (void)(rng() % 2 ? t.from_home(c1, v1) : t.to_home(c2, v2));
        else
          (void)t.cost(c1, v1, c2, v2, rng());
      }
    }
    std::size_t known = 0, entries = 0;
    for (std::size_t c1 = 0; c1 < p.cells.size(); ++c1)
      for (std::size_t v1 = 0; v1 < p.cells[c1].size(); ++v1) {
        const CellVariant& from = p.cells[c1][v1];
        if (t.from_home_known(c1, v1))
          ASSERT_EQ(t.low_from_home(c1, v1), p.distance(p.home, from.entry)) << "problem " << k;
        if (t.to_home_known(c1, v1))
          ASSERT_EQ(t.low_to_home(c1, v1), p.distance(from.exit, p.home)) << "problem " << k;
        for (std::size_t c2 = 0; c2 < p.cells.size(); ++c2)
          for (std::size_t v2 = 0; v2 < p.cells[c2].size(); ++v2) {
            const CellVariant& to = p.cells[c2][v2];
            const std::uint64_t unflown = rng();
            double cost = 0;
            ++entries;
            if (!t.cost_if_known(c1, v1, c2, v2, unflown, cost)) continue;
            ++known;
            const double d = p.distance(from.exit, to.entry);
            const double truth =
                p.crossed ? cell_order_detail::penalised(d, p.crossing_weight,
                                                         p.crossed(from.exit, to.entry) & unflown)
                          : d;
            ASSERT_EQ(cost, truth) << "problem " << k;
          }
      }
    EXPECT_GT(known, 0u) << "problem " << k;
    EXPECT_LT(known, entries) << "problem " << k;
  }
}

// A symmetric problem's orders are the plain search's bit for bit (and those of the search that
// asks each entry for itself), asking the metric fewer times: on runs and two-lane cells with
// shared ends, routed-like transits round a wall, with and without crossings.
TEST(CellOrderSearch, SymmetricTransitsAskedOnceAPairKeepThePlainSearch) {
  std::mt19937_64 rng(5253);
#ifdef SWATH_SANITIZED
  const int problems = 4;
#else
  const int problems = 12;
#endif
  for (int k = 0; k < problems; ++k) {
    CellOrderProblem p = runs_problem(rng, 10 + std::size_t(k) * 3, k % 2 == 0);
    const CellOrder truth = PlainSearch{p}.heuristic();
    std::size_t calls = 0;
    const auto metric = p.distance;
    p.distance = [&](geometry::Point2 a, geometry::Point2 b) {
      ++calls;
      return metric(a, b);
    };
    const CellOrder each = heuristic_cell_order(p);
    const std::size_t calls_each = calls;
    calls = 0;
    p.symmetric = true;
    const CellOrder shared = heuristic_cell_order(p);
    for (const CellOrder* o : {&each, &shared}) {
      ASSERT_EQ(o->objective_m, truth.objective_m) << "problem " << k;
      ASSERT_EQ(o->visits.size(), truth.visits.size());
      for (std::size_t i = 0; i < truth.visits.size(); ++i) {
        ASSERT_EQ(o->visits[i].cell, truth.visits[i].cell) << "problem " << k << " at " << i;
        ASSERT_EQ(o->visits[i].variant, truth.visits[i].variant);
      }
    }
    EXPECT_LT(calls, calls_each) << "problem " << k;
  }
}

// The cells 0..n-1 in a random order.
std::vector<std::size_t> shuffled_cells(std::size_t n, std::mt19937_64& rng) {
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  return order;
}

// The local search's bounds for a block moved to j + 1 keep the layers of the move to j up to
// j - 2 (the same cells there, the same cells after each) where the current order is the same and
// no transit was asked since. Checked against the bounds filled afresh, each on its own memo of
// the same problem: the same verdict, the same transits asked and the same layer rejecting the
// move, move after move (one asked differently or a move rejected at another layer shows layers
// that differ; a move's layers stop where one shows it cannot win), for blocks of 1-3 cells moved
// to every j, with and without crossings, transits round a wall, verdicts both ways (objectives to
// beat below and above the current one).
TEST(CellOrderSearch, KeptBoundLayersAreTheFreshOnes) {
  std::mt19937_64 rng(5254);
  std::size_t reused = 0, rejected = 0, kept_open = 0;
  for (int k = 0; k < 16; ++k) {
    CellOrderProblem p = runs_problem(rng, 12 + std::size_t(k), k % 2 == 0);
    p.symmetric = k % 3 == 0;
    const std::size_t n = p.cells.size();
    std::vector<std::size_t> order = shuffled_cells(n, rng);
    cell_order_detail::Transit kept_t(p), fresh_t(p);
    cell_order_detail::VariantTable kept_current, fresh_current;
    const double objective = kept_current.fill(p, kept_t, order, 0);
    ASSERT_EQ(fresh_current.fill(p, fresh_t, order, 0), objective);
    kept_current.suffix(p, kept_t, order);
    fresh_current.suffix(p, fresh_t, order);
    std::uniform_real_distribution<double> beat(0.85, 1.02);
    for (int round = 0; round < 12; ++round) {
      const std::size_t len = 1 + rng() % 3, i = rng() % (n - len);
      const double give_up_m = objective * beat(rng);
      cell_order_detail::VariantTable kept, fresh;
      cell_order_detail::KeptLayers layers;  // the rule local_search() keeps layers by
      for (std::size_t j = i + len; j + len <= n; ++j) {
        const std::vector<std::size_t> candidate = PlainSearch::moved(order, 0, i, j, len);
        ASSERT_FALSE(candidate.empty());
        const std::size_t changed_end = j + len, check_at = std::min(changed_end, n - 1);
        if (i >= check_at) continue;
        const std::size_t kept_to = layers.next(i, j, kept_t.asked(), 0);
        reused += kept_to > i;
        kept.keep_layers_of(kept_current, i);
        fresh.keep_layers_of(fresh_current, i);
        const bool no = kept.cannot_win(p, kept_t, candidate, i, check_at, give_up_m,
                                        changed_end < n ? &kept_current : nullptr, kept_to);
        const bool fresh_no = fresh.cannot_win(p, fresh_t, candidate, i, check_at, give_up_m,
                                               changed_end < n ? &fresh_current : nullptr);
        ASSERT_EQ(no, fresh_no) << "problem " << k << " i " << i << " j " << j;
        ASSERT_EQ(kept_t.asked(), fresh_t.asked()) << "problem " << k << " i " << i << " j " << j;
        // Rejected at the same layer: a move's layers stop where one shows it cannot win, and
        // the next move keeps only those filled.
        ASSERT_EQ(kept.low_end(), fresh.low_end()) << "problem " << k << " i " << i << " j " << j;
        (no ? rejected : kept_open) += 1;
      }
    }
  }
  EXPECT_GT(reused, 100u);
  EXPECT_GT(rejected, 0u);
  EXPECT_GT(kept_open, 0u);
}

// The bound on a step of an order from cell c1 into cell c2 (Transit::least_step(): the transit
// from c1's exit and the internal length of the variant it enters) against every such step as the
// metric answers it, with its penalty for random cells still to be flown, before and after the
// transits are asked (the memo's values never lower it); and never below the bound it sharpens
// (the least transit into c2 from any cell, plus c2's least internal length). Transits round a
// wall (straight where it is not in the way: the bound within rounding of the step), with and
// without crossings, symmetric twins or not, and cells whose variants repeat (ties).
TEST(CellOrderSearch, LeastStepBoundsEveryStepBetweenTwoCells) {
  std::mt19937_64 rng(5257);
  std::size_t sharper = 0;
  for (int k = 0; k < 12; ++k) {
    CellOrderProblem p = runs_problem(rng, 6 + std::size_t(k), k % 2 == 0);
    p.symmetric = k % 3 == 0;
    if (k % 4 == 3)
      for (auto& cell : p.cells)
        for (std::size_t v = 1; v < cell.size(); ++v)
          if (rng() % 2) cell[v] = cell[rng() % v];
    const std::size_t n = p.cells.size();
    cell_order_detail::Transit t(p);
    ASSERT_TRUE(t.bounded());
    for (int asked = 0; asked < 2; ++asked)
      for (std::size_t c1 = 0; c1 < n; ++c1)
        for (std::size_t c2 = 0; c2 < n; ++c2) {
          if (c1 == c2) continue;
          const double step = t.least_step(c1, c2);
          ASSERT_GE(step, t.least_into(c2) + t.least_internal(c2));
          // Exactly the least straight bound (less 1e-12 of it) plus the internal length
          // entered, over every pair of their variants, whatever has been asked since.
          double least = std::numeric_limits<double>::infinity();
          for (const CellVariant& from : p.cells[c1])
            for (const CellVariant& to : p.cells[c2])
              least = std::min(
                  least, geometry::distance(from.exit, to.entry) * (1 - 1e-12) + to.internal_m);
          ASSERT_EQ(step, least) << "problem " << k << " cells " << c1 << " " << c2;
          sharper += asked == 0 && step > t.least_into(c2) + t.least_internal(c2);
          for (std::size_t u = 0; u < p.cells[c1].size(); ++u)
            for (std::size_t v = 0; v < p.cells[c2].size(); ++v) {
              const CellVariant &from = p.cells[c1][u], &to = p.cells[c2][v];
              ASSERT_LE(step, p.distance(from.exit, to.entry) + to.internal_m)
                  << "problem " << k << " cells " << c1 << " " << c2;
              ASSERT_LE(step, t.cost(c1, u, c2, v, rng()) + to.internal_m);  // asked now
            }
        }
  }
  EXPECT_GT(sharper, 100u);
}

// Where the pairs' bounds are not kept, least_step() falls back to the bound it sharpens: more
// than 320 variants in all (the scan of every pair is quadratic), and into or out of a cell
// without variants (no way through it to bound).
TEST(CellOrderSearch, LeastStepFallsBackWhereNoPairIsKept) {
  std::mt19937_64 rng(5258);
  CellOrderProblem many = runs_problem(rng, 170, false);  // 2-4 variants a cell: > 320 in all
  std::size_t variants = 0;
  for (const auto& cell : many.cells) variants += cell.size();
  ASSERT_GT(variants, 320u);
  cell_order_detail::Transit t(many);
  ASSERT_TRUE(t.bounded());
  for (std::size_t c1 = 0; c1 < many.cells.size(); c1 += 7)
    for (std::size_t c2 = 0; c2 < many.cells.size(); c2 += 5)
      if (c1 != c2) ASSERT_EQ(t.least_step(c1, c2), t.least_into(c2) + t.least_internal(c2));
  CellOrderProblem empty = runs_problem(rng, 8, true);
  empty.cells[3].clear();
  cell_order_detail::Transit e(empty);
  ASSERT_TRUE(e.bounded());
  for (std::size_t c = 0; c < empty.cells.size(); ++c) {
    if (c == 3) continue;
    EXPECT_EQ(e.least_step(3, c), e.least_into(c) + e.least_internal(c));
    EXPECT_EQ(e.least_step(c, 3), e.least_into(3) + e.least_internal(3));
  }
}

// The local search rejects most moves a few layers in: once a layer's least cost plus a bound on
// what any way pays after it (for each later cell the least step into it from the cell before it,
// Transit::least_step(); then the least of the tail's costs) reaches the objective to beat, and
// some before any layer (the least of the current order's layer before the move, the step into
// its first changed cell and the rest). Those bounds never exceed what they bound (every transit,
// as the metric answers it, and every internal length), and a move cannot_win() rejects, early or
// not, is never one whose objective (the plain search's, every transit asked) is below the
// objective to beat: checked with that objective a hair above the candidate's own (it must not be
// rejected), at it and below it (it may), for every kind of move, with and without crossings,
// transits round a wall, symmetric twins or not.
TEST(CellOrderSearch, MovesRejectedBeforeTheirLastLayerCannotWin) {
  std::mt19937_64 rng(5256);
  std::size_t early = 0, before_any = 0, rejected = 0, kept_open = 0;
  for (int k = 0; k < 16; ++k) {
    CellOrderProblem p = runs_problem(rng, 10 + std::size_t(k), k % 2 == 0);
    p.symmetric = k % 3 == 0;
    const std::size_t n = p.cells.size();
    cell_order_detail::Transit t(p);
    ASSERT_TRUE(t.bounded());
    for (std::size_t c2 = 0; c2 < n; ++c2)
      for (const CellVariant& to : p.cells[c2]) {
        ASSERT_LE(t.least_internal(c2), to.internal_m);
        for (std::size_t c1 = 0; c1 < n; ++c1)
          for (const CellVariant& from : p.cells[c1])
            if (c1 != c2) ASSERT_LE(t.least_into(c2), p.distance(from.exit, to.entry));
      }
    const std::vector<std::size_t> order = shuffled_cells(n, rng);
    cell_order_detail::VariantTable current;
    current.fill(p, t, order, 0);
    current.suffix(p, t, order);
    const PlainSearch plain{p};
    for (int round = 0; round < 60; ++round) {
      const int move = int(rng() % 3);
      const std::size_t len = move == 0 ? 1 + rng() % 3 : 1, i = rng() % n, j = rng() % n;
      const std::vector<std::size_t> candidate = PlainSearch::moved(order, move, i, j, len);
      if (candidate.empty() || i == j) continue;
      const std::size_t changed_end = move == 0 ? std::max(i, j) + len : j + 1;
      const std::size_t from = std::min(i, j), check_at = std::min(changed_end, n - 1);
      if (from >= check_at) continue;
      const double truth = plain.variants(candidate).objective_m;
      const double beat[] = {truth * (1 + 1e-7), truth, truth * 0.999, truth * 0.97};
      const double give_up_m = beat[rng() % 4];
      cell_order_detail::VariantTable trial;
      trial.keep_layers_of(current, from);
      const bool no = trial.cannot_win(p, t, candidate, from, check_at, give_up_m,
                                       changed_end < n ? &current : nullptr);
      if (no)
        ASSERT_GE(truth, give_up_m) << "problem " << k << " move " << move << " " << i << " to "
                                    << j << " rejected at " << trial.low_end();
      (no ? rejected : kept_open) += 1;
      early += no && trial.low_end() <= check_at;
      before_any += no && trial.low_end() == from;
    }
  }
  EXPECT_GT(early, 50u);
  EXPECT_GT(before_any, 10u);
  EXPECT_GT(rejected, early);
  EXPECT_GT(kept_open, 50u);
}

// After a kept move, the local search's suffix costs at the positions the move left as they were
// (the same cells from there on) are copied from the order before, the rest computed: the same
// values, bit for bit, as the new order's suffix computed whole (each on its own memo), for every
// kind of move, with and without crossings, transits round a wall, and with transits asked in
// between (exact leasts whatever the memo holds).
TEST(CellOrderSearch, SuffixKeptFromTheOrderBeforeIsTheWholeOne) {
  std::mt19937_64 rng(5255);
  std::size_t copied = 0;
  for (int k = 0; k < 24; ++k) {
    CellOrderProblem p = runs_problem(rng, 9 + std::size_t(k), k % 2 == 0);
    p.symmetric = k % 3 == 0;
    const std::size_t n = p.cells.size();
    std::vector<std::size_t> order = shuffled_cells(n, rng);
    cell_order_detail::Transit kept_t(p), whole_t(p);
    cell_order_detail::VariantTable before, after, whole;
    before.suffix(p, kept_t, order);
    for (int ask = 0; ask < 20 && k % 4 == 1; ++ask)  // more known since
      (void)kept_t.cost(rng() % n, 0, rng() % n, 0, rng());
    std::vector<std::size_t> moved;
    const int move = int(rng() % 3);
    std::size_t i = 0, j = 0, len = 1 + (move == 0 ? rng() % 3 : 0);
    while (moved.empty() || i == j) {
      i = rng() % n;
      j = rng() % n;
      moved = PlainSearch::moved(order, move, i, j, len);
    }
    const std::size_t same_from = move == 0 ? std::max(i, j) + len : j + 1;
    for (std::size_t x = same_from; x < n; ++x) ASSERT_EQ(moved[x], order[x]);
    after.suffix(p, kept_t, moved, &before, same_from);
    whole.suffix(p, whole_t, moved);
    copied += n - std::min(n, same_from);
    for (std::size_t x = 0; x < n; ++x)
      for (std::size_t v = 0; v < p.cells[moved[x]].size(); ++v)
        ASSERT_EQ(after.rest_cost(x, v), whole.rest_cost(x, v))
            << "problem " << k << " at " << x << " (same from " << same_from << ")";
  }
  EXPECT_GT(copied, 50u);
}

}  // namespace
}  // namespace swath::planning

// VisibilityRouter builds its graph and tests what a path's ends see lazily, goes on from a corner
// only the way a shortest path can (round it), and stops its search as soon as the path is proven
// shortest. Its paths must be as short as the eager computation's: checked against that
// computation written out over every edge (every corner's view of every corner, a full Dijkstra
// from the start, the best last corner over all corners), on random areas with holes (fixed
// seeds), integer grids full of collinear edges, combs and spirals, for ends on vertices, on
// edges, in line with vertices and at random, asked in random order so that searches are resumed
// from every depth. With a corner allowance, the path stays inside and is at most 2 allowances a
// bend longer. Big outlines (thousands of reflex vertices) are routed, inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <random>
#include <thread>

#include "brute_area.hpp"
#include "random_polygons.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/visibility.hpp"

namespace swath::geometry {
namespace {

// The router before the lazy search, over every edge of every ring: the truth.
class EagerRouter {
 public:
  // The graph of the reflex corners, each moved by the allowance as the router does.
  explicit EagerRouter(std::vector<Ring> rings, double allowance_m = 0)
      : rings_(std::move(rings)), area_(rings_) {
    for (const Ring& ring : rings_) {
      const std::size_t n = ring.size();
      for (std::size_t i = 0; i < n; ++i)
        if (orientation(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) ==
            Orientation::clockwise)
          nodes_.push_back(
              moved_out(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n], allowance_m));
    }
    adjacent_.resize(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      for (std::size_t j = i + 1; j < nodes_.size(); ++j)
        if (visible(nodes_[i], nodes_[j])) {
          const double w = distance(nodes_[i], nodes_[j]);
          adjacent_[i].push_back({j, w});
          adjacent_[j].push_back({i, w});
        }
  }

  std::vector<Point2> path(Point2 a, Point2 b) {
    if (visible(a, b)) return {a, b};
    const std::size_t n = nodes_.size();
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    std::vector<std::size_t> previous(n, n);
    using Item = std::pair<double, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    const std::vector<char>& from_a = sees(a);
    for (std::size_t i = 0; i < n; ++i)
      if (from_a[i]) {
        dist[i] = distance(a, nodes_[i]);
        queue.push({dist[i], i});
      }
    while (!queue.empty()) {
      const auto [d, u] = queue.top();
      queue.pop();
      if (d > dist[u]) continue;
      for (const auto& [v, w] : adjacent_[u])
        if (d + w < dist[v]) {
          dist[v] = d + w;
          previous[v] = u;
          queue.push({dist[v], v});
        }
    }
    const std::vector<char>& to_b = sees(b);
    std::size_t last = n;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      if (to_b[i] && dist[i] + distance(nodes_[i], b) < best) {
        best = dist[i] + distance(nodes_[i], b);
        last = i;
      }
    if (last == n) return {a, b};
    std::vector<Point2> route{b};
    for (std::size_t v = last; v != n; v = previous[v]) route.push_back(nodes_[v]);
    route.push_back(a);
    std::reverse(route.begin(), route.end());
    return route;
  }

  std::size_t nodes() const { return nodes_.size(); }

 private:
  bool contains(Point2 p) const { return area_.contains(p); }
  bool visible(Point2 a, Point2 b) const { return area_.visible(a, b); }
  Point2 moved_out(Point2 before, Point2 corner, Point2 after, double allowance_m) const {
    if (!(allowance_m > 0)) return corner;
    const Point2 u = before - corner, v = after - corner;
    const double nu = std::hypot(u.x, u.y), nv = std::hypot(v.x, v.y);
    if (nu == 0 || nv == 0) return corner;
    Point2 out = (u * (1 / nu) + v * (1 / nv)) * -1.0;
    const double len = std::hypot(out.x, out.y);
    if (len < 1e-12) return corner;
    const Point2 moved = corner + out * (allowance_m / len);
    if (contains(moved) && visible(moved, corner + u * 0.5) && visible(moved, corner + v * 0.5))
      return moved;
    return corner;
  }
  const std::vector<char>& sees(Point2 p) {
    auto [it, added] = sees_.try_emplace({p.x, p.y});
    if (added)
      for (const Point2& node : nodes_) it->second.push_back(visible(p, node));
    return it->second;
  }

  std::vector<Ring> rings_;
  test::BruteArea area_;
  std::vector<Point2> nodes_;
  std::vector<std::vector<std::pair<std::size_t, double>>> adjacent_;
  std::map<std::pair<double, double>, std::vector<char>> sees_;
};

// `path` runs from a to b inside the area (each leg by the brute-force area), and is as long as
// the full search's `truth` (without an allowance; with one, at most 2 allowances a bend longer);
// no path where the full search has none.
void expect_as_short(const test::BruteArea& area, const std::vector<Point2>& path,
                     const std::vector<Point2>& truth, Point2 a, Point2 b, double allowance_m) {
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path.front(), a);
  EXPECT_EQ(path.back(), b);
  if (truth.size() == 2 && !area.visible(a, b)) {  // no inside path: the straight leg
    EXPECT_EQ(path.size(), 2u);
    return;
  }
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    EXPECT_LE(area.length_outside(path[i], path[i + 1]), 1e-6) << "leg " << i;
  const double length = polyline_length(path), shortest = polyline_length(truth);
  const double rounding = 1e-9 * (1 + shortest);
  EXPECT_GE(length, shortest - rounding);
  EXPECT_LE(length, shortest + 2 * allowance_m * double(path.size() - 2) + rounding);
}

// A field with holes: rectangles on a grid (corners in line with each other: collinear legs and
// equal-length detours) and small random stars, clockwise.
std::vector<Ring> search_holey_area(test::Rng& rng, std::size_t n, int holes) {
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

// Path ends: vertices, points on edges (as lanes end), points in line with a vertex (through
// corners), the midpoints of rectangle sides, and random points (some outside).
std::vector<Point2> path_ends(test::Rng& rng, const std::vector<Ring>& rings, int count) {
  std::vector<Point2> vertices;
  std::vector<std::pair<Point2, Point2>> edges;
  double extent = 0;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      vertices.push_back(ring[i]);
      edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
      extent = std::max({extent, std::abs(ring[i].x), std::abs(ring[i].y)});
    }
  std::uniform_real_distribution<double> unit(0, 1), coordinate(-extent, extent);
  std::uniform_int_distribution<std::size_t> vertex(0, vertices.size() - 1),
      edge(0, edges.size() - 1);
  std::vector<Point2> out;
  for (int k = 0; k < count; ++k) {
    switch (k % 5) {
      case 0:
        out.push_back(vertices[vertex(rng)]);
        break;
      case 1: {
        const auto& [a, b] = edges[edge(rng)];
        out.push_back(a + (b - a) * unit(rng));
        break;
      }
      case 2: {
        const Point2 v = vertices[vertex(rng)];
        out.push_back(k % 2 ? Point2{coordinate(rng), v.y} : Point2{v.x, coordinate(rng)});
        break;
      }
      case 3: {
        const auto& [a, b] = edges[edge(rng)];
        out.push_back((a + b) * 0.5);
        break;
      }
      default:
        out.push_back({coordinate(rng), coordinate(rng)});
    }
  }
  return out;
}

// Under the sanitizers (CI's second pass looks for memory errors, not for every path) an eighth of
// the queries: the same areas and allowances.
#ifdef SWATH_SANITIZED
constexpr int kQueries = 150;
#else
constexpr int kQueries = 1200;
#endif

TEST(VisibilityRouterSearch, PathsAreAsShortAsTheFullSearchs) {
  test::Rng rng(1818);
  std::size_t bent = 0;
  for (int area = 0; area < 10; ++area) {
    std::vector<Ring> rings;
    switch (area % 5) {
      case 0:
      case 1:
        rings = search_holey_area(rng, std::size_t(12) << area % 3, 6 + 7 * area);
        break;
      case 2:
        rings = {test::random_grid_ring(rng, 24, 10)};
        break;
      case 3:
        rings = {test::comb_polygon(6, 10, 40, 10)};
        break;
      default:
        rings = {test::spiral_polygon(5, 200, 40, 10)};
    }
    const test::BruteArea brute(rings);
    for (const double allowance_m : {0.0, 2.0}) {
      EagerRouter eager(rings, allowance_m);
      const VisibilityRouter router(rings, Routing::routed, allowance_m);
      ASSERT_TRUE(router.routes());
      const std::vector<Point2> points = path_ends(rng, rings, 60);
      std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
      for (int q = 0; q < kQueries; ++q) {
        const Point2 a = points[pick(rng)], b = points[pick(rng)];
        const std::vector<Point2> lazy = router.path(a, b), truth = eager.path(a, b);
        SCOPED_TRACE(::testing::Message()
                     << "area " << area << " allowance " << allowance_m << " (" << a.x << ", "
                     << a.y << ") - (" << b.x << ", " << b.y << ")");
        // Without an allowance the search is pruned (ties may go another way): as short. With
        // one, the full A* over the moved bends: bit for bit the full Dijkstra's path.
        if (allowance_m > 0)
          ASSERT_EQ(lazy, truth);
        else
          expect_as_short(brute, lazy, truth, a, b, 0.0);
        if (::testing::Test::HasFailure()) return;
        bent += truth.size() > 2;
      }
    }
  }
  // Most queries are routed around something, not straight.
  EXPECT_GT(bent, std::size_t(3000) * kQueries / 1200);
}

// Areas of hundreds of corners for the groups' tests (area 0 to 2): 300- and 450-vertex outlines
// with 8 and 16 holes (several 64-node words, groups near and far), then a 40-tooth comb (paths
// far longer than a first run's limit).
std::vector<Ring> hundreds_of_corners(test::Rng& rng, int area) {
  if (area == 2) return {test::comb_polygon(40, 10, 60, 10)};
  return search_holey_area(rng, std::size_t(300 + 150 * area), 8 + 8 * area);
}

// With a corner allowance, a node settled skips the open nodes in groups whose box puts every leg
// into them above the search's cut, and folds them into the next limit only after a run without an
// answer. Outlines of hundreds of corners (several 64-node words, groups near and far) and a comb
// (paths far longer than the first run's limit), ends of every kind: bit for bit the full
// Dijkstra's.
TEST(VisibilityRouterSearch, OutlinesOfHundredsOfCornersAreRoutedAsByTheFullSearch) {
  test::Rng rng(1825);
  std::size_t bent = 0;
  for (int area = 0; area < 3; ++area) {
    const std::vector<Ring> rings = hundreds_of_corners(rng, area);
    const VisibilityRouter router(rings, Routing::routed, 2.0);
    EagerRouter eager(rings, 2.0);
    EXPECT_GT(eager.nodes(), 64u) << area;
    const std::vector<Point2> points = path_ends(rng, rings, 50);
    std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
    for (int q = 0; q < kQueries / 6; ++q) {
      const Point2 a = points[pick(rng)], b = points[pick(rng)];
      const std::vector<Point2> lazy = router.path(a, b), truth = eager.path(a, b);
      ASSERT_EQ(lazy, truth) << "area " << area << " (" << a.x << ", " << a.y << ") - (" << b.x
                             << ", " << b.y << ")";
      bent += truth.size() > 2;
    }
  }
  EXPECT_GT(bent, std::size_t(kQueries / 10));
}

}  // namespace

// One run of path()'s search (private: the groups' bounds on or off), for the test below.
struct VisibilityRouterSearchProbe {
  static VisibilityRouter::SearchRun run(const VisibilityRouter& r, Point2 a, Point2 b,
                                         double limit, bool groups) {
    return r.search_run(a, b, limit, groups);
  }
  /// How many pairs of graph nodes the router has tested for sight so far.
  static std::size_t pairs_tested(const VisibilityRouter& r) {
    std::size_t tested = 0;
    for (std::size_t i = 0; i < r.nodes_.size(); ++i)
      for (std::size_t j = i + 1; j < r.nodes_.size(); ++j)
        tested += r.nodes_known(i, j) != VisibilityRouter::kUnknown;
    return tested;
  }
};

namespace {

// The groups' bounds leave legs above the cut unmeasured, folded into the least f left out only
// after a run without an answer. Runs under limits from the straight leg's length to twice it,
// with the bounds and without (every leg measured), on two routers of the same area (their tables
// fill alike): the same answer, or none and the same least f left out, bit for bit.
TEST(VisibilityRouterSearch, GroupsLeaveOutWhatMeasuringEveryLegLeavesOut) {
  test::Rng rng(1826);
  std::size_t unanswered = 0;
  for (int area = 0; area < 3; ++area) {
    const std::vector<Ring> rings = hundreds_of_corners(rng, area);
    const VisibilityRouter fast(rings, Routing::routed, 2.0), full(rings, Routing::routed, 2.0);
    const std::vector<Point2> points = path_ends(rng, rings, 50);
    std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
    for (int q = 0; q < kQueries / 4; ++q) {
      const Point2 a = points[pick(rng)], b = points[pick(rng)];
      const double limit = distance(a, b) * (1 + 0.1 * double(q % 11));
      const auto x = VisibilityRouterSearchProbe::run(fast, a, b, limit, true),
                 y = VisibilityRouterSearchProbe::run(full, a, b, limit, false);
      SCOPED_TRACE(::testing::Message() << "area " << area << " (" << a.x << ", " << a.y << ") - ("
                                        << b.x << ", " << b.y << ") limit " << limit);
      ASSERT_EQ(x.answered, y.answered);
      ASSERT_EQ(x.left_out, y.left_out);
      if (x.answered) {
        ASSERT_EQ(x.last, y.last);
      } else {
        ASSERT_EQ(x.beyond, y.beyond);
        unanswered += x.beyond < std::numeric_limits<double>::infinity();
      }
    }
  }
  EXPECT_GT(unanswered, std::size_t(kQueries / 8));
}

// A point clearly outside the area (a line end past the outline by its turnaround) sees no corner,
// so no inside path reaches it: the straight leg, as the full search says, and known at once. The
// lazy search from an inside point settled every corner first, testing the sight between them
// (with turnarounds on a 3,000-vertex outline, 45 s a plan); now it tests none.
TEST(VisibilityRouterSearch, APointClearlyOutsideIsAnsweredWithoutASearch) {
  test::Rng rng(1827);
  const std::vector<Ring> rings = hundreds_of_corners(rng, 0);
  const VisibilityRouter router(rings, Routing::routed, 2.0);
  EagerRouter eager(rings, 2.0);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Point2& p : rings[0])
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  std::uniform_real_distribution<double> along(0, 1), beyond_m(1, 20);
  std::vector<Point2> inside = path_ends(rng, rings, 40);
  std::erase_if(inside, [&](Point2 p) { return !router.contains(p); });
  ASSERT_GT(inside.size(), 20u);
  for (int q = 0; q < 40; ++q) {
    // Beyond each side of the outline's box in turn.
    const double u = along(rng), d = beyond_m(rng);
    const Point2 outside = q % 4 == 0   ? Point2{x0 - d, y0 + u * (y1 - y0)}
                           : q % 4 == 1 ? Point2{x1 + d, y0 + u * (y1 - y0)}
                           : q % 4 == 2 ? Point2{x0 + u * (x1 - x0), y0 - d}
                                        : Point2{x0 + u * (x1 - x0), y1 + d};
    const Point2 a = inside[std::size_t(q) % inside.size()];
    const std::vector<Point2> straight{a, outside};
    EXPECT_EQ(router.path(a, outside), straight) << q;
    EXPECT_EQ(eager.path(a, outside), straight) << q;
  }
  EXPECT_EQ(VisibilityRouterSearchProbe::pairs_tested(router), 0u);
}

// A fresh copy (another thread's router) answers as the original, whatever the original has been
// asked before: the same paths bit for bit, asked in a different order.
TEST(VisibilityRouterSearch, AFreshCopyGivesTheSamePaths) {
  test::Rng rng(1820);
  for (int area = 0; area < 3; ++area) {
    const std::vector<Ring> rings = search_holey_area(rng, std::size_t(24) << area, 10 + 9 * area);
    const VisibilityRouter router(rings, Routing::routed, 1.5);
    const std::vector<Point2> points = path_ends(rng, rings, 40);
    std::vector<std::vector<Point2>> first;
    for (std::size_t i = 0; i < points.size(); ++i)
      first.push_back(router.path(points[i], points[(i * 7 + 3) % points.size()]));
    const std::unique_ptr<VisibilityRouter> copy = router.fresh_copy();
    ASSERT_TRUE(copy->routes());
    std::size_t bent = 0;
    for (std::size_t i = points.size(); i-- > 0;) {
      const std::vector<Point2> again = copy->path(points[i], points[(i * 7 + 3) % points.size()]);
      EXPECT_EQ(again, first[i]) << "area " << area << " query " << i;
      bent += again.size() > 2;
    }
    EXPECT_GT(bent, std::size_t(5)) << area;
  }
}

// Copies share which nodes see each other (whoever asks first keeps the answer) and may ask at
// once: four threads, each on its own copy, asking the same and different paths concurrently, get
// what a lone router of the same area answers, bit for bit.
TEST(VisibilityRouterSearch, CopiesAskingAtOnceGiveTheSamePaths) {
  test::Rng rng(1821);
  for (int area = 0; area < 3; ++area) {
    const std::vector<Ring> rings = search_holey_area(rng, std::size_t(24) << area, 12 + 9 * area);
    const std::vector<Point2> points = path_ends(rng, rings, 48);
    const auto query = [&](std::size_t k, std::size_t i) {
      return std::pair{points[i], points[(i * (5 + 2 * (k % 2)) + 3 + k) % points.size()]};
    };
    constexpr std::size_t kThreads = 4;
    std::vector<std::vector<std::vector<Point2>>> truth(kThreads);
    for (std::size_t k = 0; k < kThreads; ++k) {
      const VisibilityRouter lone(rings, Routing::routed, 1.5);  // tables of its own
      for (std::size_t i = 0; i < points.size(); ++i) {
        const auto [a, b] = query(k, i);
        truth[k].push_back(lone.path(a, b));
      }
    }
    const VisibilityRouter router(rings, Routing::routed, 1.5);
    std::vector<std::unique_ptr<VisibilityRouter>> copies;
    for (std::size_t k = 0; k < kThreads; ++k) copies.push_back(router.fresh_copy());
    std::vector<std::vector<std::vector<Point2>>> got(kThreads);
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < kThreads; ++k)
      threads.emplace_back([&, k] {
        for (std::size_t i = 0; i < points.size(); ++i) {
          const auto [a, b] = query(k, i);
          got[k].push_back(copies[k]->path(a, b));
        }
      });
    for (std::thread& t : threads) t.join();
    std::size_t bent = 0;
    for (std::size_t k = 0; k < kThreads; ++k)
      for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(got[k][i], truth[k][i]) << "area " << area << " thread " << k << " query " << i;
        bent += truth[k][i].size() > 2;
      }
    EXPECT_GT(bent, std::size_t(10)) << area;
  }
}

// A point asked about often gets a fan (the edges by direction from it); edges within a
// millionth of the area's size of it are asked for every leg, as their direction from it is not
// to be trusted. Path ends a hair (1e-10 to 1e-4 m) off vertices and along edges just past a
// vertex, each asked about dozens of times: paths bit for bit the eager ones.
TEST(VisibilityRouterSearch, EndsAHairFromCornersAreSeenAsByTheFullSearch) {
  test::Rng rng(1819);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t bent = 0;
  for (int area = 0; area < 4; ++area) {
    const std::vector<Ring> rings =
        area % 2 ? std::vector<Ring>{test::random_grid_ring(rng, 24, 10)}
                 : search_holey_area(rng, std::size_t(12) << area, 6 + 7 * area);
    const VisibilityRouter router(rings, Routing::routed, 0.0);
    EagerRouter eager(rings);
    const test::BruteArea brute(rings);
    std::vector<Point2> points;
    for (int k = 0; k < 30; ++k) {
      const Ring& ring = rings[std::size_t(k) % rings.size()];
      const std::size_t i = std::size_t(unit(rng) * double(ring.size())) % ring.size();
      const Point2 v = ring[i], w = ring[(i + 1) % ring.size()];
      const double hair_m = std::pow(10.0, -10 + 6 * unit(rng));
      const double turn = 2 * 3.141592653589793 * unit(rng);
      points.push_back(k % 2 ? v + Point2{std::cos(turn), std::sin(turn)} * hair_m
                             : v + (w - v) * (hair_m / distance(v, w)));
    }
    std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
    for (int q = 0; q < kQueries / 2; ++q) {
      const Point2 a = points[pick(rng)], b = points[pick(rng)];
      const std::vector<Point2> lazy = router.path(a, b), truth = eager.path(a, b);
      SCOPED_TRACE(::testing::Message() << "area " << area << " (" << a.x << ", " << a.y << ") - ("
                                        << b.x << ", " << b.y << ")");
      expect_as_short(brute, lazy, truth, a, b, 0.0);
      if (::testing::Test::HasFailure()) return;
      bent += truth.size() > 2;
    }
  }
  EXPECT_GT(bent, std::size_t(kQueries / 4));
}

// A comb of 150 teeth (298 reflex corners, all of the floor's in one line): from the tip of one
// tooth to another's, the shortest path goes down the first tooth to the corner at its foot, along
// the gaps' floor and up the other: 2 hypot(w / 2, h) + (2 (j - i) - 1) w, for teeth i < j (w wide,
// h tall). With a corner allowance, inside and at most 2 allowances a bend longer.
TEST(VisibilityRouterSearch, ACombIsRoutedAlongItsFloor) {
  constexpr int kTeeth = 150;
  constexpr double w = 10, h = 200, b = 20;
  const std::vector<Ring> rings{test::comb_polygon(kTeeth, w, h, b)};
  const test::BruteArea brute(rings);
  test::Rng rng(1822);
  std::uniform_int_distribution<int> tooth(0, kTeeth - 1);
  for (const double allowance_m : {0.0, 1.5}) {
    const VisibilityRouter router(rings, Routing::routed, allowance_m);
    for (int q = 0; q < 20; ++q) {
      int i = tooth(rng), j = tooth(rng);
      if (i == j) continue;
      if (i > j) std::swap(i, j);
      const Point2 a{2 * i * w + w / 2, b + h}, z{2 * j * w + w / 2, b + h};
      const std::vector<Point2> path = router.path(a, z);
      const double shortest = 2 * std::hypot(w / 2, h) + (2 * (j - i) - 1) * w;
      SCOPED_TRACE(::testing::Message()
                   << "allowance " << allowance_m << " teeth " << i << " " << j);
      ASSERT_GT(path.size(), 2u);
      double outside = 0;
      for (std::size_t k = 0; k + 1 < path.size(); ++k)
        outside += brute.length_outside(path[k], path[k + 1]);
      EXPECT_LE(outside, 1e-6);
      EXPECT_NEAR(polyline_length(path), shortest, allowance_m == 0 ? 1e-6 : 4 * allowance_m);
      EXPECT_GE(polyline_length(path), shortest - 1e-6);
    }
  }
}

// A traced field outline of 5,000 vertices (about 2,000 reflex): paths between its vertices stay
// inside, and many bend.
TEST(VisibilityRouterSearch, ABigFieldOutlineIsRoutedInside) {
  test::Rng rng(1823);
  const std::vector<Ring> rings{test::random_field_polygon(rng, 5000, 500)};
  const test::BruteArea brute(rings);
  const VisibilityRouter router(rings, Routing::routed, 1.5);
  std::uniform_int_distribution<std::size_t> vertex(0, rings[0].size() - 1);
  std::size_t bent = 0;
  for (int q = 0; q < 40; ++q) {
    const Point2 a = rings[0][vertex(rng)], z = rings[0][vertex(rng)];
    const std::vector<Point2> path = router.path(a, z);
    double outside = 0;
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
      outside += brute.length_outside(path[k], path[k + 1]);
    EXPECT_LE(outside, 1e-6) << q;
    bent += path.size() > 2;
  }
  EXPECT_GT(bent, 10u);
}

// The search's groups of corners are passed over by distance_to_box() (point.hpp): it must never
// exceed distance() to a point of the box, nor its sum as the search adds it (g, the leg, h =
// (1 - 1e-6) |u b|) the sum to any corner of the group, bit for bit, at every scale of coordinates;
// and it is distance() itself for a box of one point (so no margin hides a scaled bound).
TEST(VisibilityRouterSearch, DistanceToABoxIsNeverAboveTheDistanceToAPointInIt) {
  test::Rng rng(1827);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr double kShrink = 1 - 1e-6;
  std::size_t outside = 0;
  for (int k = 0; k < 200000; ++k) {
    const double scale = std::pow(10.0, -3 + 10 * unit(rng));  // 1e-3 to 1e7 metres
    const auto coordinate = [&] { return scale * (2 * unit(rng) - 1); };
    Point2 lo{coordinate(), coordinate()}, hi{coordinate(), coordinate()};
    if (lo.x > hi.x) std::swap(lo.x, hi.x);
    if (lo.y > hi.y) std::swap(lo.y, hi.y);
    const Point2 p{coordinate(), coordinate()}, b{coordinate(), coordinate()};
    const int where = int(rng() % 4);  // a corner, a side, anywhere inside, the box of u alone
    Point2 u{lo.x + (hi.x - lo.x) * unit(rng), lo.y + (hi.y - lo.y) * unit(rng)};
    if (where == 0) u = {rng() % 2 ? lo.x : hi.x, rng() % 2 ? lo.y : hi.y};
    if (where == 1) u.x = rng() % 2 ? lo.x : hi.x;
    u = {std::clamp(u.x, lo.x, hi.x), std::clamp(u.y, lo.y, hi.y)};
    const Point2 box_lo = where == 3 ? u : lo, box_hi = where == 3 ? u : hi;
    const double to_box = distance_to_box(p, box_lo, box_hi), to_u = distance(p, u);
    if (where == 3) ASSERT_EQ(to_box, to_u) << "k " << k;
    ASSERT_LE(to_box, to_u) << "k " << k;
    const double g = scale * unit(rng);
    ASSERT_LE(g + to_box + kShrink * distance_to_box(b, box_lo, box_hi),
              g + to_u + kShrink * distance(u, b))
        << "k " << k;
    outside += to_box > 0;
  }
  EXPECT_GT(outside, 100000u);  // most points lie outside their box
}
}  // namespace
}  // namespace swath::geometry

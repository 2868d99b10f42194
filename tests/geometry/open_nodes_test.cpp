#include "swath/geometry/open_nodes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

namespace swath::geometry {
namespace {

// Bit for bit: a sum that rounded otherwise (or -0 for +0) is a different path in the plan.
bool same_bits(double x, double y) {
  return std::memcmp(&x, &y, sizeof x) == 0;
}

// OpenNodes against the straightforward computation the search made before it (g + distance(),
// + h, compared with the cut node by node, over a plain list of the open nodes): on random nodes
// (fixed seed) from integer grids (equal distances: f on the cut) and from wide ranges, open sets
// of every size (odd ones end in the scalar tail), removed in random order, legs from nodes and
// from other points, cuts on an f, between, below and above all.
TEST(OpenNodes, LegsAreTheStraightforwardOnesBitForBit) {
  std::mt19937 random(52);
  std::size_t on_cut = 0, under_total = 0;
  for (int run = 0; run < 300; ++run) {
    const std::size_t n = std::size_t(random() % 70);
    const bool grid = run % 2 == 0;
    std::uniform_real_distribution<double> wide(-3e4, 3e4), unit(0, 1);
    std::vector<Point2> nodes(n);
    std::vector<double> h(n);
    for (std::size_t u = 0; u < n; ++u) {
      nodes[u] = grid ? Point2{double(random() % 12), double(random() % 12)}
                      : Point2{wide(random), wide(random)};
      h[u] = grid ? double(random() % 5) : (1 - 1e-6) * std::abs(wide(random));
    }
    std::vector<std::size_t> open;
    for (std::size_t u = 0; u < n; ++u)
      if (random() % 4 != 0) open.push_back(u);
    std::shuffle(open.begin(), open.end(), random);
    OpenNodes nodes_open;
    nodes_open.reset(open, n, nodes, h);
    while (true) {
      ASSERT_EQ(nodes_open.size(), open.size());
      const Point2 c = !open.empty() && random() % 2 ? nodes[open[random() % open.size()]]
                       : grid ? Point2{double(random() % 12), double(random() % 12)}
                              : Point2{wide(random), wide(random)};
      const double g = grid ? double(random() % 7) : 1e3 * unit(random);
      // The straightforward legs, and a cut: one of their f (ties), or anywhere.
      using Leg = std::tuple<std::uint32_t, double, double>;  // node, through, f
      std::vector<Leg> all;
      for (const std::size_t u : open) {
        const double through = g + distance(c, nodes[u]);
        all.push_back({std::uint32_t(u), through, through + h[u]});
      }
      double cut;
      switch (random() % 4) {
        case 0:
          cut = all.empty() ? 0.0 : std::get<2>(all[random() % all.size()]);
          break;
        case 1:
          cut = -std::numeric_limits<double>::infinity();
          break;
        case 2:
          cut = std::numeric_limits<double>::infinity();
          break;
        default:
          cut = g + (grid ? double(random() % 20) : 4e4 * unit(random));
      }
      std::vector<Leg> want;
      double least_above = std::numeric_limits<double>::infinity();
      for (const Leg& leg : all) {
        if (std::get<2>(leg) <= cut)
          want.push_back(leg);
        else
          least_above = std::min(least_above, std::get<2>(leg));
        on_cut += std::get<2>(leg) == cut;
      }
      const double got_least = nodes_open.legs(c, g, cut);
      EXPECT_TRUE(same_bits(got_least, least_above)) << "run " << run;
      std::vector<Leg> got;
      for (const std::uint32_t k : nodes_open.under()) {
        ASSERT_LT(k, nodes_open.size());
        got.push_back({nodes_open.node(k), nodes_open.through(k), nodes_open.f(k)});
      }
      std::sort(got.begin(), got.end());
      std::sort(want.begin(), want.end());
      ASSERT_EQ(got.size(), want.size()) << "run " << run;
      for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(std::get<0>(got[i]), std::get<0>(want[i])) << "run " << run;
        EXPECT_TRUE(same_bits(std::get<1>(got[i]), std::get<1>(want[i]))) << "run " << run;
        EXPECT_TRUE(same_bits(std::get<2>(got[i]), std::get<2>(want[i]))) << "run " << run;
      }
      under_total += got.size();
      if (::testing::Test::HasFailure() || open.empty()) break;
      // One node settles.
      const std::size_t i = random() % open.size();
      nodes_open.remove(open[i]);
      open.erase(open.begin() + std::ptrdiff_t(i));
    }
  }
  // The cases the comparison is for happened: legs under the cut, and f exactly on it.
  EXPECT_GT(under_total, 10000u);
  EXPECT_GT(on_cut, 1000u);
}

}  // namespace
}  // namespace swath::geometry

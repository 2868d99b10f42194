// Tuning's search (docs/swath-fleet.md) apart from its runs: the trials' weights and successive
// halving against a synthetic score whose best trial is known.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "swath/fleet/tuning.hpp"

namespace swath::fleet {
namespace {

TEST(Tuning, TrialsStartWithTheGivenAndReactivesWeightsThenDrawFourDigitWeights) {
  Weights start;
  start.speculative = 2;
  start.avoid_mutual = 3;
  const std::vector<Weights> t = draw_trials(start, 40, 7);
  ASSERT_EQ(t.size(), 40u);
  EXPECT_EQ(t[0].speculative, 2);
  EXPECT_EQ(t[1].speculative, 0);
  EXPECT_EQ(t[1].avoid_mutual, 0);
  int zeros = 0;
  for (std::size_t i = 2; i < t.size(); ++i)
    for (const FreeWeight& f : free_weights()) {
      const double w = t[i].*f.member;
      if (w == 0) {
        ++zeros;
        continue;
      }
      EXPECT_GE(w, 1e-3);
      EXPECT_LE(w, 1e3);
      const double scale = std::pow(10.0, 3 - std::floor(std::log10(w)));
      EXPECT_NEAR(w * scale, std::round(w * scale), 1e-6) << w;  // 4 significant digits
    }
  EXPECT_GT(zeros, 0);
  EXPECT_EQ(draw_trials(start, 40, 7)[17].fairness, t[17].fairness);  // the seed decides
  EXPECT_NE(weights_yaml(t[5], "x").find("avoid_mutual: "), std::string::npos);
}

TEST(Tuning, SuccessiveHalvingKeepsTheBetterHalfEachRungAndEndsAtTheBest) {
  std::vector<Trial> trials(9);
  // Trial i scores 100 + |i - 6| on every rung; trial 2 is lucky on the first (ahead of 5 and 7
  // there, behind them after the second): trial 6 wins.
  std::vector<int> runs(9, 0);
  const std::size_t winner = successive_halving(trials, 3, [&](std::size_t i, int rung) {
    ++runs[i];
    return 100.0 + std::abs(static_cast<double>(i) - 6.0) + (rung == 0 && i == 2 ? -3.0 : 0.0);
  });
  EXPECT_EQ(winner, 6u);
  int rung0 = 0, rung2 = 0;
  for (int r : runs) rung0 += r >= 1, rung2 += r >= 3;
  EXPECT_EQ(rung0, 9);
  EXPECT_EQ(rung2, 3);  // 9 -> 5 -> 3
  EXPECT_EQ(trials[6].times_s.size(), 3u);
  EXPECT_EQ(trials[2].times_s.size(), 2u);
  // Ties go to the lower trial.
  std::vector<Trial> tied(3);
  for (Trial& t : tied) t.times_s = {10};
  EXPECT_EQ(better_half(tied, {2, 1, 0}), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(best_trial(tied, {2, 1}), 1u);
  EXPECT_NE(tune_csv(trials).find("trial,coverage,fairness"), std::string::npos);
}

}  // namespace
}  // namespace swath::fleet

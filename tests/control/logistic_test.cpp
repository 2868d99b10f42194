// The trigger model (paper 002 eq. 1) and its fits (docs/swath-control.md): the threshold is eq. 1
// inverted, synthetic coefficients are recovered, OLS on grouped logits equals its closed form,
// degenerate data falls back to the pooled logit; trigger data reads in every CSV dialect.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "swath/base/input_error.hpp"

#include "swath/control/logistic.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::control {
namespace {

std::vector<TriggerPoint> synthetic(double b1, double b2, int n, std::uint64_t seed) {
  auto random = vehicle::SplitMix64::stream(seed, "logistic");
  std::vector<TriggerPoint> data;
  for (int i = 0; i < n; ++i) {
    const double x = random.uniform(0, 4);
    const double p = 1 / (1 + std::exp(-(b1 + b2 * x)));
    data.push_back({x, random.uniform() < p});
  }
  return data;
}

TEST(Logistic, TheThresholdIsEquationOneInverted) {
  for (const double p : {0.2, 0.5, 0.6, 0.8}) {
    const LogisticModel m{-3, 2, false, 0};
    const double x = trigger_threshold(m, p);
    EXPECT_NEAR(trigger_probability(m, x), p, 1e-12);
    for (double probe = 0; probe < 5; probe += 0.01)
      EXPECT_EQ(trigger_probability(m, probe) > p, probe > x) << p << " " << probe;
  }
  // β2 ≤ 0: never or always.
  EXPECT_TRUE(std::isinf(trigger_threshold({-3, 0, true, 0}, 0.6)));
  EXPECT_EQ(trigger_threshold({3, 0, true, 0}, 0.6), 0.0);
  EXPECT_EQ(trigger_threshold({3, -1, false, 0}, 0.6), 0.0);
}

TEST(Logistic, SyntheticCoefficientsAreRecovered) {
  // β = (−3, 2) on x uniform in [0, 4], 20,000 points, five seeds.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto data = synthetic(-3, 2, 20'000, seed);
    const LogisticModel mle = fit_logistic(data, FitMethod::mle);
    // The standard errors from the Fisher information at the estimate.
    double h11 = 0, h12 = 0, h22 = 0;
    for (const TriggerPoint& p : data) {
      const double mu = trigger_probability(mle, p.x), w = mu * (1 - mu);
      h11 += w;
      h12 += w * p.x;
      h22 += w * p.x * p.x;
    }
    const double det = h11 * h22 - h12 * h12;
    const double se1 = std::sqrt(h22 / det), se2 = std::sqrt(h11 / det);
    EXPECT_NEAR(mle.beta1, -3, 3 * se1) << seed;
    EXPECT_NEAR(mle.beta2, 2, 3 * se2) << seed;
    const LogisticModel ols = fit_logistic(data, FitMethod::logit_ols);
    EXPECT_NEAR(ols.beta1, -3, 0.15 * 3) << seed;  // grouped logits are biased towards 0
    EXPECT_NEAR(ols.beta2, 2, 0.15 * 2) << seed;
    const LogisticModel wls = fit_logistic(data, FitMethod::logit_wls);
    EXPECT_NEAR(wls.beta2, 2, 0.15 * 2) << seed;
  }
}

TEST(Logistic, OlsOnGroupedLogitsIsItsClosedForm) {
  // 4 groups of 25 points at x = 1, 2, 3, 4 with 2, 8, 15, 22 changed: z_j by hand.
  std::vector<TriggerPoint> data;
  const int changed[] = {2, 8, 15, 22};
  for (int g = 0; g < 4; ++g)
    for (int i = 0; i < 25; ++i) data.push_back({g + 1.0, i < changed[g]});
  const LogisticModel m = fit_logistic(data, FitMethod::logit_ols, 20, 25);
  double z[4], zm = 0;
  for (int g = 0; g < 4; ++g) {
    z[g] = std::log((changed[g] + 0.5) / (25 - changed[g] + 0.5));
    zm += z[g] / 4;
  }
  double sxz = 0, sxx = 0;
  for (int g = 0; g < 4; ++g) {
    sxz += (g + 1 - 2.5) * (z[g] - zm);
    sxx += (g + 1 - 2.5) * (g + 1 - 2.5);
  }
  EXPECT_NEAR(m.beta2, sxz / sxx, 1e-12);
  EXPECT_NEAR(m.beta1, zm - m.beta2 * 2.5, 1e-12);
  EXPECT_FALSE(m.degenerate);
}

// The grouped-logit fits depend on the multiset of points only: any order, ties of one x with
// both labels in any order, gives the same bits (the reactive scheduler fits data it keeps sorted).
TEST(Logistic, GroupedFitsDoNotDependOnTheOrderOfThePoints) {
  auto random = vehicle::SplitMix64::stream(5, "order");
  for (int round = 0; round < 20; ++round) {
    std::vector<TriggerPoint> data;
    for (int i = 0; i < 2000; ++i) {
      // Half the points on 9 values (long runs of ties with both labels), half continuous.
      const double x = i % 2 ? static_cast<double>(random.below(9)) * 0.25 : random.uniform(0, 2);
      data.push_back({x, random.uniform() < 1 / (1 + std::exp(2 - 2 * x))});
    }
    std::vector<std::vector<TriggerPoint>> orders(4, data);
    for (std::size_t i = orders[1].size() - 1; i > 0; --i)  // a shuffle
      std::swap(orders[1][i], orders[1][random.below(i + 1)]);
    std::sort(orders[2].begin(), orders[2].end(), [](const auto& a, const auto& b) {
      return a.x < b.x || (a.x == b.x && a.changed < b.changed);
    });
    std::sort(orders[3].begin(), orders[3].end(), [](const auto& a, const auto& b) {
      return a.x < b.x || (a.x == b.x && a.changed > b.changed);
    });
    for (const FitMethod method : {FitMethod::logit_ols, FitMethod::logit_wls}) {
      const LogisticModel first = fit_logistic(orders[0], method);
      ASSERT_FALSE(first.degenerate);
      for (std::size_t k = 1; k < orders.size(); ++k) {
        const LogisticModel m = fit_logistic(orders[k], method);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(m.beta1), std::bit_cast<std::uint64_t>(first.beta1))
            << round << " " << k;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(m.beta2), std::bit_cast<std::uint64_t>(first.beta2))
            << round << " " << k;
      }
    }
  }
}

// The trigger check compares sums of squares with x*'s bound instead of square roots with x*:
// the same decision for every sum, checked on the doubles next to x*² and at random.
TEST(Logistic, TheSquareBoundDecidesAsTheSquareRootDoes) {
  auto random = vehicle::SplitMix64::stream(9, "bound");
  std::vector<double> thresholds = {0.0,
                                    1.0,
                                    0.1,
                                    3.0,
                                    1e-160,
                                    1e-300,
                                    1e150,
                                    1e160,
                                    std::numeric_limits<double>::denorm_min(),
                                    std::numeric_limits<double>::max(),
                                    std::numeric_limits<double>::infinity()};
  for (int k = 0; k < 20'000; ++k)
    thresholds.push_back(
        std::ldexp(random.uniform(0.5, 1), static_cast<int>(random.below(40)) - 30));
  const double inf = std::numeric_limits<double>::infinity();
  for (const double x : thresholds) {
    const double bound = largest_square_within(x);
    std::vector<double> sums = {0.0, bound, inf, x * x, random.uniform(0, 4) * x * x};
    double up = x * x, down = x * x;
    for (int step = 0; step < 4; ++step) {
      sums.push_back(up = std::nextafter(up, inf));
      sums.push_back(down = std::nextafter(down, 0.0));
    }
    for (const double sum : sums)
      ASSERT_EQ(sum > bound, std::sqrt(sum) > x) << "x " << x << " sum " << sum;
  }
  EXPECT_TRUE(std::isnan(largest_square_within(-1.0)));
}

TEST(Logistic, DegenerateDataGivesThePooledLogit) {
  std::vector<TriggerPoint> all_changed(100, {1.0, true});
  for (int i = 0; i < 100; ++i) all_changed[i].x = i * 0.1;
  for (FitMethod method : {FitMethod::logit_ols, FitMethod::logit_wls, FitMethod::mle}) {
    const LogisticModel m = fit_logistic(all_changed, method);
    EXPECT_TRUE(m.degenerate);
    EXPECT_EQ(m.beta2, 0);
    EXPECT_NEAR(m.beta1, std::log(100.5 / 0.5), 1e-12);
  }
  // Too few points for two groups; every x the same.
  const std::vector<TriggerPoint> few{{1, true}, {2, false}, {3, true}};
  EXPECT_TRUE(fit_logistic(few, FitMethod::logit_ols).degenerate);
  std::vector<TriggerPoint> same(200, {2.0, false});
  for (int i = 0; i < 100; ++i) same[i].changed = true;
  EXPECT_TRUE(fit_logistic(same, FitMethod::logit_ols).degenerate);
  EXPECT_TRUE(fit_logistic({}, FitMethod::mle).degenerate);
  // Separable data: no finite optimum, IRLS gives up to the pooled logit.
  std::vector<TriggerPoint> separable;
  for (int i = 0; i < 100; ++i) separable.push_back({i * 0.1, i >= 50});
  EXPECT_TRUE(fit_logistic(separable, FitMethod::mle).degenerate);
}

// swath-control fit's data in the dialects the area reader takes (base::CsvText): quoted cells,
// ';' with decimal commas, tabs, CR-only and CRLF line ends, a BOM, trailing comments: the same
// points, value for value.
TEST(TriggerData, EveryCsvDialectReadsTheSamePoints) {
  const std::vector<std::pair<double, bool>> expected{{0.125, false}, {2.5, true}, {17, true}};
  for (const std::string text : {
           "x,changed\n0.125,0\n2.5,1\n17,1\n",
           "# a trial\n\"x\",\"changed\",\"note\"\n\"0.125\",\"0\",\"a, b\"\n2.5,1,\"#3\"\n17,1,\n",
           "changed;x\n0;0,125\n1;2,5\n1;17\n",
           "x\tchanged\n0.125\t0\n2.5\t1\n17\t1\n",
           "x,changed\r0.125,0\r2.5,1\r17,1",
           "\xEF\xBB\xBFx,changed\r\n0.125,0\r\n\r\n2.5,1 # the second\r\n17,1#\r\n",
       }) {
    SCOPED_TRACE(text);
    const std::vector<TriggerPoint> data = parse_trigger_data(text, "d.csv");
    ASSERT_EQ(data.size(), expected.size());
    for (std::size_t i = 0; i < data.size(); ++i) {
      EXPECT_EQ(data[i].x, expected[i].first) << i;
      EXPECT_EQ(data[i].changed, expected[i].second) << i;
    }
  }
  auto refusal = [](const std::string& text) {
    try {
      parse_trigger_data(text, "d.csv");
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("x;changed\n1.234,5;1\n"),
            "d.csv: line 2: x '1.234,5' is not a finite number >= 0");
  EXPECT_EQ(refusal("x\tchanged\r1\r2\t1\r"),
            "d.csv: line 2: 1 tab-separated fields, the header has 2");
  EXPECT_EQ(refusal("x,changed\n1,\"1\n"),
            "d.csv: line 2: column 2 opens a quote that the line does not close");
}

}  // namespace
}  // namespace swath::control

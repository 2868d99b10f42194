// The random streams: reference values of SplitMix64, independence of named streams, and the
// distributions' moments over many draws (fixed seeds).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "swath/vehicle/clock.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::vehicle {
namespace {

TEST(SplitMix64, MatchesTheReferenceSequence) {
  // Vigna's splitmix64.c with seed 1234567: the first outputs.
  SplitMix64 r(1234567);
  EXPECT_EQ(r.next(), 6457827717110365317ull);
  EXPECT_EQ(r.next(), 3203168211198807973ull);
  EXPECT_EQ(r.next(), 9817491932198370423ull);
}

TEST(SplitMix64, Fnv1aOfKnownStrings) {
  EXPECT_EQ(fnv1a(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a("foobar"), 0x85944171f73967e8ull);
}

TEST(SplitMix64, NamedStreamsDifferAndRepeat) {
  SplitMix64 gyro = SplitMix64::stream(7, "gyro"), accel = SplitMix64::stream(7, "accel");
  SplitMix64 gyro2 = SplitMix64::stream(7, "gyro");
  int equal = 0;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t draw = gyro.next();
    equal += draw == accel.next();
    EXPECT_EQ(draw, gyro2.next());
  }
  EXPECT_EQ(equal, 0);
}

TEST(SplitMix64, MomentsOfTheDistributions) {
  SplitMix64 r(42);
  const int n = 200000;
  double su = 0, sn = 0, sn2 = 0, sn4 = 0, se = 0;
  std::vector<int> counts(7, 0);
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u;
    const double z = r.normal();
    sn += z;
    sn2 += z * z;
    sn4 += z * z * z * z;
    se += r.exponential(2.0);
    ++counts[r.below(7)];
  }
  // Standard errors: uniform mean 0.29/sqrt(n) = 6.5e-4; normal mean 2.2e-3, variance 3.2e-3.
  EXPECT_NEAR(su / n, 0.5, 4e-3);
  EXPECT_NEAR(sn / n, 0.0, 1.2e-2);
  EXPECT_NEAR(sn2 / n, 1.0, 1.6e-2);
  EXPECT_NEAR(sn4 / n, 3.0, 0.1);  // kurtosis of a normal
  EXPECT_NEAR(se / n, 0.5, 6e-3);
  for (const int c : counts) EXPECT_NEAR(c, n / 7.0, 5 * std::sqrt(n / 7.0));
}

TEST(SimClock, SecondsAndPeriods) {
  EXPECT_EQ(from_seconds(1.5), 1'500'000'000);
  EXPECT_DOUBLE_EQ(seconds(2'500'000), 0.0025);
  EXPECT_EQ(period_of_rate(1000), 1'000'000);
  EXPECT_EQ(period_of_rate(490), 0);  // 2,040,816.33 ns: not a whole number
  EXPECT_EQ(period_of_rate(400), 2'500'000);
  EXPECT_EQ(period_of_rate(0), 0);
}

}  // namespace
}  // namespace swath::vehicle

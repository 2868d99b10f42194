// The one rest-to-rest time against independent truth: the trapezoid and triangle in closed form
// (swath plan's old formula) and, with an approach phase, the time-optimal profile integrated
// numerically (the speed at each point the least of what every limit allows).
#include "swath/vehicle/kinematics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "swath/vehicle/random.hpp"

namespace swath::vehicle {
namespace {

// ∫ ds / v(s) with v the pointwise least of: from rest at a, to rest at a, the cap (cruise, or
// the approach speed in the last approach_within_m), and braking in time for the approach cap.
double brute_force_s(double length, double cruise, double approach, double within, double a) {
  const double va = std::min(approach, cruise), zone_start = length - std::min(within, length);
  const int n = 400'000;
  const double h = length / n;
  // The first and last cells in closed form: there v = √(2 a s) (from and to rest), whose 1/√s
  // the midpoint rule would undercount; the midpoint rule between them.
  double t = 2 * std::sqrt(2 * h / a);
  for (int i = 1; i + 1 < n; ++i) {
    const double s = (i + 0.5) * h;
    double v = std::min(std::sqrt(2 * a * s), std::sqrt(2 * a * (length - s)));
    v = std::min(v, s >= zone_start ? va : cruise);
    if (s < zone_start) v = std::min(v, std::sqrt(va * va + 2 * a * (zone_start - s)));
    t += h / v;
  }
  return t;
}

TEST(RestToRest, TrapezoidOrTriangleInClosedForm) {
  SplitMix64 random(3);
  for (int i = 0; i < 5000; ++i) {
    const double length = random.uniform(0.01, 500), v = random.uniform(0.5, 20),
                 a = random.uniform(0.5, 5);
    const double expected = length >= v * v / a ? length / v + v / a : 2 * std::sqrt(length / a);
    EXPECT_NEAR(rest_to_rest_s(length, v, a), expected, 1e-9 * expected) << length << " " << v;
  }
  EXPECT_EQ(rest_to_rest_s(0, 5, 2.5), 0.0);
  EXPECT_EQ(rest_to_rest_s(-1, 5, 2.5), 0.0);
}

TEST(RestToRest, WithAnApproachPhaseMatchesTheTimeOptimalProfile) {
  SplitMix64 random(46);
  for (int i = 0; i < 40; ++i) {
    const double length = random.uniform(1, 300), cruise = random.uniform(2, 15),
                 approach = random.uniform(0.5, 4), within = random.uniform(0, 60),
                 a = random.uniform(0.5, 4);
    const double t = rest_to_rest_s(length, cruise, approach, within, a);
    // The midpoint rule's error (the kinks of the profile) is far below 1 ms at these steps.
    EXPECT_NEAR(t, brute_force_s(length, cruise, approach, within, a), 1e-3)
        << length << " " << cruise << " " << approach << " " << within << " " << a;
  }
}

}  // namespace
}  // namespace swath::vehicle

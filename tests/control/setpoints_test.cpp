// Carrot setpoints (docs/swath-control.md): the trapezoid against a numerical integral of
// its speed profile min(a t, v, a (T − t)), and the carrot along legs: 50-Hz updates, stops at the
// waypoints, climb-limited legs, yaw along each leg slewed the shorter way at its rate.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "swath/control/setpoints.hpp"

namespace swath::control {
namespace {

// ∫ min(a τ, v, a (T − τ)) dτ from 0 to t by the midpoint rule, T from the area condition.
double integrated_distance(double t, double length, double v, double a) {
  const double peak = std::min(v, std::sqrt(length * a));
  const double total = peak / a + length / peak;  // ramp up, cruise, ramp down
  double s = 0;
  const int n = 200'000;
  const double h = std::min(t, total) / n;
  for (int k = 0; k < n; ++k) {
    const double tau = (k + 0.5) * h;
    s += h * std::min({a * tau, v, a * (total - tau)});
  }
  return s;
}

TEST(Setpoints, TrapezoidMatchesTheIntegralOfItsSpeed) {
  struct Case {
    double length, v, a;
  };
  for (const Case c : {Case{20, 3, 1}, Case{4, 3, 1}, Case{9, 3, 1}, Case{100, 5, 0.5}}) {
    const double total = trapezoid_duration_s(c.length, c.v, c.a);
    const double peak = std::min(c.v, std::sqrt(c.length * c.a));
    EXPECT_NEAR(total, peak / c.a + c.length / peak, 1e-12);
    for (double t = 0; t <= total + 1; t += total / 37) {
      EXPECT_NEAR(trapezoid_distance_m(t, c.length, c.v, c.a),
                  integrated_distance(t, c.length, c.v, c.a), 1e-6)
          << c.length << " at " << t;
    }
    EXPECT_EQ(trapezoid_distance_m(total + 0.1, c.length, c.v, c.a), c.length);
  }
  EXPECT_EQ(trapezoid_duration_s(0, 3, 1), 0);
}

TEST(Setpoints, CarrotMovesAt50HzStopsAtWaypointsAndFacesTheLeg) {
  const std::vector<Vec3> wp{{0, 0, 5}, {20, 0, 5}, {20, 10, 5}, {20, 10, 8}};
  const CarrotLimits limits;  // 3 m/s, climb 1.5 m/s, 1 m/s², 50 Hz
  const CarrotPath path(wp, limits);
  ASSERT_EQ(path.legs(), 3u);
  // Leg 3 climbs 3 m at most 1.5 m/s: its speed is 1.5 m/s.
  const double t1 = trapezoid_duration_s(20, 3, 1), t2 = trapezoid_duration_s(10, 3, 1),
               t3 = trapezoid_duration_s(3, 1.5, 1);
  EXPECT_EQ(path.end_ns(), vehicle::from_seconds(t1 + t2 + t3));
  Setpoint previous = path.at(0);
  double max_climb = 0;
  for (SimTime t = 0; t < path.end_ns() + 1'000'000'000; t += 1'000'000) {
    const Setpoint sp = path.at(t);
    const SimTime sample = t / 20'000'000 * 20'000'000;
    const double ts = vehicle::seconds(sample);
    // Held between 50-Hz updates.
    if (t % 20'000'000 != 0) {
      EXPECT_EQ(sp.position_m, previous.position_m);
    }
    // Position from the trapezoid of the leg in force at the sample.
    Vec3 expected;
    double yaw = 0;
    if (ts < t1) {
      expected = wp[0] + Vec3{trapezoid_distance_m(ts, 20, 3, 1), 0, 0};
    } else if (ts < t1 + t2) {
      expected = wp[1] + Vec3{0, trapezoid_distance_m(ts - t1, 10, 3, 1), 0};
      // Slewed from east to north at 45°/s from the leg's start (2 s for the quarter turn).
      yaw = std::min(std::numbers::pi / 2, limits.yaw_slew_rad_s * (ts - t1));
    } else {
      expected = wp[2] + Vec3{0, 0, trapezoid_distance_m(ts - t1 - t2, 3, 1.5, 1)};
      yaw = std::numbers::pi / 2;  // vertical: the previous leg's heading
    }
    EXPECT_NEAR(norm(sp.position_m - expected), 0, 1e-6) << ts;
    EXPECT_NEAR(sp.yaw_rad, yaw, 1e-8) << ts;
    // The slew's rate is its feed-forward, only while it turns.
    EXPECT_EQ(sp.yaw_rate_rad_s,
              yaw > 0 && yaw < std::numbers::pi / 2 - 1e-8 ? limits.yaw_slew_rad_s : 0.0)
        << ts;
    max_climb = std::max(max_climb, std::abs(sp.velocity_m_s.z));
    EXPECT_LE(norm(sp.velocity_m_s), 3 + 1e-12);
    previous = sp;
  }
  EXPECT_NEAR(max_climb, 1.5, 1e-12);
  // At each waypoint's arrival the carrot is at rest there.
  const double arrivals[] = {t1, t1 + t2};
  for (int k = 0; k < 2; ++k) {
    const SimTime at = (vehicle::from_seconds(arrivals[k]) / 20'000'000 + 1) * 20'000'000;
    const Setpoint sp = path.at(at);
    // At most ½ a (20 ms)² = 0.2 mm along the next leg.
    EXPECT_LT(norm(sp.position_m - wp[static_cast<std::size_t>(k) + 1]), 3e-4);
    EXPECT_LT(norm(sp.velocity_m_s), 0.021);  // at most a · 20 ms after the stop
  }
  EXPECT_EQ(path.at(path.end_ns() + 40'000'000).position_m, wp.back());
  EXPECT_EQ(path.at(path.end_ns() + 40'000'000).leg, 3u);
}

TEST(Setpoints, TheHeadingSlewsTheShorterWayAtItsRateOrStepsWithoutOne) {
  // East-north-east (10°) then west-south-west (−170° + …): from 170° to −170° is 20° through
  // 180°, not 340° the other way.
  const double d = std::numbers::pi / 180;
  const std::vector<Vec3> wp{{0, 0, 5},
                             {-10 * std::cos(10 * d), 10 * std::sin(10 * d), 5},
                             {-10 * std::cos(10 * d) - 10 * std::cos(10 * d),
                              10 * std::sin(10 * d) - 10 * std::sin(10 * d) - 5, 5}};
  for (const double slew_dps : {45.0, 0.0}) {
    CarrotLimits limits;
    limits.yaw_slew_rad_s = slew_dps * d;
    const CarrotPath path(wp, limits);
    const SimTime leg2 = vehicle::from_seconds(trapezoid_duration_s(10, 3, 1));
    const double from = path.at(leg2 - 20'000'000).yaw_rad;
    const double to = path.at(path.end_ns() - 20'000'000).yaw_rad;
    double turned = 0, previous = from;
    for (SimTime t = leg2; t < path.end_ns(); t += 20'000'000) {
      const Setpoint sp = path.at(t);
      const double step = std::remainder(sp.yaw_rad - previous, 2 * std::numbers::pi);
      if (slew_dps > 0) {
        EXPECT_LE(std::abs(step), limits.yaw_slew_rad_s * 0.02 + 1e-9) << t;
      }
      turned += step;
      previous = sp.yaw_rad;
    }
    // The turn taken equals the shorter angle between the headings, whatever the rate.
    EXPECT_NEAR(turned, std::remainder(to - from, 2 * std::numbers::pi), 1e-9);
    EXPECT_LT(std::abs(turned), std::numbers::pi);
  }
}

TEST(Setpoints, TheHeldCarrotExtrapolatedToAnyTimeIsTheContinuousCarrot) {
  // The 50-Hz sample advanced along its own velocity and yaw rate against a carrot updated every
  // nanosecond (the continuous trapezoid): within ½ a T² (0.2 mm at 1 m/s², T = 20 ms) where the
  // speed changes, exact at cruise; the heading within one period's slew where a turn ends. The
  // held sample alone lags by up to v T (60 mm at 3 m/s).
  const std::vector<Vec3> wp{{0, 0, 5}, {20, 0, 5}, {20, 10, 5}, {20, 10, 8}};
  const CarrotLimits limits;  // 3 m/s, climb 1.5 m/s, 1 m/s², 50 Hz, 45°/s
  CarrotLimits fine = limits;
  fine.update_hz = 1e9;
  const CarrotPath held(wp, limits), continuous(wp, fine);
  const double period_s = 0.02, bound_m = 0.5 * limits.max_accel_m_s2 * period_s * period_s;
  double worst_m = 0, worst_held_m = 0;
  for (SimTime t = 0; t < held.end_ns() + 100'000'000; t += 1'000'000) {
    const Setpoint sample = held.at(t), truth = continuous.at(t);
    EXPECT_EQ(sample.sampled_ns, t / 20'000'000 * 20'000'000);
    const Setpoint now = extrapolated(sample, t);
    worst_m = std::max(worst_m, norm(now.position_m - truth.position_m));
    worst_held_m = std::max(worst_held_m, norm(sample.position_m - truth.position_m));
    EXPECT_LE(std::abs(std::remainder(now.yaw_rad - truth.yaw_rad, 2 * std::numbers::pi)),
              limits.yaw_slew_rad_s * period_s + 1e-9)
        << t;
    if (t % 20'000'000 == 0) {
      EXPECT_EQ(now.position_m, sample.position_m);  // nothing to advance at the update
    }
  }
  EXPECT_LE(worst_m, bound_m + 1e-9);
  EXPECT_GT(worst_held_m, 0.9 * limits.max_speed_m_s * period_s);  // the sawtooth it removes
}

}  // namespace
}  // namespace swath::control

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "swath/energy/battery.hpp"
#include "swath/energy/power_model.hpp"

namespace swath::energy {
namespace {

// Paper 004 eq. 12 by hand, with the defaults 14.8 V, 12 V, 0.0012 ohm, 5 Ah at 200 W:
// 4 R V~ P / V = 4 * 0.0012 * 12 * 200 / 14.8 = 0.778378..., V^2 = 219.04,
// sqrt(218.261622) = 14.773680, I = (14.8 - 14.773680) / 0.0024 = 10.96665 A.
TEST(Battery, CurrentAndStateOfChargeByHand) {
  const Battery b;
  EXPECT_NEAR(battery_current_a(b, 200.0), 10.96665, 1e-5);
  const double direct =
      (14.8 - std::sqrt(14.8 * 14.8 - 4 * 0.0012 * 12 * 200 / 14.8)) / (2 * 0.0012);
  EXPECT_NEAR(battery_current_a(b, 200.0), direct, 1e-9);
  // 600 s at 200 W: 10.96665 * 600 / (3600 * 5) = 0.365555 of the charge.
  EXPECT_NEAR(soc_after(b, 1.0, 200.0, 600.0), 1.0 - 0.365555, 1e-6);
  // Down to the 20 % reserve: 0.8 * 18000 / 10.96665 = 1313.07 s.
  EXPECT_NEAR(seconds_to_soc(b, 1.0, 0.2, 200.0), 1313.07, 0.01);
  EXPECT_NEAR(usable_energy_j(b, 1.0, 0.2, 200.0), 200.0 * 1313.07, 2.0);
  EXPECT_EQ(seconds_to_soc(b, 0.1, 0.2, 200.0), 0.0);
  EXPECT_TRUE(std::isinf(seconds_to_soc(b, 1.0, 0.2, 0.0)));
  EXPECT_DOUBLE_EQ(battery_current_a(b, 0.0), 0.0);
}

TEST(Battery, BeyondTheMaximumPowerThereIsNoCurrent) {
  const Battery b;
  const double pmax = max_power_w(b);  // 14.8^3 / (4 * 0.0012 * 12) = 56,229 W
  EXPECT_NEAR(pmax, 14.8 * 14.8 * 14.8 / (4 * 0.0012 * 12), 1e-6);
  EXPECT_TRUE(std::isfinite(battery_current_a(b, 0.999 * pmax)));
  EXPECT_TRUE(std::isnan(battery_current_a(b, 1.001 * pmax)));
}

TEST(PowerModel, ComputationCurveIsPiecewiseLinear) {
  const PowerCurve fps{"detection", {{2, 4.75}, {10, 9.75}}};
  EXPECT_DOUBLE_EQ(computation_power_w(fps, 2), 4.75);
  EXPECT_DOUBLE_EQ(computation_power_w(fps, 10), 9.75);
  EXPECT_DOUBLE_EQ(computation_power_w(fps, 6), 7.25);
  EXPECT_DOUBLE_EQ(computation_power_w(fps, 0), 0.0);    // switched off
  EXPECT_DOUBLE_EQ(computation_power_w(fps, 12), 11.0);  // extended linearly
  const PowerCurve three{"x", {{1, 1.0}, {2, 3.0}, {4, 4.0}}};
  EXPECT_DOUBLE_EQ(computation_power_w(three, 1.5), 2.0);
  EXPECT_DOUBLE_EQ(computation_power_w(three, 3.0), 3.5);
  EXPECT_DOUBLE_EQ(computations_power_w({fps, three}, {10, 3.0}), 13.25);
}

TEST(PowerModel, MechanicalPowerGrowsWithSpeedAndBank) {
  const MechanicalPower m{150.0, 12.0, 0.4, 35.0};
  EXPECT_DOUBLE_EQ(level_flight_power_w(m, 12.0), 150.0);
  EXPECT_DOUBLE_EQ(level_flight_power_w(m, 24.0), 150.0 * (0.6 + 0.4 * 8));
  // A 45 degree bank (lateral acceleration g): load factor sqrt 2, power x 2^0.75.
  EXPECT_NEAR(mechanical_power_w(m, 12.0, 9.80665), 150.0 * std::pow(2.0, 0.75), 1e-9);
}

// The one state-of-charge integrator (vehicle::soc_after_charge, what swath-energy, swath-fleet
// and swath-control draw through): the capacity's worth of charge empties the pack (5 Ah: 5 A
// for an hour), and a flight drawn in random pieces ends where it ends drawn at once.
TEST(Battery, OneIntegratorEmptiesThePackAtItsCapacityAndAddsUpInPieces) {
  Battery b;
  b.capacity_ah = 5.0;
  EXPECT_DOUBLE_EQ(soc_after_charge(b, 1.0, 5.0 * 3600.0), 0.0);
  EXPECT_DOUBLE_EQ(soc_after_charge(b, 0.8, 2.5 * 1800.0), 0.55);
  std::uint64_t x = 46;
  double soc = 1.0, total_as = 0.0;
  for (int i = 0; i < 1000; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;  // fixed-seed LCG
    const double power_w = 50.0 + static_cast<double>(x >> 40) / (1 << 24) * 300.0;
    const double dt_s = 0.5;
    total_as += battery_current_a(b, power_w) * dt_s;
    soc = soc_after(b, soc, power_w, dt_s);
  }
  EXPECT_NEAR(soc, soc_after_charge(b, 1.0, total_as), 1e-12);
  EXPECT_NEAR(soc, 1.0 - total_as / (3600.0 * 5.0), 1e-12);
}

// The noise as it was written before it drew from vehicle::SplitMix64 (its own SplitMix64 and
// Box-Muller on (0, 1)): the same numbers, so every seeded flight keeps its bytes.
class OwnSplitMixNoise {
 public:
  OwnSplitMixNoise(std::uint64_t seed, double sigma) : state_(seed), sigma_(sigma) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return sigma_ * spare_;
    }
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    const double angle = 2.0 * std::numbers::pi * uniform();
    spare_ = r * std::sin(angle);
    has_spare_ = true;
    return sigma_ * r * std::cos(angle);
  }

 private:
  double uniform() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
  }
  std::uint64_t state_;
  double sigma_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

TEST(PowerModel, NoiseKeepsItsNumbersOnSwathsOneGenerator) {
  for (const std::uint64_t seed : {0ull, 1ull, 7ull, 0xdeadbeefull, ~0ull}) {
    GaussianNoise noise(seed, 1.5);
    OwnSplitMixNoise reference(seed, 1.5);
    for (int i = 0; i < 10000; ++i) ASSERT_EQ(noise.next(), reference.next()) << seed << " " << i;
  }
}

TEST(PowerModel, NoiseIsSeededAndGaussian) {
  GaussianNoise a(3, 2.0), b(3, 2.0), c(4, 2.0);
  double sum = 0, sum2 = 0;
  bool differs = false;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = a.next();
    EXPECT_EQ(x, b.next());
    differs = differs || x != c.next();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(sum / n, 0.0, 0.02);
  EXPECT_NEAR(std::sqrt(sum2 / n), 2.0, 0.02);
}

}  // namespace
}  // namespace swath::energy

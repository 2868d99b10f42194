// Sensors against their parameters: noise statistics, the bias's random walk, the converter's LSB
// and range, the low-pass step response, latency, the schedule on the integer clock, the
// specific force and field a tilted body feels, Gauss–Markov fixes, exact accumulation.
#include "swath/vehicle/sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "swath/vehicle/multirotor.hpp"

namespace swath::vehicle {
namespace {

struct Stats {
  double mean = 0, variance = 0;
};
template <typename F>
Stats stats_of(int n, F value) {
  double sum = 0, sq = 0;
  for (int i = 0; i < n; ++i) {
    const double v = value();
    sum += v;
    sq += v * v;
  }
  const double mean = sum / n;
  return {mean, sq / n - mean * mean};
}

TEST(Sensors, WhiteNoiseHasTheGivenDeviation) {
  SensorSettings s;
  s.noise = 0.01;
  Sensor gyro(s, SplitMix64::stream(1, "gyro"));
  SimTime t = 0;
  const Stats st = stats_of(20000, [&] {
    gyro.measure(t, {});
    t += s.period_ns;
    return gyro.deliver(t).back().value.x;
  });
  EXPECT_NEAR(st.mean, 0, 4 * 0.01 / std::sqrt(20000.0));
  EXPECT_NEAR(std::sqrt(st.variance), 0.01, 0.01 * 0.03);
}

TEST(Sensors, TheUnfilteredValueIsTheSameSensorWithoutItsLowPass) {
  // The same noise stream with and without a 20 Hz low-pass: the filtered sensor's unfiltered
  // value is the unfiltered sensor's value, sample by sample; its filtered value is not.
  SensorSettings plain;
  plain.noise = 0.05;
  SensorSettings filtered = plain;
  filtered.lpf_hz = 20;
  Sensor a(plain, SplitMix64::stream(3, "gyro")), b(filtered, SplitMix64::stream(3, "gyro"));
  double differs = 0;
  for (SimTime t = 0; t < 200 * plain.period_ns; t += plain.period_ns) {
    a.measure(t, {});
    b.measure(t, {});
    const SensorSample sa = a.deliver(t).back(), sb = b.deliver(t).back();
    EXPECT_EQ(sb.unfiltered.x, sa.value.x);
    EXPECT_EQ(sa.unfiltered.x, sa.value.x);
    differs = std::max(differs, std::abs(sb.value.x - sa.value.x));
  }
  EXPECT_GT(differs, 0.05);
}

TEST(Sensors, BiasWalksWithSigmaTimesRootTime) {
  // 400 sensors for 100 s each: the bias's spread is σ_rw √100.
  SensorSettings s;
  s.bias_random_walk_per_sqrt_s = 1e-3;
  s.period_ns = 100'000'000;  // 10 Hz: the walk does not depend on the rate
  int k = 0;
  const Stats st = stats_of(400, [&] {
    Sensor sensor(s, SplitMix64::stream(static_cast<std::uint64_t>(k++), "accel"));
    for (SimTime t = 0; t < 100'000'000'000; t += s.period_ns) sensor.measure(t, {});
    return sensor.bias().y;
  });
  EXPECT_NEAR(std::sqrt(st.variance), 1e-3 * 10, 1e-2 * 0.12);
}

TEST(Sensors, ConverterRangeAndLsbAndTheLowPassStep) {
  SensorSettings s;
  s.lsb = 1.065e-3;
  s.range = 34.9;
  Sensor gyro(s, SplitMix64(3));
  Truth fast;
  fast.rate_rad_s = {0.1234567, -50.0, 3.0};
  gyro.measure(0, fast);
  const Vec3 v = gyro.deliver(0).back().value;
  EXPECT_NEAR(v.x / s.lsb, std::round(v.x / s.lsb), 1e-9);
  EXPECT_NEAR(v.x, 0.1234567, s.lsb / 2);
  EXPECT_NEAR(v.y, -34.9, s.lsb / 2);  // clamped to the range, then converted
  // First-order low-pass at 10 Hz sampled at 1 kHz: after one time constant 1 − e^{−1} of a step.
  SensorSettings f;
  f.lpf_hz = 10;
  Sensor filtered(f, SplitMix64(4));
  filtered.measure(0, {});  // starts at zero
  Truth step;
  step.rate_rad_s = {1, 0, 0};
  const double tau_s = 1 / (2 * M_PI * 10);
  const int samples = static_cast<int>(std::lround(tau_s / 0.001));
  double last = 0;
  for (int i = 1; i <= samples; ++i) {
    filtered.measure(i * 1'000'000, step);
    last = filtered.deliver(i * 1'000'000).back().value.x;
  }
  EXPECT_NEAR(last, 1 - std::exp(-samples * 0.001 / tau_s), 1e-12);
}

TEST(Sensors, ScheduleOnTheIntegerClockAndLatency) {
  SensorSettings s;
  s.type = SensorType::position;
  s.period_ns = 100'000'000;  // 10 Hz
  s.phase_ns = 3'000'000;
  s.latency_s = 0.1;
  Sensor gps(s, SplitMix64(5));
  Truth at;
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(gps.next_measurement(), 3'000'000 + k * 100'000'000);
    at.position_m = {static_cast<double>(k), 0, 0};
    gps.measure(gps.next_measurement(), at);
  }
  // Measured at 3 ms + k 100 ms, delivered 100 ms later with the position of then.
  const auto delivered = gps.deliver(203'000'000);
  ASSERT_EQ(delivered.size(), 2u);
  EXPECT_EQ(delivered[1].measured_at, 103'000'000);
  EXPECT_EQ(delivered[1].delivered_at, 203'000'000);
  EXPECT_EQ(delivered[1].value.x, 1.0);
}

TEST(Sensors, ATiltedBodyFeelsGravityAndTheFieldInItsAxes) {
  Truth t;
  t.attitude = axis_angle({1, 0, 0}, M_PI / 2);  // rolled 90°: body y points up
  SensorSettings a;
  a.type = SensorType::accel;
  Sensor accel(a, SplitMix64(6));
  accel.measure(0, t);
  const Vec3 f = accel.deliver(0).back().value;
  EXPECT_NEAR(f.y, kStandardGravity_m_s2, 1e-12);  // up, along body y
  EXPECT_NEAR(f.z, 0, 1e-12);
  SensorSettings m;
  m.type = SensorType::mag;
  Sensor mag(m, SplitMix64(7));
  mag.measure(0, {});
  EXPECT_NEAR(norm(mag.deliver(0).back().value), 1.0, 1e-12);
}

TEST(Sensors, GaussMarkovFixErrorHasItsStationaryDeviation) {
  SensorSettings s;
  s.type = SensorType::position;
  s.period_ns = 100'000'000;
  s.markov_sigma_m = 0.5;
  s.markov_time_constant_s = 60;
  // Many independent receivers, sampled after 10 s: stationary from the start.
  int k = 0;
  const Stats st = stats_of(2000, [&] {
    Sensor gps(s, SplitMix64::stream(static_cast<std::uint64_t>(k++), "gps"));
    SensorSample last;
    for (SimTime t = 0; t < 10'000'000'000; t += s.period_ns) {
      gps.measure(t, {});
      last = gps.deliver(t).back();
    }
    return last.value.x;
  });
  EXPECT_NEAR(std::sqrt(st.variance), 0.5, 0.5 * 0.08);
}

TEST(Sensors, AccumulationIsExactForAConstantRateAndResets) {
  InertialAccumulator acc;
  for (int i = 0; i < 2500; ++i) {
    acc.add_gyro({0.2, -0.1, 0.05}, 0.001);
    if (i % 2 == 0) acc.add_accel({0, 0, 9.8}, 0.002);
  }
  const auto d = acc.take();
  EXPECT_NEAR(d.angle_rad.x, 0.2 * 2.5, 1e-12);
  EXPECT_NEAR(d.angle_rad.z, 0.05 * 2.5, 1e-12);
  EXPECT_NEAR(d.velocity_m_s.z, 9.8 * 2.5, 1e-10);
  EXPECT_NEAR(d.gyro_s, 2.5, 1e-12);
  EXPECT_EQ(acc.take().gyro_s, 0.0);
}

}  // namespace
}  // namespace swath::vehicle

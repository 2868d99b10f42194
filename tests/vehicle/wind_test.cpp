// Wind against closed forms: the log profile, MIL-F-8785C's scales, the forming filters' exact
// discretisation (Φ and Q in closed form, the stationary variance = σ² by the discrete Lyapunov
// equation), the simulated spectrum against Dryden's PSD per octave, gusts and regions.
#include "swath/vehicle/wind.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>

namespace swath::vehicle {
namespace {

TEST(Wind, MeanWindFollowsTheLogProfileFromItsBearing) {
  MeanWind w{4.1, 270, 6.1, 0.05, 0.0};
  const Vec3 at_ref = mean_wind_m_s(w, 6.1, 0);
  EXPECT_NEAR(at_ref.x, 4.1, 1e-12);  // from the west: towards the east
  EXPECT_NEAR(at_ref.y, 0, 1e-12);
  EXPECT_NEAR(norm(mean_wind_m_s(w, 30, 0)), 4.1 * std::log(30 / 0.05) / std::log(6.1 / 0.05),
              1e-12);
  EXPECT_EQ(norm(mean_wind_m_s(w, 0.01, 0)), 0.0);  // below the roughness length
  w.from_deg = 0;                                   // from the north: towards the south
  EXPECT_NEAR(mean_wind_m_s(w, 6.1, 0).y, -4.1, 1e-12);
  w.ramp_m_s_per_min = 0.05;
  EXPECT_NEAR(norm(mean_wind_m_s(w, 6.1, 600)), 4.1 + 0.5, 1e-12);
}

TEST(Wind, DrydenScalesOfMilF8785cAtFiveMetres) {
  // docs/swath-control.md: at 5 m, W20 4.1 m/s: σ_w 0.41, σ_u 0.80; L_w 5.0 m, L_u 36.6 m.
  const DrydenScales s = dryden_scales(5.0, 4.1);
  EXPECT_NEAR(s.sigma_w_m_s, 0.41, 1e-12);
  EXPECT_NEAR(s.sigma_u_m_s, 0.80, 0.005);
  EXPECT_EQ(s.sigma_v_m_s, s.sigma_u_m_s);
  EXPECT_NEAR(s.length_w_m, 5.0, 1e-9);
  EXPECT_NEAR(s.length_u_m, 36.6, 0.05);
  // Below 10 ft the scales of 10 ft.
  EXPECT_NEAR(dryden_scales(1.0, 4.1).length_w_m, 3.048, 1e-12);
}

TEST(Wind, ExactDiscretisationAndStationaryVarianceIsSigmaSquared) {
  for (double tau : {0.2, 1.0, 7.3}) {
    for (double dt : {0.001, 0.005, 0.05}) {
      const double sigma = 0.8;
      const DiscreteFilter u = discretise(longitudinal_filter(sigma, tau), dt);
      // First order in closed form: Φ = e^{−dt/τ}, Q = σ² (1 − e^{−2 dt/τ}).
      EXPECT_NEAR(u.phi[0], std::exp(-dt / tau), 1e-14);
      EXPECT_NEAR(u.q[0], sigma * sigma * (1 - std::exp(-2 * dt / tau)), 1e-14);
      EXPECT_NEAR(u.output_variance(), sigma * sigma, 1e-12 * sigma * sigma);
      const DiscreteFilter w = discretise(transverse_filter(sigma, tau), dt);
      EXPECT_NEAR(w.output_variance(), sigma * sigma, 1e-12 * sigma * sigma) << tau << " " << dt;
      // Φ of the double pole: e^{−dt/τ} [[1 + dt/τ, dt], [−dt/τ², 1 − dt/τ]].
      const double e = std::exp(-dt / tau);
      EXPECT_NEAR(w.phi[0], e * (1 + dt / tau), 1e-13);
      EXPECT_NEAR(w.phi[1], e * dt, 1e-13);
      EXPECT_NEAR(w.phi[2], -e * dt / (tau * tau), 1e-13 / (tau * tau));
      EXPECT_NEAR(w.phi[3], e * (1 - dt / tau), 1e-13);
    }
  }
}

// One-sided PSD in m²/s²/Hz of the forming filters driven by unit-intensity white noise:
// G(f) = 2 |H(j 2π f)|².
double dryden_psd(bool longitudinal, double sigma, double tau, double f) {
  const double x = 2 * M_PI * f * tau;
  if (longitudinal) return 2 * sigma * sigma * 2 * tau / (1 + x * x);
  return 2 * sigma * sigma * tau * (1 + 3 * x * x) / ((1 + x * x) * (1 + x * x));
}

TEST(Wind, SimulatedSpectrumIsDrydensWithinFifteenPercentPerOctave) {
  const DrydenScales s = dryden_scales(5.0, 4.1);
  const double speed = 5.0, dt = 0.005;
  DrydenTurbulence turbulence(s, speed, dt, SplitMix64::stream(42, "turbulence"));
  constexpr int kSegment = 8192, kSegments = 128;
  std::array<std::vector<double>, 3> psd;
  for (auto& p : psd) p.assign(kSegment / 2, 0.0);
  std::vector<double> window(kSegment);
  double window_power = 0;
  for (int i = 0; i < kSegment; ++i) {
    window[i] = 0.5 - 0.5 * std::cos(2 * M_PI * i / kSegment);  // Hann
    window_power += window[i] * window[i];
  }
  Eigen::FFT<double> fft;
  std::array<std::vector<double>, 3> x;
  for (auto& v : x) v.resize(kSegment);
  std::vector<std::complex<double>> spectrum;
  for (int seg = 0; seg < kSegments; ++seg) {
    for (int i = 0; i < kSegment; ++i) {
      const auto sample = turbulence.step();
      for (int k = 0; k < 3; ++k) x[k][i] = sample[k] * window[i];
    }
    for (int k = 0; k < 3; ++k) {
      fft.fwd(spectrum, x[k]);
      for (int j = 1; j < kSegment / 2; ++j)
        psd[k][j] += 2 * dt * std::norm(spectrum[j]) / window_power / kSegments;
    }
  }
  const double df = 1.0 / (kSegment * dt);
  const double taus[3] = {s.length_u_m / speed, s.length_v_m / speed, s.length_w_m / speed};
  const double sigmas[3] = {s.sigma_u_m_s, s.sigma_v_m_s, s.sigma_w_m_s};
  for (int k = 0; k < 3; ++k) {
    for (double lo = 0.1; lo < 12; lo *= 2) {
      double measured = 0, expected = 0;
      for (int j = 1; j < kSegment / 2; ++j) {
        const double f = j * df;
        if (f < lo || f >= 2 * lo) continue;
        measured += psd[k][j];
        expected += dryden_psd(k == 0, sigmas[k], taus[k], f);
      }
      EXPECT_NEAR(measured / expected, 1.0, 0.15) << "axis " << k << ", octave from " << lo;
    }
  }
}

TEST(Wind, GustsRiseHoldAndFallAsOneMinusCosine) {
  EXPECT_EQ(Gusts::shape(-1, 1, 2), 0.0);
  EXPECT_NEAR(Gusts::shape(0.5, 1, 2), 0.5, 1e-15);
  EXPECT_NEAR(Gusts::shape(1.0, 1, 2), 1.0, 1e-15);
  EXPECT_EQ(Gusts::shape(2.5, 1, 2), 1.0);
  EXPECT_NEAR(Gusts::shape(3.5, 1, 2), 0.5, 1e-15);
  EXPECT_EQ(Gusts::shape(4.0 + 1e-9, 1, 2), 0.0);
  // Arrivals are Poisson: over 10 hours at 3 per minute, 1800 ± 4·√1800 gusts. A gust raises the
  // wind from zero: count the rises from rest.
  GustSettings gust_settings;
  gust_settings.rate_per_min = 3;
  gust_settings.rise_s = {0.01, 0.01};
  gust_settings.hold_s = {0, 0};
  Gusts gusts(gust_settings, SplitMix64::stream(7, "gusts"));
  int starts = 0;
  bool calm = true;
  double peak = 0;
  for (double t = 0; t < 36000; t += 0.005) {
    const double v = norm(gusts.at(t));
    peak = std::max(peak, v);
    if (calm && v > 0) ++starts;
    calm = v == 0;
  }
  EXPECT_NEAR(starts, 1800, 4 * std::sqrt(1800.0));
  EXPECT_LE(peak, 2 * 2.5);  // two overlapping gusts at most, in practice
}

TEST(Wind, RegionsAddTheirWindInsideTheirCylinder) {
  const std::vector<WindRegion> duct{{{5, 5}, 1.5, {0, 0, -1}}};
  EXPECT_EQ(region_wind_m_s(duct, {5.5, 4.0, 3}).z, -1.0);
  EXPECT_EQ(region_wind_m_s(duct, {7, 5, 3}).z, 0.0);
}

// The one wind convention: FROM a bearing clockwise from north; the velocity points where the
// air goes. The compass points by hand (independent truth), then a seeded property: a velocity
// taken to its bearing and speed and back is the same velocity, and each form is kept exactly.
TEST(Wind, BlowsFromItsBearingAndKeepsTheFormItWasMadeIn) {
  struct Point {
    double from_deg, east_m_s, north_m_s;
  };
  // 5 m/s from the north blows south; from the east blows west; and so on.
  for (const Point& p : {Point{0, 0, -5}, Point{90, -5, 0}, Point{180, 0, 5}, Point{270, 5, 0}}) {
    const geometry::Point2 v = Wind(5, p.from_deg).velocity_m_s();
    EXPECT_NEAR(v.x, p.east_m_s, 1e-12) << p.from_deg;
    EXPECT_NEAR(v.y, p.north_m_s, 1e-12) << p.from_deg;
    const Wind w = Wind::from_velocity(p.east_m_s, p.north_m_s);
    EXPECT_NEAR(w.from_deg(), p.from_deg, 1e-12) << p.from_deg;
    EXPECT_EQ(w.speed_m_s(), 5.0);
  }
  EXPECT_EQ(Wind().speed_m_s(), 0.0);
  EXPECT_EQ(Wind::from_velocity(0, 0).from_deg(), 0.0);
  EXPECT_FALSE(std::signbit(Wind::from_velocity(0.0, -3).from_deg()));  // 0, not -0
  SplitMix64 random(46);
  for (int i = 0; i < 2000; ++i) {
    const double east_m_s = 40 * random.uniform() - 20, north_m_s = 40 * random.uniform() - 20;
    const Wind w = Wind::from_velocity(east_m_s, north_m_s);
    // Kept exactly: the velocity as given, bit for bit.
    EXPECT_EQ(w.velocity_m_s().x, east_m_s);
    EXPECT_EQ(w.velocity3_m_s().y, north_m_s);
    EXPECT_GE(w.from_deg(), 0.0);
    EXPECT_LT(w.from_deg(), 360.0);
    const geometry::Point2 back = Wind(w.speed_m_s(), w.from_deg()).velocity_m_s();
    EXPECT_NEAR(back.x, east_m_s, 1e-12);
    EXPECT_NEAR(back.y, north_m_s, 1e-12);
    // And a bearing as given, bit for bit (a velocity round trip would not be).
    const double from_deg = 360 * random.uniform();
    EXPECT_EQ(Wind(3.7, from_deg).from_deg(), from_deg);
    EXPECT_EQ(Wind(3.7, from_deg).speed_m_s(), 3.7);
  }
}

}  // namespace
}  // namespace swath::vehicle

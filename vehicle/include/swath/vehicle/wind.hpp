#pragma once
// The wind of docs/swath-control.md: a mean wind with a logarithmic profile and an optional ramp,
// Dryden turbulence (MIL-F-8785C, low altitude) from forming filters discretised exactly, discrete
// 1 − cos gusts with Poisson arrivals, and regions of fixed added wind. World ENU, m/s. Each part
// draws from its own named random stream (common random numbers across runs that differ in
// anything else).

#include <array>
#include <cstdint>
#include <vector>

#include "swath/geometry/point.hpp"
#include "swath/vehicle/random.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::vehicle {

/// A steady wind, swath's one convention: the direction it blows FROM, degrees clockwise from
/// north (0 from the north, 90 from the east), and its speed, m/s; velocity_m_s() is the air's
/// velocity (east, north, m/s: it points where the wind blows TO). A wind keeps the form it was
/// made in exactly and computes the other on request — a bearing-to-vector round trip is not
/// bit-exact, and each program's outputs stay those of the form its users give (swath-energy's
/// `wind: {speed_m_s, from_deg}`, swath-fleet's `--wind E,N`).
class Wind {
 public:
  Wind() = default;  ///< calm
  /// `speed_m_s` (>= 0) blowing from the compass bearing `from_deg` (degrees clockwise from north).
  Wind(double speed_m_s, double from_deg) : first_(speed_m_s), second_(from_deg) {}
  /// The wind whose air moves at (east_m_s, north_m_s).
  static Wind from_velocity(double east_m_s, double north_m_s);

  double speed_m_s() const;
  /// Degrees clockwise from north the wind blows from: as given when made from a bearing; in
  /// [0, 360) when made from a velocity (0 when calm).
  double from_deg() const;
  /// The air's velocity, x east and y north, m/s.
  geometry::Point2 velocity_m_s() const;
  /// The same with z = 0 (world ENU).
  Vec3 velocity3_m_s() const;

 private:
  bool from_vector_ = false;
  double first_ = 0.0, second_ = 0.0;  ///< speed and bearing, or east and north
};

/// Mean wind given at `reference_height_m`, blowing FROM the compass bearing `from_deg`
/// (degrees clockwise from north), growing by `ramp_m_s_per_min`.
struct MeanWind {
  double speed_m_s = 0.0;           ///< >= 0, at the reference height
  double from_deg = 0.0;            ///< compass bearing the wind comes from, degrees
  double reference_height_m = 6.1;  ///< 20 ft, the MIL-F-8785C reference
  double roughness_m = 0.03;        ///< z0 of the log profile, > 0
  double ramp_m_s_per_min = 0.0;    ///< the reference speed's growth
};

/// The mean wind at `height_m` above ground at time `t_s`: u(h) = u_ref ln(h / z0) / ln(h_ref /
/// z0), zero at or below z0.
Vec3 mean_wind_m_s(const MeanWind& wind, double height_m, double t_s);

/// Dryden's scales at height h (MIL-F-8785C low altitude, h in ft, at least 10 ft):
/// L_w = h, L_u = L_v = h / (0.177 + 0.000823 h)^1.2; σ_w = 0.1 W20,
/// σ_u = σ_v = σ_w / (0.177 + 0.000823 h)^0.4. Lengths in metres, intensities in m/s.
struct DrydenScales {
  double sigma_u_m_s = 0, sigma_v_m_s = 0, sigma_w_m_s = 0;
  double length_u_m = 0, length_v_m = 0, length_w_m = 0;
};
DrydenScales dryden_scales(double height_m, double w20_m_s);

/// One forming filter as a linear system driven by unit-intensity white noise w:
/// ẋ = A x + B w, output y = C x (n = 1 for u, 2 for v and w). Row-major A (n x n).
struct FormingFilter {
  int order = 1;
  std::array<double, 4> a{};  ///< A, row-major
  std::array<double, 2> b{};  ///< B
  std::array<double, 2> c{};  ///< C
};
/// σ √(2τ) / (1 + τ s): the longitudinal filter.
FormingFilter longitudinal_filter(double sigma_m_s, double tau_s);
/// σ √τ (1 + √3 τ s) / (1 + τ s)²: the lateral and vertical filter.
FormingFilter transverse_filter(double sigma_m_s, double tau_s);

/// The exact discretisation of a filter over `dt_s` (Van Loan's matrix exponential):
/// x_{k+1} = Φ x_k + n_k, n_k ~ N(0, Q) with Q the integrated noise covariance.
struct DiscreteFilter {
  FormingFilter filter;
  std::array<double, 4> phi{};         ///< Φ = exp(A dt), row-major
  std::array<double, 4> q{};           ///< Q, row-major, symmetric
  std::array<double, 4> q_cholesky{};  ///< lower L with L Lᵀ = Q
  /// The stationary covariance P = Φ P Φᵀ + Q (discrete Lyapunov), row-major.
  std::array<double, 4> stationary{};
  /// C P Cᵀ: the output's stationary variance (σ² for Dryden's filters).
  double output_variance() const;
};
DiscreteFilter discretise(const FormingFilter& filter, double dt_s);

/// Dryden turbulence along the mean wind (u), across it (v) and vertical (w), advanced in equal
/// steps of `dt_s`; started in its stationary distribution. V = max(mean wind, mission speed,
/// 1 m/s) (a hovering drone carries no frozen field).
class DrydenTurbulence {
 public:
  DrydenTurbulence(const DrydenScales& scales, double speed_m_s, double dt_s, SplitMix64 random);
  /// The next sample, [u, v, w] in m/s.
  std::array<double, 3> step();
  const DiscreteFilter& axis(int k) const { return axes_[k]; }

 private:
  std::array<DiscreteFilter, 3> axes_;
  std::array<std::array<double, 2>, 3> state_{};
  SplitMix64 random_;
};

/// Discrete gusts: arrivals at `rate_per_min` (Poisson), each rising as 1 − cos over a rise
/// time, holding, and falling as 1 − cos again; amplitude, rise and hold drawn uniformly from
/// their [lo, hi]; direction uniform in the horizontal, with `vertical_share` of the amplitude
/// up or down.
struct GustSettings {
  double rate_per_min = 0.0;
  std::array<double, 2> amplitude_m_s{1, 2.5}, rise_s{0.5, 1.5}, hold_s{0, 2};
  double vertical_share = 0.1;
};

class Gusts {
 public:
  Gusts(const GustSettings& settings, SplitMix64 random);
  /// The gust wind at `t_s` (non-decreasing across calls), world ENU.
  Vec3 at(double t_s);
  /// The shape of one gust of unit amplitude at `t_s` from its start: 1 − cos rise, hold, fall.
  static double shape(double t_s, double rise_s, double hold_s);

 private:
  struct Gust {
    double start_s, amplitude_m_s, rise_s, hold_s;
    Vec3 direction;
  };
  void schedule_next(double after_s);

  GustSettings settings_;
  SplitMix64 random_;
  std::vector<Gust> active_;
  double next_start_s_ = 0.0;
};

/// A vertical cylinder of fixed added wind (LAB's ceiling duct).
struct WindRegion {
  std::array<double, 2> center_m{};  ///< east, north
  double radius_m = 0.0;
  Vec3 wind_m_s;
};
/// The sum of the regions' winds at `position_m` (world ENU).
Vec3 region_wind_m_s(const std::vector<WindRegion>& regions, const Vec3& position_m);

}  // namespace swath::vehicle

#include "swath/vehicle/wind.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

namespace swath::vehicle {
namespace {

constexpr double kFeetPerMetre = 1.0 / 0.3048;
constexpr double kDeg = std::numbers::pi / 180.0;

// The unit vector the wind blows towards, from the compass bearing it comes from.
Vec3 towards(double from_deg) {
  return {-std::sin(from_deg * kDeg), -std::cos(from_deg * kDeg), 0.0};
}

}  // namespace

Wind Wind::from_velocity(double east_m_s, double north_m_s) {
  Wind w;
  w.from_vector_ = true;
  w.first_ = east_m_s;
  w.second_ = north_m_s;
  return w;
}

double Wind::speed_m_s() const {
  return from_vector_ ? std::hypot(first_, second_) : first_;
}

double Wind::from_deg() const {
  if (!from_vector_) return second_;
  if (first_ == 0.0 && second_ == 0.0) return 0.0;
  // The air moves towards b + 180: it comes from the bearing of (-east, -north).
  const double b = std::atan2(-first_, -second_) / kDeg;
  const double wrapped = b < 0.0 ? b + 360.0 : b + 0.0;  // + 0.0: no -0
  return wrapped >= 360.0 ? 0.0 : wrapped;               // a tiny negative bearing rounds up to 360
}

geometry::Point2 Wind::velocity_m_s() const {
  if (from_vector_) return {first_, second_};
  // From bearing b the air moves towards b + 180: east = -sin b, north = -cos b (written as
  // swath-energy always computed it, so its outputs keep every bit).
  const double b = second_ * std::numbers::pi / 180.0;
  return {-first_ * std::sin(b), -first_ * std::cos(b)};
}

Vec3 Wind::velocity3_m_s() const {
  const geometry::Point2 v = velocity_m_s();
  return {v.x, v.y, 0.0};
}

Vec3 mean_wind_m_s(const MeanWind& w, double height_m, double t_s) {
  const double speed_ref = std::max(0.0, w.speed_m_s + w.ramp_m_s_per_min * t_s / 60.0);
  if (!(height_m > w.roughness_m) || speed_ref == 0.0) return {};
  const double factor =
      std::log(height_m / w.roughness_m) / std::log(w.reference_height_m / w.roughness_m);
  return towards(w.from_deg) * (speed_ref * factor);
}

DrydenScales dryden_scales(double height_m, double w20_m_s) {
  const double h_ft = std::max(10.0, height_m * kFeetPerMetre);
  const double k = 0.177 + 0.000823 * h_ft;
  DrydenScales s;
  s.length_w_m = h_ft / kFeetPerMetre;
  s.length_u_m = s.length_v_m = h_ft / std::pow(k, 1.2) / kFeetPerMetre;
  s.sigma_w_m_s = 0.1 * w20_m_s;
  s.sigma_u_m_s = s.sigma_v_m_s = s.sigma_w_m_s / std::pow(k, 0.4);
  return s;
}

FormingFilter longitudinal_filter(double sigma, double tau) {
  // ẋ = −x/τ + (σ √(2τ) / τ) w, y = x.
  FormingFilter f;
  f.order = 1;
  f.a[0] = -1.0 / tau;
  f.b[0] = sigma * std::sqrt(2 * tau) / tau;
  f.c[0] = 1.0;
  return f;
}

FormingFilter transverse_filter(double sigma, double tau) {
  // Controllable canonical form of (σ √τ / τ²)(1 + √3 τ s) / (s + 1/τ)²:
  // ẋ1 = x2, ẋ2 = −x1/τ² − 2 x2/τ + w, y = (σ √τ / τ²)(x1 + √3 τ x2).
  FormingFilter f;
  f.order = 2;
  f.a = {0.0, 1.0, -1.0 / (tau * tau), -2.0 / tau};
  f.b = {0.0, 1.0};
  const double gain = sigma * std::sqrt(tau) / (tau * tau);
  f.c = {gain, gain * std::sqrt(3.0) * tau};
  return f;
}

double DiscreteFilter::output_variance() const {
  const int n = filter.order;
  double v = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) v += filter.c[i] * stationary[i * n + j] * filter.c[j];
  return v;
}

DiscreteFilter discretise(const FormingFilter& filter, double dt_s) {
  const int n = filter.order;
  Eigen::MatrixXd a(n, n), b(n, 1);
  for (int i = 0; i < n; ++i) {
    b(i, 0) = filter.b[i];
    for (int j = 0; j < n; ++j) a(i, j) = filter.a[i * n + j];
  }
  // Van Loan (1978): exp([−A, B Bᵀ; 0, Aᵀ] dt) = [·, Φ⁻¹ Q; 0, Φᵀ].
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  m.topLeftCorner(n, n) = -a * dt_s;
  m.topRightCorner(n, n) = b * b.transpose() * dt_s;
  m.bottomRightCorner(n, n) = a.transpose() * dt_s;
  const Eigen::MatrixXd e = m.exp();
  const Eigen::MatrixXd phi = e.bottomRightCorner(n, n).transpose();
  Eigen::MatrixXd q = phi * e.topRightCorner(n, n);
  q = 0.5 * (q + q.transpose());
  // Stationary covariance: vec(P) = (I − Φ ⊗ Φ)⁻¹ vec(Q).
  Eigen::MatrixXd kron(n * n, n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) kron.block(i * n, j * n, n, n) = phi(i, j) * phi;
  const Eigen::VectorXd vec_q = Eigen::Map<const Eigen::VectorXd>(q.data(), n * n);
  const Eigen::VectorXd vec_p =
      (Eigen::MatrixXd::Identity(n * n, n * n) - kron).fullPivLu().solve(vec_q);
  Eigen::MatrixXd p = Eigen::Map<const Eigen::MatrixXd>(vec_p.data(), n, n);
  p = 0.5 * (p + p.transpose());
  const Eigen::MatrixXd l = q.llt().matrixL();
  DiscreteFilter d;
  d.filter = filter;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      d.phi[i * n + j] = phi(i, j);
      d.q[i * n + j] = q(i, j);
      d.q_cholesky[i * n + j] = l(i, j);
      d.stationary[i * n + j] = p(i, j);
    }
  return d;
}

DrydenTurbulence::DrydenTurbulence(const DrydenScales& s, double speed_m_s, double dt_s,
                                   SplitMix64 random)
    : random_(random) {
  const double v = std::max({speed_m_s, 1.0});
  axes_[0] = discretise(longitudinal_filter(s.sigma_u_m_s, s.length_u_m / v), dt_s);
  axes_[1] = discretise(transverse_filter(s.sigma_v_m_s, s.length_v_m / v), dt_s);
  axes_[2] = discretise(transverse_filter(s.sigma_w_m_s, s.length_w_m / v), dt_s);
  // Start stationary: x ~ N(0, P), drawn through P's Cholesky factor.
  for (int k = 0; k < 3; ++k) {
    const DiscreteFilter& d = axes_[k];
    const int n = d.filter.order;
    Eigen::MatrixXd p(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) p(i, j) = d.stationary[i * n + j];
    const Eigen::MatrixXd l = p.llt().matrixL();
    std::array<double, 2> z{random_.normal(), n > 1 ? random_.normal() : 0.0};
    for (int i = 0; i < n; ++i) {
      state_[k][i] = 0;
      for (int j = 0; j <= i; ++j) state_[k][i] += l(i, j) * z[j];
    }
  }
}

std::array<double, 3> DrydenTurbulence::step() {
  std::array<double, 3> out{};
  for (int k = 0; k < 3; ++k) {
    const DiscreteFilter& d = axes_[k];
    const int n = d.filter.order;
    const std::array<double, 2> z{random_.normal(), n > 1 ? random_.normal() : 0.0};
    std::array<double, 2> next{};
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) next[i] += d.phi[i * n + j] * state_[k][j];
      for (int j = 0; j <= i; ++j) next[i] += d.q_cholesky[i * n + j] * z[j];
    }
    state_[k] = next;
    for (int i = 0; i < n; ++i) out[k] += d.filter.c[i] * next[i];
  }
  return out;
}

double Gusts::shape(double t, double rise, double hold) {
  if (t <= 0) return 0.0;
  if (t < rise) return 0.5 * (1 - std::cos(std::numbers::pi * t / rise));
  if (t <= rise + hold) return 1.0;
  const double fall = t - rise - hold;
  if (fall < rise) return 0.5 * (1 + std::cos(std::numbers::pi * fall / rise));
  return 0.0;
}

Gusts::Gusts(const GustSettings& settings, SplitMix64 random)
    : settings_(settings), random_(random) {
  schedule_next(0.0);
}

void Gusts::schedule_next(double after_s) {
  next_start_s_ = settings_.rate_per_min > 0
                      ? after_s + random_.exponential(settings_.rate_per_min / 60.0)
                      : INFINITY;
}

Vec3 Gusts::at(double t_s) {
  auto draw = [&](const std::array<double, 2>& range) {
    return random_.uniform(range[0], range[1]);
  };
  while (next_start_s_ <= t_s) {
    Gust g;
    g.start_s = next_start_s_;
    g.amplitude_m_s = draw(settings_.amplitude_m_s);
    g.rise_s = std::max(1e-3, draw(settings_.rise_s));
    g.hold_s = draw(settings_.hold_s);
    const double bearing = random_.uniform(0, 2 * std::numbers::pi);
    const double up = random_.uniform() < 0.5 ? -1.0 : 1.0;
    const double h =
        std::sqrt(std::max(0.0, 1 - settings_.vertical_share * settings_.vertical_share));
    g.direction = {h * std::sin(bearing), h * std::cos(bearing), up * settings_.vertical_share};
    active_.push_back(g);
    schedule_next(g.start_s);
  }
  Vec3 sum{};
  std::erase_if(active_, [&](const Gust& g) { return t_s - g.start_s > 2 * g.rise_s + g.hold_s; });
  for (const Gust& g : active_)
    sum += g.direction * (g.amplitude_m_s * shape(t_s - g.start_s, g.rise_s, g.hold_s));
  return sum;
}

Vec3 region_wind_m_s(const std::vector<WindRegion>& regions, const Vec3& p) {
  Vec3 sum{};
  for (const WindRegion& r : regions)
    if (std::hypot(p.x - r.center_m[0], p.y - r.center_m[1]) <= r.radius_m) sum += r.wind_m_s;
  return sum;
}

}  // namespace swath::vehicle

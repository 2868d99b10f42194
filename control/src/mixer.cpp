#include "swath/control/mixer.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace swath::control {
namespace {

using Forces = std::array<double, kMaxRotors>;

bool layout_valid(const MixerRotors& l) {
  if (l.count < 4 || l.count > kMaxRotors) return false;
  if (!(l.thrust_coeff_n_s2 > 0) || !(l.torque_coeff_nm_s2 > 0) || !(l.max_speed_rad_s > 0))
    return false;
  if (!(l.pwm_max_us > l.pwm_min_us) || !(l.resolution_us > 0)) return false;
  for (std::size_t i = 0; i < l.count; ++i)
    if (!(l.rotors[i].efficiency > 0) || !(l.rotors[i].efficiency <= 1)) return false;
  return true;
}

Forces times_column(const MixerMatrices& m, std::size_t axis, double value) {
  Forces f{};
  for (std::size_t i = 0; i < m.count; ++i) f[i] = m.pseudo_inverse[i][axis] * value;
  return f;
}

// The largest k in [0, 1] with lo <= base + k·dir <= hi for every rotor, given base in range
// (forces a hair outside by rounding count as on the bound).
double largest_scale(const Forces& base, const Forces& dir, std::size_t n, double hi) {
  double k = 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (dir[i] > 0)
      k = std::min(k, (hi - base[i]) / dir[i]);
    else if (dir[i] < 0)
      k = std::min(k, (0.0 - base[i]) / dir[i]);
  }
  return std::clamp(k, 0.0, 1.0);
}

void add_scaled(Forces& f, const Forces& dir, double k, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) f[i] += k * dir[i];
}

}  // namespace

std::optional<MixerMatrices> mixer_matrices(const MixerRotors& layout) {
  if (!layout_valid(layout)) return std::nullopt;
  const auto n = static_cast<Eigen::Index>(layout.count);
  Eigen::MatrixXd a(4, n);
  const double yaw_per_newton = layout.torque_coeff_nm_s2 / layout.thrust_coeff_n_s2;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Rotor& r = layout.rotors[static_cast<std::size_t>(i)];
    const double eta = r.efficiency;
    // r × (η f e3) = η f (y, −x, 0); the drag torque −s k_Q Ω² = −s (k_Q / k_T) f about +z.
    a(0, i) = eta;
    a(1, i) = eta * r.position_m.y;
    a(2, i) = -eta * r.position_m.x;
    a(3, i) = (r.ccw ? -1.0 : 1.0) * yaw_per_newton;
  }
  // Rank by SVD with a relative tolerance: a frame whose singular values spread by more than
  // 1e9 cannot be flown with finite forces either.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
  const auto& s = svd.singularValues();
  if (!(s(3) > 1e-9 * s(0))) return std::nullopt;
  const Eigen::MatrixXd pinv = a.transpose() * (a * a.transpose()).inverse();
  MixerMatrices m;
  m.count = layout.count;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index r = 0; r < 4; ++r) {
      m.effectiveness[static_cast<std::size_t>(r)][static_cast<std::size_t>(i)] = a(r, i);
      m.pseudo_inverse[static_cast<std::size_t>(i)][static_cast<std::size_t>(r)] = pinv(i, r);
    }
  return m;
}

double quantise_pwm_us(const MixerRotors& layout, double u) {
  const double span = layout.pwm_max_us - layout.pwm_min_us;
  const double levels = std::floor(span / layout.resolution_us + 1e-9);
  const double share = u >= 0 ? std::min(u, 1.0) : 0.0;  // NaN: no thrust
  const double level = std::clamp(std::round(share * span / layout.resolution_us), 0.0, levels);
  return layout.pwm_min_us + level * layout.resolution_us;
}

namespace {

// The collectives t for which 0 <= t·u_i + k·rp_i <= hi holds for every rotor (u the force per
// newton of collective), as [lo, high]; empty when lo > high.
struct Interval {
  double lo = 0, high = 0;
};
Interval collective_range(const Forces& u, const Forces& rp, double k, std::size_t n, double hi) {
  Interval r{0.0, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < n; ++i) {
    const double a = k * rp[i];
    if (u[i] > 1e-12) {
      r.lo = std::max(r.lo, -a / u[i]);
      r.high = std::min(r.high, (hi - a) / u[i]);
    } else if (a < -1e-12 || a > hi + 1e-12) {  // a rotor the collective cannot move
      r.lo = std::numeric_limits<double>::infinity();
    }
  }
  return r;
}

}  // namespace

MixerOutput mix(const MixerRotors& layout, const MixerMatrices& m, const Wrench& request) {
  MixerOutput out;
  const std::size_t n = m.count;
  const double f_max = layout.max_rotor_force_n();
  auto finite_or_zero = [](double v) { return std::isfinite(v) ? v : 0.0; };
  const double thrust = std::isfinite(request.thrust_n) ? std::max(request.thrust_n, 0.0) : 0.0;
  const Forces per_newton = times_column(m, 0, 1.0);
  Forces f_rp = times_column(m, 1, finite_or_zero(request.torque_nm.x));
  add_scaled(f_rp, times_column(m, 2, finite_or_zero(request.torque_nm.y)), 1.0, n);

  // 1. Roll and pitch first (their direction kept), as ArduPilot's and PX4's mixers do: the
  // largest scale k <= 1 for which some collective keeps every rotor in range. Feasibility is
  // monotone in k (the range of k·rp only widens), so bisection finds it.
  double k = 1.0;
  auto feasible = [&](double scale) {
    const Interval r = collective_range(per_newton, f_rp, scale, n, f_max);
    return r.lo <= r.high;
  };
  if (!feasible(1.0)) {
    double lo = 0.0, hi = 1.0;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      (feasible(mid) ? lo : hi) = mid;
    }
    k = lo;
  }
  out.roll_pitch_scale = k;
  // 2. The collective nearest the request that leaves room for them: reduced when rotors would
  // saturate high, raised when they would stop (attitude before altitude, for a moment).
  const Interval range = collective_range(per_newton, f_rp, k, n, f_max);
  const double collective = std::clamp(thrust, range.lo, std::max(range.lo, range.high));
  out.thrust_clipped = collective != thrust;
  Forces f{};
  add_scaled(f, per_newton, collective, n);
  add_scaled(f, f_rp, k, n);
  // 3. Yaw with what is left: the weakest axis of a multirotor is given up first.
  const Forces f_yaw = times_column(m, 3, finite_or_zero(request.torque_nm.z));
  out.yaw_scale = largest_scale(f, f_yaw, n, f_max);
  add_scaled(f, f_yaw, out.yaw_scale, n);

  double w[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    f[i] = std::clamp(f[i], 0.0, f_max);  // rounding only: f is in range by construction
    for (std::size_t r = 0; r < 4; ++r) w[r] += m.effectiveness[r][i] * f[i];
    // 4. The pulse, quantised, and the speed it commands.
    const double share = f[i] / f_max;
    const bool thrust_linear = layout.mapping == EscMapping::thrust_linear;
    const double pwm = quantise_pwm_us(layout, thrust_linear ? share : std::sqrt(share));
    const double u = (pwm - layout.pwm_min_us) / (layout.pwm_max_us - layout.pwm_min_us);
    out.force_n[i] = f[i];
    out.pwm_us[i] = pwm;
    out.speed_cmd_rad_s[i] = layout.max_speed_rad_s * (thrust_linear ? std::sqrt(u) : u);
  }
  out.achieved = Wrench{w[0], {w[1], w[2], w[3]}};
  return out;
}

}  // namespace swath::control

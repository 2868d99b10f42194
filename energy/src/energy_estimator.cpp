#include "swath/energy/energy_estimator.hpp"

#include <cmath>

namespace swath::energy {
namespace {

// M <- R M R^T for the block-diagonal rotation R = exp(A dt), O(m^2).
void rotate_both_sides(const FourierModel& model, std::vector<double>& p) {
  const int n = model.states();
  auto rotate = [&](auto&& at) {
    for (int j = 0; j < model.order; ++j) {
      const int i = 1 + 2 * j;
      const double c = model.cos_dt[j], s = model.sin_dt[j];
      for (int k = 0; k < n; ++k) {
        double& x = at(i, k);
        double& y = at(i + 1, k);
        const double nx = c * x + s * y;
        y = -s * x + c * y;
        x = nx;
      }
    }
  };
  rotate([&](int r, int k) -> double& { return p[r * n + k]; });  // rows: R M
  rotate([&](int r, int k) -> double& { return p[k * n + r]; });  // columns: (R M) R^T
}

}  // namespace

EnergyEstimator::EnergyEstimator(const FourierModel& model, const KalmanSettings& settings,
                                 double first_w)
    : model_(model), settings_(settings), q_(state_of_measurement(first_w, model)) {
  const int n = model_.states();
  p_.assign(static_cast<std::size_t>(n * n), 0.0);
  const double sd = model_.period_s * settings_.initial_w;
  for (int i = 0; i < n; ++i) p_[i * n + i] = sd * sd;
}

void EnergyEstimator::predict(double power_step_w) {
  advance_state(model_, q_);
  if (power_step_w != 0.0) apply_power_step(model_, q_, power_step_w);
  rotate_both_sides(model_, p_);
  const int n = model_.states();
  const double sd = model_.period_s * settings_.process_w;
  const double q = sd * sd * model_.dt_s;
  for (int i = 0; i < n; ++i) p_[i * n + i] += q;
}

bool EnergyEstimator::correct(double measured_w) {
  if (!std::isfinite(measured_w)) return false;  // no measurement: open loop
  const double innovation = measured_w - output_w();
  if (std::abs(innovation) <= settings_.gate_w) return false;
  const int n = model_.states();
  const double inv_t = 1.0 / model_.period_s;
  // C has 1/T at index 0 and at every alpha_j.
  auto c_at = [&](int i) { return (i == 0 || i % 2 == 1) ? inv_t : 0.0; };
  std::vector<double>& pc = pc_;  // P C^T
  pc.assign(n, 0.0);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < n; ++k) pc[r] += p_[r * n + k] * c_at(k);
  double s = settings_.measurement_w * settings_.measurement_w;
  for (int k = 0; k < n; ++k) s += c_at(k) * pc[k];
  std::vector<double>& gain = gain_;
  gain.resize(n);
  for (int r = 0; r < n; ++r) gain[r] = pc[r] / s;
  for (int r = 0; r < n; ++r) q_[r] += gain[r] * innovation;
  // Joseph form: P <- (I - K C) P (I - K C)^T + K R K^T; C P = (P C^T)^T as P is symmetric.
  std::vector<double>& x = x_;
  x = p_;
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < n; ++k) x[r * n + k] -= gain[r] * pc[k];  // X = (I - K C) P
  std::vector<double>& xc = xc_;                                  // X C^T
  xc.assign(n, 0.0);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < n; ++k) xc[r] += x[r * n + k] * c_at(k);
  const double rr = settings_.measurement_w * settings_.measurement_w;
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < n; ++k)
      p_[r * n + k] = x[r * n + k] - xc[r] * gain[k] + gain[r] * rr * gain[k];
  for (int r = 0; r < n; ++r)  // symmetric to the last bit, so rounding cannot build up
    for (int k = r + 1; k < n; ++k)
      p_[r * n + k] = p_[k * n + r] = 0.5 * (p_[r * n + k] + p_[k * n + r]);
  ++corrections_;
  return true;
}

void EnergyEstimator::set_period(double period_s) {
  const double scale = period_s / model_.period_s;
  model_ = with_period(model_, q_, period_s);
  for (double& v : p_) v *= scale * scale;
}

}  // namespace swath::energy

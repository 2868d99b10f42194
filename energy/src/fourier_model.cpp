#include "swath/energy/fourier_model.hpp"

#include <cmath>
#include <numbers>

namespace swath::energy {

FourierModel fourier_model(int order, double period_s, double dt_s) {
  FourierModel m;
  m.order = order;
  m.period_s = period_s;
  m.dt_s = dt_s;
  const double w = 2.0 * std::numbers::pi / period_s;
  for (int j = 1; j <= order; ++j) {
    m.cos_dt.push_back(std::cos(w * j * dt_s));
    m.sin_dt.push_back(std::sin(w * j * dt_s));
  }
  return m;
}

std::vector<double> transition_matrix(const FourierModel& model) {
  const int n = model.states();
  std::vector<double> a(static_cast<std::size_t>(n * n), 0.0);
  a[0] = 1.0;
  for (int j = 0; j < model.order; ++j) {
    const int i = 1 + 2 * j;
    a[i * n + i] = model.cos_dt[j];
    a[i * n + i + 1] = model.sin_dt[j];
    a[(i + 1) * n + i] = -model.sin_dt[j];
    a[(i + 1) * n + i + 1] = model.cos_dt[j];
  }
  return a;
}

void advance_state(const FourierModel& model, std::vector<double>& q) {
  for (int j = 0; j < model.order; ++j) {
    double& alpha = q[1 + 2 * j];
    double& beta = q[2 + 2 * j];
    const double c = model.cos_dt[j], s = model.sin_dt[j];
    const double a = c * alpha + s * beta;
    beta = -s * alpha + c * beta;
    alpha = a;
  }
}

double output_w(const FourierModel& model, const std::vector<double>& q) {
  double sum = q[0];
  for (int j = 0; j < model.order; ++j) sum += q[1 + 2 * j];
  return sum / model.period_s;
}

std::vector<double> state_of_series(double a0, const std::vector<double>& a,
                                    const std::vector<double>& b, double /*period_s*/) {
  std::vector<double> q{a0};
  for (std::size_t j = 0; j < a.size(); ++j) {
    q.push_back(2.0 * a[j]);
    q.push_back(2.0 * b[j]);
  }
  return q;
}

std::vector<double> state_of_measurement(double y0_w, const FourierModel& model) {
  std::vector<double> q(static_cast<std::size_t>(model.states()), 0.0);
  q[0] = model.period_s * y0_w;
  return q;
}

void apply_power_step(const FourierModel& model, std::vector<double>& q, double delta_w) {
  q[0] += model.period_s * delta_w;
}

double energy_over_j(const FourierModel& model, const std::vector<double>& q, double horizon_s) {
  if (horizon_s <= 0.0) return 0.0;
  const double w = 2.0 * std::numbers::pi / model.period_s;
  double sum = q[0] * horizon_s;
  for (int j = 1; j <= model.order; ++j) {
    const double wj = w * j;
    sum += (q[2 * j - 1] * std::sin(wj * horizon_s) + q[2 * j] * (1.0 - std::cos(wj * horizon_s))) /
           wj;
  }
  return sum / model.period_s;
}

FourierModel with_period(const FourierModel& model, std::vector<double>& q, double period_s) {
  const double scale = period_s / model.period_s;
  for (double& v : q) v *= scale;
  return fourier_model(model.order, period_s, model.dt_s);
}

}  // namespace swath::energy

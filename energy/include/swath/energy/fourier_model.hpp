#pragma once
// The periodic energy model of paper 004 §II-B: a linear state-space system whose state is the
// Fourier coefficients of the power signal.

#include <vector>

namespace swath::energy {

/// State q = [alpha_0, alpha_1, beta_1, .., alpha_r, beta_r] (m = 2r + 1), dynamics
/// q' = A q with A = diag(0, A_1, .., A_r), A_j = [[0, w j], [-w j, 0]], w = 2 pi / T, and output
/// y = C q, C = (1/T) [1 1 0 1 0 ..] (paper eq. 6-7). The discrete step is exact: exp(A dt) is
/// block-diagonal with rotations [[cos, sin], [-sin, cos]] of angle w j dt. alpha_0 is the energy
/// of one period (J) when y is in watts.
struct FourierModel {
  int order = 3;                       ///< r >= 0
  double period_s = 60.0;              ///< T > 0
  double dt_s = 0.01;                  ///< time step > 0
  std::vector<double> cos_dt, sin_dt;  ///< per harmonic j = 1..r: cos(w j dt), sin(w j dt)

  int states() const { return 2 * order + 1; }
};

FourierModel fourier_model(int order, double period_s, double dt_s);

/// The dense m x m matrix exp(A dt), row-major (for tests and for the Kalman covariance).
std::vector<double> transition_matrix(const FourierModel& model);

/// q <- exp(A dt) q.
void advance_state(const FourierModel& model, std::vector<double>& q);

/// y = C q, W.
double output_w(const FourierModel& model, const std::vector<double>& q);

/// The state whose output is h(t) = a0/T + (2/T) sum_j (a_j cos(w j t) + b_j sin(w j t))
/// (paper eq. 4) for all t >= 0: [a0, 2 a1, 2 b1, ..]. Lemma II.2 prints [a0, a1/2, b1/2, ..],
/// which with the same C gives a quarter of each harmonic; the factor 2 is what the lemma means.
std::vector<double> state_of_series(double a0, const std::vector<double>& a,
                                    const std::vector<double>& b, double period_s);

/// The initial state for a first measurement y0 (paper Theorem III.1): the whole measurement in
/// the mean (alpha_0 = T y0), harmonics zero, so that C q0 = y0. (The theorem's split y0/m,
/// y0/(2m), .. does not sum to y0 for r > 0.)
std::vector<double> state_of_measurement(double y0_w, const FourierModel& model);

/// A step change of `delta_w` in the mean power (the input B (u_k - u_{k-1}) of eq. 8, with the
/// parameter gains already applied): alpha_0 += T delta_w.
void apply_power_step(const FourierModel& model, std::vector<double>& q, double delta_w);

/// Integral of the model's output from now over the next `horizon_s` seconds, closed form, J.
double energy_over_j(const FourierModel& model, const std::vector<double>& q, double horizon_s);

/// Rescales the state to a new period (same output now, new frequencies) and returns the model
/// for it; the caller scales covariances by (new/old)^2.
FourierModel with_period(const FourierModel& model, std::vector<double>& q, double period_s);

}  // namespace swath::energy

#pragma once
// State estimation of the periodic energy model: a Kalman filter applied only when the model and
// the measurement disagree (paper 004 Algorithm lines 9-16), with the covariance in Joseph form.

#include <vector>

#include "swath/energy/fourier_model.hpp"

namespace swath::energy {

/// Noise levels in watts of the output, so they do not depend on the period.
struct KalmanSettings {
  double process_w = 0.1;      ///< random walk of each coefficient's output share, W per sqrt(s)
  double measurement_w = 2.0;  ///< measurement noise standard deviation R^(1/2), W (> 0)
  double initial_w = 20.0;     ///< initial uncertainty of each coefficient's share, W
  double gate_w = 1.0;         ///< epsilon: correct only when |y - C q^-| > gate_w, W (>= 0)
};

/// The model's state, its covariance and the gated filter. One step: predict(), then correct()
/// with the measurement (or skip it when no measurement is available).
class EnergyEstimator {
 public:
  EnergyEstimator(const FourierModel& model, const KalmanSettings& settings, double first_w);

  /// Time update: q <- exp(A dt) q + B du (du as a mean power step, W), P <- A P A^T + Q.
  void predict(double power_step_w = 0.0);
  /// Measurement update with `measured_w`, only when it differs from the model by more than the
  /// gate. Returns whether it corrected.
  bool correct(double measured_w);
  /// Changes the period, keeping the current output (state and covariance rescaled).
  void set_period(double period_s);

  double output_w() const { return energy::output_w(model_, q_); }
  /// Energy the model predicts over the next `horizon_s` seconds, J.
  double energy_over_j(double horizon_s) const {
    return energy::energy_over_j(model_, q_, horizon_s);
  }
  const std::vector<double>& state() const { return q_; }
  const std::vector<double>& covariance() const { return p_; }  ///< row-major m x m
  const FourierModel& model() const { return model_; }
  long corrections() const { return corrections_; }

 private:
  FourierModel model_;
  KalmanSettings settings_;
  std::vector<double> q_, p_;
  std::vector<double> pc_, gain_, x_, xc_;  // scratch of correct(), kept to avoid allocations
  long corrections_ = 0;
};

}  // namespace swath::energy

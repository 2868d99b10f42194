#pragma once
// Internal: a Gaussian process over the plane with the RBF kernel k(p, q) = σ_f² exp(−|p − q|² /
// (2ℓ²)) and Gaussian noise σ_n (the wifi app's map, paper 000 §5.1.2). Eigen stays in the .cpp.

#include <array>
#include <memory>
#include <vector>

namespace swath::fleet {

class GaussianProcess {
 public:
  GaussianProcess(double length_m, double sigma_f, double sigma_n);
  ~GaussianProcess();
  /// A reading `value` at (x, y). Refits (Cholesky, O(n³) for n readings; n ≤ a few hundred).
  void add(double x_m, double y_m, double value);
  /// Posterior mean and standard deviation at (x, y); the prior mean is the readings' mean.
  std::array<double, 2> predict(double x_m, double y_m) const;
  std::size_t size() const { return xs_.size(); }

 private:
  double k(double ax, double ay, double bx, double by) const;
  double length_, sf2_, sn2_;
  std::vector<double> xs_, ys_, vs_;
  struct Fit;
  std::unique_ptr<Fit> fit_;
};

}  // namespace swath::fleet

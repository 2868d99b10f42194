#include "gaussian_process.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <cmath>

namespace swath::fleet {

struct GaussianProcess::Fit {
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::VectorXd alpha;
  double mean = 0;
};

GaussianProcess::GaussianProcess(double length_m, double sigma_f, double sigma_n)
    : length_(length_m), sf2_(sigma_f * sigma_f), sn2_(sigma_n * sigma_n) {}
GaussianProcess::~GaussianProcess() = default;

double GaussianProcess::k(double ax, double ay, double bx, double by) const {
  const double d2 = (ax - bx) * (ax - bx) + (ay - by) * (ay - by);
  return sf2_ * std::exp(-d2 / (2 * length_ * length_));
}

void GaussianProcess::add(double x, double y, double v) {
  xs_.push_back(x);
  ys_.push_back(y);
  vs_.push_back(v);
  const auto n = static_cast<Eigen::Index>(xs_.size());
  Eigen::MatrixXd K(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      K(i, j) = k(xs_[static_cast<std::size_t>(i)], ys_[static_cast<std::size_t>(i)],
                  xs_[static_cast<std::size_t>(j)], ys_[static_cast<std::size_t>(j)]) +
                (i == j ? sn2_ : 0.0);
  fit_ = std::make_unique<Fit>();
  double mean = 0;
  for (double value : vs_) mean += value / static_cast<double>(n);
  Eigen::VectorXd r(n);
  for (Eigen::Index i = 0; i < n; ++i) r(i) = vs_[static_cast<std::size_t>(i)] - mean;
  fit_->llt.compute(K);
  fit_->alpha = fit_->llt.solve(r);
  fit_->mean = mean;
}

std::array<double, 2> GaussianProcess::predict(double x, double y) const {
  if (!fit_) return {0.0, std::sqrt(sf2_)};
  const auto n = static_cast<Eigen::Index>(xs_.size());
  Eigen::VectorXd ks(n);
  for (Eigen::Index i = 0; i < n; ++i)
    ks(i) = k(x, y, xs_[static_cast<std::size_t>(i)], ys_[static_cast<std::size_t>(i)]);
  const double mean = fit_->mean + ks.dot(fit_->alpha);
  const Eigen::VectorXd v = fit_->llt.matrixL().solve(ks);
  return {mean, std::sqrt(std::max(0.0, sf2_ - v.squaredNorm()))};
}

}  // namespace swath::fleet

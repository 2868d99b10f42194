#include "swath/control/logistic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "swath/base/csv_text.hpp"
#include "swath/base/input_error.hpp"

namespace swath::control {
namespace {

struct Group {
  double x_mean = 0;
  double n = 0, k = 0;  // points, of which changed
};

LogisticModel pooled(const std::vector<TriggerPoint>& data) {
  double k = 0;
  for (const TriggerPoint& p : data) k += p.changed ? 1 : 0;
  const auto n = static_cast<double>(data.size());
  LogisticModel m;
  m.beta1 = std::log((k + 0.5) / (n - k + 0.5));
  m.degenerate = true;
  m.points = data.size();
  return m;
}

// Equal-count groups over x, never splitting a run of equal x. The groups depend only on the
// multiset of points: a run of equal x is never split and sums the same value, so any order of
// the ties gives the same bits (the reactive scheduler passes its data already sorted).
std::vector<Group> groups(const std::vector<TriggerPoint>& given, int bins, int min_per_bin) {
  const auto by_x = [](const TriggerPoint& a, const TriggerPoint& b) { return a.x < b.x; };
  // Sorted already (NaN has no order: such data is sorted as it always was).
  bool sorted = true;
  for (std::size_t i = 0; i < given.size() && sorted; ++i)
    sorted = !std::isnan(given[i].x) && (i == 0 || !(given[i].x < given[i - 1].x));
  std::vector<TriggerPoint> copy;
  if (!sorted) {
    copy = given;
    std::sort(copy.begin(), copy.end(), by_x);
  }
  const std::vector<TriggerPoint>& data = copy.empty() ? given : copy;
  const std::size_t n = data.size();
  const std::size_t count =
      std::min<std::size_t>(static_cast<std::size_t>(std::max(bins, 1)),
                            n / static_cast<std::size_t>(std::max(min_per_bin, 1)));
  std::vector<Group> out;
  if (count < 2) return out;
  std::size_t start = 0;
  for (std::size_t b = 1; b <= count && start < n; ++b) {
    std::size_t end = b == count ? n : b * n / count;
    end = std::max(end, start + 1);
    while (end < n && data[end].x == data[end - 1].x) ++end;  // keep ties together
    Group g;
    for (std::size_t i = start; i < end; ++i) {
      g.x_mean += data[i].x;
      g.k += data[i].changed ? 1 : 0;
    }
    g.n = static_cast<double>(end - start);
    g.x_mean /= g.n;
    out.push_back(g);
    start = end;
  }
  return out;
}

// Weighted least squares of z on x over the groups.
LogisticModel logit_fit(const std::vector<TriggerPoint>& data, bool weighted, int bins,
                        int min_per_bin) {
  const std::vector<Group> g = groups(data, bins, min_per_bin);
  if (g.size() < 2) return pooled(data);
  double sw = 0, sx = 0, sz = 0;
  std::vector<double> z(g.size()), w(g.size());
  for (std::size_t j = 0; j < g.size(); ++j) {
    const double a = g[j].k + 0.5, b = g[j].n - g[j].k + 0.5;
    z[j] = std::log(a / b);
    w[j] = weighted ? 1.0 / (1.0 / a + 1.0 / b) : 1.0;
    sw += w[j];
    sx += w[j] * g[j].x_mean;
    sz += w[j] * z[j];
  }
  const double mx = sx / sw, mz = sz / sw;
  double sxx = 0, sxz = 0;
  for (std::size_t j = 0; j < g.size(); ++j) {
    sxx += w[j] * (g[j].x_mean - mx) * (g[j].x_mean - mx);
    sxz += w[j] * (g[j].x_mean - mx) * (z[j] - mz);
  }
  if (!(sxx > 0)) return pooled(data);
  LogisticModel m;
  m.beta2 = sxz / sxx;
  m.beta1 = mz - m.beta2 * mx;
  m.points = data.size();
  return m;
}

// The log-likelihood at (b1, b2) with its gradient and Hessian (negated), in one pass: each point
// costs one exp and one log1p.
struct Evaluation {
  double ll = 0, g1 = 0, g2 = 0, h11 = 1e-8, h12 = 0, h22 = 1e-8;  // ridge 1e-8
};

Evaluation evaluate(const std::vector<TriggerPoint>& data, double b1, double b2) {
  Evaluation e;
  for (const TriggerPoint& p : data) {
    const double eta = b1 + b2 * p.x;
    // σ(η) and log(1 + e^−|η|) from one exponential, stable for any η.
    const double z = std::exp(-std::abs(eta));
    const double mu = eta >= 0 ? 1 / (1 + z) : z / (1 + z);
    const double softplus = std::log1p(z) + (eta < 0 ? -eta : 0.0);  // log(1 + e^−η)
    e.ll += p.changed ? -softplus : -(eta + softplus);
    const double r = (p.changed ? 1.0 : 0.0) - mu, w = mu * (1 - mu);
    e.g1 += r;
    e.g2 += r * p.x;
    e.h11 += w;
    e.h12 += w * p.x;
    e.h22 += w * p.x * p.x;
  }
  return e;
}

// IRLS (Newton on the log-likelihood) with a 1e-8 ridge and step halving, ≤ 50 iterations.
// A start near the optimum in one pass: the linear-discriminant coefficients (exact for normal
// x within each label with a common variance), which saves Newton a few passes over the data.
std::pair<double, double> discriminant_start(const std::vector<TriggerPoint>& data) {
  double n[2] = {0, 0}, sum[2] = {0, 0}, sq[2] = {0, 0};
  for (const TriggerPoint& p : data) {
    const int k = p.changed ? 1 : 0;
    n[k] += 1;
    sum[k] += p.x;
    sq[k] += p.x * p.x;
  }
  const double m0 = sum[0] / n[0], m1 = sum[1] / n[1];
  const double var = (sq[0] - n[0] * m0 * m0 + sq[1] - n[1] * m1 * m1) / (n[0] + n[1] - 2);
  const double b2 = var > 0 ? (m1 - m0) / var : 0.0;
  const double b1 = std::log(n[1] / n[0]) - b2 * (m0 + m1) / 2;
  if (!std::isfinite(b1) || !std::isfinite(b2)) return {pooled(data).beta1, 0.0};
  return {b1, b2};
}

LogisticModel mle_fit(const std::vector<TriggerPoint>& data) {
  auto [b1, b2] = discriminant_start(data);
  Evaluation at = evaluate(data, b1, b2);
  for (int it = 0; it < 50; ++it) {
    const double det = at.h11 * at.h22 - at.h12 * at.h12;
    if (!(det > 0)) break;
    const double d1 = (at.h22 * at.g1 - at.h12 * at.g2) / det;
    const double d2 = (at.h11 * at.g2 - at.h12 * at.g1) / det;
    // Newton's step already negligible: the optimum, without another pass over the data.
    if (std::abs(d1) <= 1e-10 * (1 + std::abs(b1)) && std::abs(d2) <= 1e-10 * (1 + std::abs(b2)))
      break;
    double step = 1.0;
    Evaluation next;
    bool accepted = false;
    for (int half = 0; half < 30 && !accepted; ++half, step /= 2) {
      next = evaluate(data, b1 + step * d1, b2 + step * d2);
      accepted = next.ll >= at.ll;
      if (accepted) {
        b1 += step * d1;
        b2 += step * d2;
      }
    }
    if (!accepted) break;
    const bool converged = std::abs(next.ll - at.ll) < 1e-12 * (1 + std::abs(at.ll));
    at = next;
    if (converged) break;
  }
  // Separable data has no finite optimum: the coefficients run away.
  if (!std::isfinite(b1) || !std::isfinite(b2) || std::abs(b2) > 1e12) return pooled(data);
  LogisticModel m;
  m.beta1 = b1;
  m.beta2 = b2;
  m.points = data.size();
  return m;
}

}  // namespace

double trigger_probability(const LogisticModel& m, double x) {
  return 1.0 / (1.0 + std::exp(-(m.beta1 + m.beta2 * x)));
}

double trigger_threshold(const LogisticModel& m, double p_run) {
  const double logit = std::log(p_run / (1 - p_run));
  if (m.beta2 > 0) return std::max(0.0, (logit - m.beta1) / m.beta2);
  // β2 ≤ 0: L is largest at x = 0.
  return trigger_probability(m, 0.0) > p_run ? 0.0 : std::numeric_limits<double>::infinity();
}

double largest_square_within(double x) {
  if (!(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(x)) return x;
  // x² rounded is within an ulp or two of the bound: step to it.
  double s = x * x;
  while (std::sqrt(s) > x) s = std::nextafter(s, 0.0);
  while (!std::isinf(s)) {
    const double next = std::nextafter(s, std::numeric_limits<double>::infinity());
    if (std::sqrt(next) > x) break;
    s = next;
  }
  return s;
}

LogisticModel fit_logistic(const std::vector<TriggerPoint>& data, FitMethod method, int bins,
                           int min_per_bin) {
  // One label only: nothing to separate. Completely separated labels (every unchanged x below
  // every changed x, or above): the likelihood has no finite optimum.
  double lo0 = INFINITY, hi0 = -INFINITY, lo1 = INFINITY, hi1 = -INFINITY;
  for (const TriggerPoint& p : data) {
    double& lo = p.changed ? lo1 : lo0;
    double& hi = p.changed ? hi1 : hi0;
    lo = std::min(lo, p.x);
    hi = std::max(hi, p.x);
  }
  const bool one_label = !(lo0 <= hi0) || !(lo1 <= hi1);
  if (one_label || (method == FitMethod::mle && (hi0 < lo1 || hi1 < lo0))) return pooled(data);
  switch (method) {
    case FitMethod::logit_ols:
      return logit_fit(data, false, bins, min_per_bin);
    case FitMethod::logit_wls:
      return logit_fit(data, true, bins, min_per_bin);
    case FitMethod::mle:
      return mle_fit(data);
  }
  return pooled(data);
}

std::vector<TriggerPoint> parse_trigger_data(const std::string& text, const std::string& source) {
  constexpr std::size_t kMaxRows = 10'000'000;
  std::vector<TriggerPoint> out;
  std::size_t x_col = std::string::npos, changed_col = std::string::npos, columns = 0;
  base::CsvText csv(text, source);
  while (csv.next()) {
    const std::vector<std::string>& cells = csv.cells();
    const std::string where = source + ": line " + std::to_string(csv.line());
    if (columns == 0) {
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (cells[c] == "x") x_col = c;
        if (cells[c] == "changed") changed_col = c;
      }
      if (x_col == std::string::npos || changed_col == std::string::npos)
        throw base::InputError(where + ": the header must name the columns x and changed");
      columns = cells.size();
      continue;
    }
    if (cells.size() != columns)
      throw base::InputError(where + ": " + std::to_string(cells.size()) + " " +
                             base::separated_text(csv.separator()) + " fields, the header has " +
                             std::to_string(columns));
    TriggerPoint p;
    const std::optional<double> x = csv.number(cells[x_col]);
    if (!x || !std::isfinite(*x) || *x < 0)
      throw base::InputError(where + ": x '" + cells[x_col] + "' is not a finite number >= 0");
    p.x = *x;
    if (cells[changed_col] != "0" && cells[changed_col] != "1")
      throw base::InputError(where + ": changed '" + cells[changed_col] + "' is not 0 or 1");
    p.changed = cells[changed_col] == "1";
    if (out.size() >= kMaxRows) throw base::InputError(source + ": more than 10,000,000 rows");
    out.push_back(p);
  }
  if (columns == 0) throw base::InputError(source + ": no header (x,changed) and no data");
  return out;
}

}  // namespace swath::control

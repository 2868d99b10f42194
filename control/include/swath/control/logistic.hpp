#pragma once
// The per-sensor trigger model of paper 002 (eq. 1): L(x) = 1 / (1 + e^−(β1 + β2 x)), the
// probability that a change x of a sensor's value calls for a new control decision, and its fits
// (docs/swath-control.md). The paper fits β by ordinary least squares on the logit of 0/1
// outcomes, which is undefined (the logit of 0 or 1 is infinite); `logit_ols` makes it defined
// with grouped empirical logits, `logit_wls` weights the groups by their variance, `mle` is the
// maximum-likelihood fit by IRLS.

#include <cstddef>
#include <string>
#include <vector>

#include "swath/control/config.hpp"

namespace swath::control {

/// One observation: a change x (≥ 0, the sensor's units) and whether the output changed.
struct TriggerPoint {
  double x = 0;
  bool changed = false;
};

struct LogisticModel {
  double beta1 = 0, beta2 = 0;
  bool degenerate = false;  ///< one label only, fewer than 2 groups, or no spread in x
  std::size_t points = 0;   ///< the data set's size
};

/// L(x) (eq. 1), in [0, 1].
double trigger_probability(const LogisticModel& m, double x);

/// The change above which L exceeds p_run (eq. 1 inverted, the form paper 002 §5 programs into
/// sensors): x* = (ln(p/(1−p)) − β1) / β2 when β2 > 0; otherwise +∞ when L(x) ≤ p_run everywhere
/// (it then never triggers) and 0 when L(0) > p_run (it always does). p_run in (0, 1).
double trigger_threshold(const LogisticModel& m, double p_run);
/// The largest sum of squares s with √s ≤ `x` (√ correctly rounded, so monotone): √s > x exactly
/// when s > this, so a change can be checked against x* without its square root (NaN for a
/// negative or NaN `x`).
double largest_square_within(double x);

/// The fit of `data` by `method`; `bins` and `min_per_bin` shape the groups of the logit fits
/// (B = min(bins, ⌊n / min_per_bin⌋) equal-count groups, ties never split). Degenerate data (one
/// label only, B < 2, S_xx = 0, or IRLS without a finite optimum) gives β2 = 0 and β1 the pooled
/// logit ln((k + ½) / (n − k + ½)).
LogisticModel fit_logistic(const std::vector<TriggerPoint>& data, FitMethod method, int bins = 20,
                           int min_per_bin = 25);

/// Reads trigger data (`swath-control fit`): CSV with a header naming the columns `x` and
/// `changed` (others ignored, any order); x ≥ 0 finite, changed 0 or 1; blank lines and '#'
/// comments skipped; at most 10,000,000 rows. The dialects (quoted cells, ';' with decimal commas
/// or tab separators, LF, CRLF or CR line ends, a BOM) are base::CsvText's, as the area reader's.
/// Throws base::InputError naming `source`, the line and the problem.
std::vector<TriggerPoint> parse_trigger_data(const std::string& text, const std::string& source);

}  // namespace swath::control

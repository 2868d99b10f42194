#include "intervals.hpp"

#include <algorithm>
#include <cmath>

namespace swath::apps {

double t95(int n) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                 2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                 2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                 2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  const int df = n - 1;
  if (df <= 30) return table[df - 1];
  return 1.96 + 2.4 / df;  // within 0.002 of the exact quantile beyond 30
}

Interval mean_interval95(const std::vector<double>& x) {
  Interval out;
  const double n = static_cast<double>(x.size());
  for (double v : x) out.mean += v / n;
  double ss = 0;
  for (double v : x) ss += (v - out.mean) * (v - out.mean);
  out.half = t95(static_cast<int>(x.size())) * std::sqrt(ss / (n - 1) / n);
  return out;
}

}  // namespace swath::apps

namespace swath::apps {

std::optional<double> kaplan_meier_median_s(std::vector<TimeObservation> runs) {
  // Completions before censorings at one time: a run censored at t was still running at t.
  std::sort(runs.begin(), runs.end(), [](const TimeObservation& a, const TimeObservation& b) {
    return a.time_s != b.time_s ? a.time_s < b.time_s : a.completed > b.completed;
  });
  double surviving = 1.0;
  std::size_t i = 0;
  while (i < runs.size()) {
    const double t = runs[i].time_s;
    const double at_risk = static_cast<double>(runs.size() - i);
    double completions = 0;
    for (; i < runs.size() && runs[i].time_s == t && runs[i].completed; ++i) ++completions;
    for (; i < runs.size() && runs[i].time_s == t; ++i) {
    }  // censored at t: they leave the risk set after t
    if (completions == 0) continue;
    surviving *= 1.0 - completions / at_risk;
    if (surviving <= 0.5 + 1e-12) return t;
  }
  return std::nullopt;
}

PairedRuns pair_runs(const TimeObservation& first, const TimeObservation& other) {
  PairedRuns p;
  if (first.completed && other.completed) {
    p.relative_change = other.time_s / first.time_s - 1.0;
    p.sign = other.time_s < first.time_s ? -1 : (other.time_s > first.time_s ? 1 : 0);
    p.known = true;
  } else if (first.completed && other.time_s >= first.time_s) {  // other still running later
    p.sign = 1, p.known = true;
  } else if (other.completed && first.time_s >= other.time_s) {
    p.sign = -1, p.known = true;
  }
  return p;
}

}  // namespace swath::apps

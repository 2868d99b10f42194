#include "intervals.hpp"

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

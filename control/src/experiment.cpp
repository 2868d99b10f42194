#include "swath/control/experiment.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <cmath>

namespace swath::control {

MeanInterval mean_interval(const std::vector<double>& values) {
  MeanInterval m;
  m.n = static_cast<int>(values.size());
  if (values.empty()) return m;
  double sum = 0;
  for (double v : values) sum += v;
  m.mean = sum / m.n;
  m.low = m.high = m.mean;
  if (m.n < 2) return m;
  double ss = 0;
  for (double v : values) ss += (v - m.mean) * (v - m.mean);
  const double sd = std::sqrt(ss / (m.n - 1));
  const boost::math::students_t t(m.n - 1);
  const double half = boost::math::quantile(boost::math::complement(t, 0.025)) * sd /
                      std::sqrt(static_cast<double>(m.n));
  m.low = m.mean - half;
  m.high = m.mean + half;
  return m;
}

FlightFigures figures_of(const SimulationSummary& s) {
  FlightFigures f;
  const auto& a = s.attitude_error_deg;
  const auto& e = s.attitude_error_estimated_deg;
  f.attitude_rms_deg = std::sqrt((a[0].rms * a[0].rms + a[1].rms * a[1].rms) / 2);
  f.attitude_estimated_rms_deg = std::sqrt((e[0].rms * e[0].rms + e[1].rms * e[1].rms) / 2);
  f.cross_track_rms_m = s.cross_track_m.rms;
  f.executions_per_s = s.executions.per_second_mean;
  f.unchanged_fraction = s.executions.unchanged_fraction;
  f.flight_time_s = s.reserve_time_s ? *s.reserve_time_s : s.flight_time_s;
  f.cpu_j = s.cpu_j;
  f.total_j = s.total_j;
  f.cpu_utilisation = s.cpu_utilisation;
  f.background_completed =
      s.background_released > 0
          ? static_cast<double>(s.background_completed) / static_cast<double>(s.background_released)
          : 1.0;
  f.axis_error_deg = a;
  const auto& d = s.attitude_error_disturbance_deg;
  f.axis_disturbance_error_deg = d;
  f.disturbance_rms_deg = std::sqrt((d[0].rms * d[0].rms + d[1].rms * d[1].rms) / 2);
  f.disturbance_share = s.disturbance_share;
  return f;
}

Improvements paired_improvements(const std::vector<FlightFigures>& baseline,
                                 const std::vector<FlightFigures>& mode) {
  std::vector<double> att, est, xt, ex, ft, dist;
  std::array<std::vector<double>, 3> axis_rms, axis_max;
  auto less = [](std::vector<double>& out, double b, double m) {
    if (b != 0) out.push_back((b - m) / b);
  };
  for (std::size_t k = 0; k < std::min(baseline.size(), mode.size()); ++k) {
    const FlightFigures &b = baseline[k], &m = mode[k];
    less(att, b.attitude_rms_deg, m.attitude_rms_deg);
    less(est, b.attitude_estimated_rms_deg, m.attitude_estimated_rms_deg);
    less(xt, b.cross_track_rms_m, m.cross_track_rms_m);
    less(ex, b.executions_per_s, m.executions_per_s);
    if (b.flight_time_s != 0) ft.push_back((m.flight_time_s - b.flight_time_s) / b.flight_time_s);
    less(dist, b.disturbance_rms_deg, m.disturbance_rms_deg);
    for (std::size_t a = 0; a < 3; ++a) {
      less(axis_rms[a], b.axis_error_deg[a].rms, m.axis_error_deg[a].rms);
      less(axis_max[a], b.axis_error_deg[a].max, m.axis_error_deg[a].max);
    }
  }
  Improvements out;
  out.attitude = mean_interval(att);
  out.attitude_estimated = mean_interval(est);
  out.cross_track = mean_interval(xt);
  out.executions = mean_interval(ex);
  out.flight_time = mean_interval(ft);
  for (std::size_t a = 0; a < 3; ++a) {
    out.axis_rms[a] = mean_interval(axis_rms[a]);
    out.axis_max[a] = mean_interval(axis_max[a]);
  }
  out.disturbance = mean_interval(dist);
  return out;
}

}  // namespace swath::control

// swath-control response: the chirp's simulated loop margins against the closed form of
// loop_response.hpp, the margin reader against loop_margins on the closed form itself, the step
// figures against a second-order system's closed form, and the step's direction on every axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <numbers>
#include <set>
#include <sstream>
#include <string>

#include "swath/control/control_files.hpp"
#include "swath/control/response.hpp"

namespace swath::control {
namespace {

constexpr double kPi = std::numbers::pi;

ResponseResult chirp(ResponseAxis axis, ResponseLoop loop, std::uint64_t seed) {
  SimulationSettings s;
  s.seed = seed;
  ResponseSettings r;
  r.axis = axis;
  r.loop = loop;
  r.input = ResponseInput::chirp;
  r.duration_s = 60;
  const ResponseResult out = run_response(s, r);
  std::cout << to_string(axis) << (loop == ResponseLoop::rate ? " rate" : " attitude")
            << " loop, seed " << seed << ": simulated " << out.measured.gain_crossover_hz
            << " Hz, PM " << out.measured.phase_margin_deg << " deg, "
            << out.measured.phase_crossover_hz << " Hz, GM " << out.measured.gain_margin_db
            << " dB; closed form " << out.closed_form.gain_crossover_hz << " Hz, PM "
            << out.closed_form.phase_margin_deg << " deg, " << out.closed_form.phase_crossover_hz
            << " Hz, GM " << out.closed_form.gain_margin_db << " dB\n";
  return out;
}

// Tolerances. The closed form models the sampled loop by delays that are exact in the mean (the
// gyro's average age, Δθ averaged over the period, the hold, the ESC frame) but not the discrete
// PID: the backward-difference derivative and the sampled low-passes are off by up to half an
// execution period (1.25 ms at 400 Hz) on part of the loop. That is ≤ 360° · 5.2 Hz · 1.25 ms
// = 2.3° at the gain crossover (margin: 3°), where the magnitude is unaffected (the hold's sinc is
// 0.998; crossover: 5 %); at the phase crossover (~21 Hz) ≤ 9.5°, which on the phase's slope there
// (~58° per e-fold of frequency) moves the crossover by ≤ 17 % (20 %) and, on the magnitude's
// slope (~14 dB per e-fold), the gain margin by ≤ 2.4 dB (3 dB). The estimate's own scatter over
// seeds is 0.1° and 0.6 dB. The attitude loop adds what the closed form leaves out: the
// estimator's attitude (accelerometer correction) instead of the integral of the rate, and the
// height loop (5° and 10 % at the gain crossover).
void expect_margins_near(const ResponseResult& r, double pm_deg, double crossover_share) {
  const MarginFigures &m = r.measured, &c = r.closed_form;
  EXPECT_NEAR(m.gain_crossover_hz / c.gain_crossover_hz, 1, crossover_share);
  EXPECT_NEAR(m.phase_margin_deg, c.phase_margin_deg, pm_deg);
  EXPECT_NEAR(m.phase_crossover_hz / c.phase_crossover_hz, 1, 0.2);
  EXPECT_NEAR(m.gain_margin_db, c.gain_margin_db, 3);
}

TEST(Response, RateLoopMarginsFromTheChirpMatchTheClosedForm) {
  for (const ResponseAxis axis : {ResponseAxis::roll, ResponseAxis::pitch}) {
    const ResponseResult r = chirp(axis, ResponseLoop::rate, 1);
    // The closed form the brief quotes for quad-f450's rate loop at 400 Hz: ~54° and ~16 dB.
    EXPECT_NEAR(r.closed_form.phase_margin_deg, 54, 1);
    EXPECT_NEAR(r.closed_form.gain_margin_db, 16.5, 1);
    expect_margins_near(r, 3, 0.05);
  }
}

TEST(Response, AttitudeLoopMarginsFromTheChirpMatchTheClosedForm) {
  for (std::uint64_t seed : {2, 3})
    expect_margins_near(chirp(ResponseAxis::roll, ResponseLoop::attitude, seed), 5, 0.1);
}

TEST(Response, ChirpCoherenceIsHighAroundTheCrossover) {
  const ResponseResult r = chirp(ResponseAxis::roll, ResponseLoop::rate, 4);
  for (const BodePoint& p : r.bode)
    if (p.frequency_hz > 1 && p.frequency_hz < 15) {
      EXPECT_GT(p.coherence, 0.9) << p.frequency_hz;
    }
}

// margins_of, fed the closed form on its grid, against loop_margins' bisection on the same model.
TEST(Response, MarginReaderAgreesWithTheClosedFormsBisection) {
  RateLoopModel model;
  model.delay_s = rate_loop_delay_s(400, 0, 1000, 490);
  for (const double attitude_p : {0.0, 8.0}) {
    model.attitude_p_1_s = attitude_p;
    std::vector<BodePoint> bode;
    for (int j = 0; j <= 80; ++j) {
      const double f = 0.5 * std::pow(80.0, j / 80.0);
      const std::complex<double> l = rate_loop_gain(model, 2 * kPi * f);
      BodePoint p;
      p.frequency_hz = f;
      p.magnitude_db = 20 * std::log10(std::abs(l));
      p.phase_deg = std::arg(l) * 180 / kPi;
      bode.push_back(p);
    }
    const MarginFigures m = margins_of(bode);
    const LoopMargins truth = loop_margins(model, 2 * kPi * 0.5, 2 * kPi * 40);
    EXPECT_NEAR(m.gain_crossover_hz * 2 * kPi / truth.gain_crossover_rad_s, 1, 1e-3);
    EXPECT_NEAR(m.phase_margin_deg, truth.phase_margin_deg, 0.1);
    EXPECT_NEAR(m.phase_crossover_hz * 2 * kPi / truth.phase_crossover_rad_s, 1, 1e-3);
    EXPECT_NEAR(m.gain_margin_db, truth.gain_margin_db, 0.05);
  }
}

// A second-order step y = 1 − e^(−ζωt)(cos ω_d t + ζ/√(1−ζ²) sin ω_d t), sampled at 10 kHz.
TEST(Response, StepFiguresOfASecondOrderSystem) {
  const double zeta = 0.4, omega = 20, amplitude = 10, step_s = 1;
  const double wd = omega * std::sqrt(1 - zeta * zeta);
  auto y = [&](double t) {
    if (t < 0) return 0.0;
    return 1 - std::exp(-zeta * omega * t) *
                   (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t));
  };
  std::vector<ResponseSample> samples;
  for (int k = 0; k <= 30'000; ++k) {
    ResponseSample s;
    s.t_s = k * 1e-4;
    s.response_deg = amplitude * y(s.t_s - step_s);
    samples.push_back(s);
  }
  const StepMetrics m = step_metrics(samples, step_s, amplitude);
  // Overshoot in closed form; rise and settling times by bisection / a 1 µs scan of y itself.
  EXPECT_NEAR(m.overshoot_percent, 100 * std::exp(-kPi * zeta / std::sqrt(1 - zeta * zeta)), 0.01);
  auto first_at = [&](double level) {
    double lo = 0, hi = kPi / wd;  // y rises monotonically to its first peak at π/ω_d
    for (int i = 0; i < 60; ++i) (y((lo + hi) / 2) < level ? lo : hi) = (lo + hi) / 2;
    return hi;
  };
  EXPECT_NEAR(m.rise_time_s, first_at(0.9) - first_at(0.1), 2e-4);
  double last_out = 0;
  for (double t = 0; t < 2; t += 1e-6)
    if (std::abs(y(t) - 1) > 0.05) last_out = t;
  EXPECT_NEAR(m.settling_time_s, last_out, 2e-4);
  EXPECT_NEAR(m.final_deg, amplitude, 1e-3);
  EXPECT_TRUE(m.settled);
}

// A step on each axis moves that axis the way the setpoint moved, most of the way within 0.5 s (yaw
// 1 s); the other two stay put.
TEST(Response, StepsMoveTheirAxisTheWayOfTheSetpoint) {
  for (const ResponseAxis axis : {ResponseAxis::roll, ResponseAxis::pitch, ResponseAxis::yaw})
    for (const double amplitude : {-8.0, 8.0}) {
      ResponseSettings r;
      r.axis = axis;
      r.amplitude_deg = amplitude;
      r.duration_s = 1;
      const ResponseResult out = run_response(SimulationSettings{}, r);
      ASSERT_TRUE(out.step);
      EXPECT_NEAR(out.samples.back().setpoint_deg - out.samples.front().setpoint_deg, amplitude,
                  0.5);
      // Yaw is a compass heading (90° at the start: the task holds east); a yaw step of P 4/s
      // rises in ~2.2/4 s, roll and pitch (P 8/s) in about half that.
      const double base = out.samples.front().response_deg;
      const double within_s = axis == ResponseAxis::yaw ? 1.0 : 0.5;
      double at_half_s = 0;
      for (const ResponseSample& s : out.samples)
        if (s.t_s <= r.settle_s + within_s) at_half_s = s.response_deg - base;
      EXPECT_GT(at_half_s / amplitude, 0.8) << to_string(axis) << ' ' << amplitude;
      EXPECT_LT(at_half_s / amplitude, 1.3) << to_string(axis) << ' ' << amplitude;
      EXPECT_GT(out.step->rise_time_s, 0.02);
      EXPECT_LT(out.step->rise_time_s, within_s);
    }
}

TEST(Response, SameSettingsGiveTheSameBytes) {
  ResponseSettings r;
  r.input = ResponseInput::chirp;
  r.duration_s = 12;
  r.from_hz = 1;
  const ResponseResult a = run_response(SimulationSettings{}, r);
  const ResponseResult b = run_response(SimulationSettings{}, r);
  EXPECT_EQ(response_csv(a.samples), response_csv(b.samples));
  EXPECT_EQ(bode_csv(a.bode), bode_csv(b.bode));
}

// What PlotJuggler's CSV loader (plotjuggler_plugins/DataLoadCSV) needs to plot a file against
// its first column without a question: a header of distinct names that are not all numbers,
// every line with the header's number of fields, every field a number (strtod reads it whole),
// and the time column never decreasing. Returns the first problem, or "".
std::string plotjuggler_problem(const std::string& csv, const std::string& time_name) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string f; std::getline(h, f, ',');) header.push_back(f);
  if (header.empty() || header.front() != time_name) return "first column is not " + time_name;
  if (std::set<std::string>(header.begin(), header.end()).size() != header.size())
    return "repeated column names";
  double previous = -1e300;
  for (int n = 2; std::getline(in, line); ++n) {
    std::vector<std::string> fields;
    std::stringstream l(line);
    for (std::string f; std::getline(l, f, ',');) fields.push_back(f);
    if (fields.size() != header.size()) return "line " + std::to_string(n) + ": field count";
    for (const std::string& f : fields) {
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      if (f.empty() || *end != '\0' || !std::isfinite(v))
        return "line " + std::to_string(n) + ": " + f + " is not a number";
    }
    const double t = std::strtod(fields.front().c_str(), nullptr);
    if (t < previous) return "line " + std::to_string(n) + ": time decreases";
    previous = t;
  }
  return "";
}

struct CsvRows : SimulationObserver {
  std::string csv;
  void on_row(const TimeseriesRow& r) override { csv += timeseries_csv_row(r); }
};

TEST(Response, PlotJugglerReadsTheTimeSeriesOfRunAndResponse) {
  SimulationSettings s;
  s.mission.name = "line";
  s.mission.legs.push_back({{0, 0, 10}, {20, 0, 10}});
  s.scheduler.run.max_time_s = 15;
  CsvRows rows;
  rows.csv = timeseries_csv_header(s.physics.airframe.rotors.size());
  simulate(s, &rows);
  EXPECT_GT(std::count(rows.csv.begin(), rows.csv.end(), '\n'), 100);  // rows, not a header alone
  EXPECT_EQ(plotjuggler_problem(rows.csv, "t_s"), "");
  ResponseSettings r;
  r.duration_s = 1;
  EXPECT_EQ(
      plotjuggler_problem(response_csv(run_response(SimulationSettings{}, r).samples), "time_s"),
      "");
  // The checker itself: a repeated time step backwards and a word are found.
  EXPECT_NE(plotjuggler_problem("t_s,a\n0,1\n1,2\n0.5,3\n", "t_s"), "");
  EXPECT_NE(plotjuggler_problem("t_s,a\n0,x\n", "t_s"), "");
}

}  // namespace
}  // namespace swath::control

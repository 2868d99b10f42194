#include "response_command.hpp"

#include <cmath>
#include <iostream>

#include "map_furniture.hpp"
#include "seed_option.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/render/chart.hpp"
#include "swath/render/image.hpp"

namespace swath::apps {
namespace {

using base::fixed_text;
using base::InputError;
using render::Color;

const Color kSimulatedColor{0.1f, 0.3f, 0.85f, 1};
const Color kReferenceColor{0.6f, 0.6f, 0.6f, 1};
const Color kRateColor{0.95f, 0.55f, 0.0f, 1};
const Color kGuideColor{0.85f, 0.15f, 0.1f, 1};

// Charts stacked top to bottom, each `height_px / count` high.
std::string stacked_png(const std::vector<render::ChartSpec>& specs, int width_px, int height_px) {
  render::Scene scene;
  const int panel = height_px / static_cast<int>(specs.size());
  for (std::size_t k = 0; k < specs.size(); ++k)
    render::stack_scene(scene, render::chart_scene(specs[k], width_px, panel, nullptr),
                        static_cast<double>(k) * panel);
  return render::encode_png(render::draw(scene, render::View{1.0, 0.0, 0.0, width_px, height_px}));
}

// Magnitude and phase against log10 of the frequency (the charts have linear axes), simulated
// and closed form, with the 0 dB and −180° lines.
std::string bode_png(const control::ResponseResult& r, const std::string& axis, int width_px,
                     int height_px) {
  render::Series db{"simulated", {}, {}, kSimulatedColor, 2.0},
      db_cf{"closed form", {}, {}, kReferenceColor, 1.5};
  render::Series deg{"simulated", {}, {}, kSimulatedColor, 2.0},
      deg_cf{"closed form", {}, {}, kReferenceColor, 1.5};
  for (const control::BodePoint& p : r.bode) {
    const double x = std::log10(p.frequency_hz);
    db.x.push_back(x);
    db.y.push_back(p.magnitude_db);
    db_cf.x.push_back(x);
    db_cf.y.push_back(p.closed_form_magnitude_db);
    deg.x.push_back(x);
    deg.y.push_back(p.phase_deg);
    deg_cf.x.push_back(x);
    deg_cf.y.push_back(p.closed_form_phase_deg);
  }
  const std::vector<double> ends{db.x.front(), db.x.back()};
  const render::Series zero{"0 dB", ends, {0.0, 0.0}, kGuideColor, 1.0};
  const render::Series half{"-180 deg", ends, {-180.0, -180.0}, kGuideColor, 1.0};
  const std::string x_label = "frequency, log10 Hz (0 = 1 Hz, 1 = 10 Hz)";
  return stacked_png({{axis + " loop gain L, magnitude (gain margin " +
                           fixed_text(r.measured.gain_margin_db, 1) + " dB)",
                       x_label,
                       "dB",
                       {zero, db_cf, db}},
                      {axis + " loop gain L, phase (phase margin " +
                           fixed_text(r.measured.phase_margin_deg, 1) + " deg)",
                       x_label,
                       "deg",
                       {half, deg_cf, deg}}},
                     width_px, height_px);
}

std::string step_png(const control::ResponseResult& r, const std::string& axis, int width_px,
                     int height_px) {
  render::Series sp{"setpoint", {}, {}, kReferenceColor, 1.5},
      y{"true", {}, {}, kSimulatedColor, 2.0};
  render::Series rate{"rate", {}, {}, kRateColor, 1.5};
  for (const control::ResponseSample& s : r.samples) {
    sp.x.push_back(s.t_s);
    sp.y.push_back(s.setpoint_deg);
    y.x.push_back(s.t_s);
    y.y.push_back(s.response_deg);
    rate.x.push_back(s.t_s);
    rate.y.push_back(s.rate_dps);
  }
  return stacked_png(
      {{axis + " step", "time (s)", "deg", {sp, y}}, {axis + " rate", "time (s)", "deg/s", {rate}}},
      width_px, height_px);
}

void check_positive(double v, const std::string& flag, const std::string& unit) {
  if (!(v > 0) || !std::isfinite(v))
    throw InputError(flag + " " + base::shortest_text(v) + ": expected " + unit + " > 0");
}

}  // namespace

void ControlResponseCommand::setup(CLI::App& app) {
  app.add_option("-o,--output", output_,
                 "Directory for response.csv (every execution: time_s, setpoint, response, error, "
                 "estimate, rates, torques, PWM) and step.csv with step.png, or bode.csv, "
                 "margins.csv and bode.png")
      ->required();
  app.add_option("--vehicle", request_.vehicle,
                 "Vehicle file, or a bundled one: quad-f450, hexa-f550, y6, quad-f450-cc3d")
      ->capture_default_str();
  app.add_option("--environment", request_.environment,
                 "Wind: calm, lab, rugby, arch or an environment file")
      ->capture_default_str();
  app.add_option("--seed", request_.seed, "Seed of the wind and the sensors' noise")
      ->check(seed_check())
      ->capture_default_str();
  app.add_option("--set", request_.sets,
                 "Override a key of the vehicle or environment file, e.g. "
                 "vehicle.controller.rate.roll.p=30 (repeatable)");
  app.add_option("--axis", axis_, "roll, pitch or yaw")
      ->check(CLI::IsMember({"roll", "pitch", "yaw"}))
      ->capture_default_str();
  app.add_option("--input", input_,
                 "step: the attitude setpoint steps by --amplitude-deg; chirp: a logarithmic sine "
                 "sweep of --amplitude-nm from --from-hz to --to-hz is added to the axis' torque")
      ->check(CLI::IsMember({"step", "chirp"}))
      ->capture_default_str();
  app.add_option("--loop", loop_,
                 "attitude: the attitude loop closed around the rate loop; rate: the rate loop "
                 "alone (the axis' attitude_p set to 0; chirp only)")
      ->check(CLI::IsMember({"attitude", "rate"}))
      ->capture_default_str();
  app.add_option("--amplitude-deg", test_.amplitude_deg,
                 "step: the step of the attitude setpoint, degrees (positive: right wing down, "
                 "nose up, clockwise)")
      ->check(CLI::Range(-45.0, 45.0))
      ->capture_default_str();
  app.add_option("--amplitude-nm", test_.amplitude_nm, "chirp: the torque sweep's amplitude, N m")
      ->check(CLI::Range(1e-6, 10.0))
      ->capture_default_str();
  app.add_option("--from-hz", test_.from_hz,
                 "chirp: the lowest frequency of the Bode plot, Hz (the sweep starts at 0.8 x)")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  app.add_option("--to-hz", test_.to_hz,
                 "chirp: the highest frequency of the Bode plot, Hz (the sweep ends at 1.25 x, "
                 "below half the rate)")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  app.add_option("--duration-s", duration_s_,
                 "The test after 2 s of hover, s (default: step 2, chirp 60)")
      ->check(CLI::Range(0.5, 3600.0));
  app.add_option("--rate-hz", test_.rate_hz, "The control task's execution rate, Hz")
      ->check(CLI::Range(20.0, 10'000.0))
      ->capture_default_str();
  app.add_option("--size", size_, "Size of the picture, WxH pixels")->capture_default_str();
}

int ControlResponseCommand::run() {
  // 1. Inputs, each checked before anything is written. prepare_flight reads the vehicle and
  // environment; the mission it needs is a placeholder (the test hovers at 10 m).
  const auto [width_px, height_px] = parse_size(size_);
  test_.axis = axis_ == "pitch" ? control::ResponseAxis::pitch
               : axis_ == "yaw" ? control::ResponseAxis::yaw
                                : control::ResponseAxis::roll;
  test_.input = input_ == "chirp" ? control::ResponseInput::chirp : control::ResponseInput::step;
  const bool chirp = test_.input == control::ResponseInput::chirp;
  test_.loop = loop_ == "rate" ? control::ResponseLoop::rate : control::ResponseLoop::attitude;
  if (!chirp && test_.loop == control::ResponseLoop::rate)
    throw InputError(
        "--loop rate: the step is a step of the attitude setpoint; use --loop "
        "attitude or --input chirp");
  test_.duration_s = duration_s_.value_or(chirp ? 60.0 : 2.0);
  if (!chirp && test_.amplitude_deg == 0) throw InputError("--amplitude-deg 0: the step is empty");
  check_positive(test_.amplitude_nm, "--amplitude-nm", "N m");
  if (chirp && !(test_.to_hz > test_.from_hz))
    throw InputError("--to-hz " + base::shortest_text(test_.to_hz) + ": expected above --from-hz " +
                     base::shortest_text(test_.from_hz));
  // The sweep runs to 1.25 × --to-hz, which must stay below the rate's Nyquist frequency.
  if (chirp && !(test_.to_hz * 1.25 < test_.rate_hz / 2))
    throw InputError("--to-hz " + base::shortest_text(test_.to_hz) +
                     ": expected below 0.4 × --rate-hz (" +
                     base::shortest_text(test_.rate_hz * 0.4) + " Hz)");
  // The estimate's segments (a sixth of the sweep) must hold two periods of the lowest frequency.
  if (chirp && test_.duration_s * test_.from_hz < 12)
    throw InputError("--duration-s " + base::shortest_text(test_.duration_s) +
                     ": expected at least 12 / --from-hz = " +
                     base::shortest_text(12 / test_.from_hz) + " s for a chirp");
  FlightRequest request = request_;
  request.mission = "random:2@10x10";
  for (const std::string& s : request.sets)
    if (s.rfind("scheduler.", 0) == 0)
      throw InputError("--set " + s + ": response runs the task at --rate-hz without a scheduler");
  const control::SimulationSettings settings = prepare_flight(request).settings;

  // A file of the user's in the way is refused before the test, not after it.
  base::check_output_names(
      output_, "control-response",
      chirp ? std::vector<std::string>{"response.csv", "bode.csv", "margins.csv", "bode.png"}
            : std::vector<std::string>{"response.csv", "step.csv", "step.png"});

  // 2. The test, then every file at once.
  const control::ResponseResult r = control::run_response(settings, test_);
  base::OutputSet set(output_, "control-response");
  set.add("response.csv", control::response_csv(r.samples));
  std::cout << "swath-control response: " << axis_ << ' ' << input_ << " into the " << loop_
            << " loop at " << base::shortest_text(test_.rate_hz) << " Hz: ";
  if (r.step) {
    set.add("step.csv", control::step_csv(*r.step, *r.step_estimate));
    set.add("step.png", step_png(r, axis_, width_px, height_px));
    auto figures = [](const control::StepMetrics& m) {
      return "rise time " + fixed_text(m.rise_time_s, 3) + " s, overshoot " +
             fixed_text(m.overshoot_percent, 1) + " %, settling time " +
             fixed_text(m.settling_time_s, 3) + " s" + (m.settled ? "" : " (not settled)");
    };
    std::cout << "true attitude: " << figures(*r.step)
              << "; estimate: " << figures(*r.step_estimate);
  } else {
    set.add("bode.csv", control::bode_csv(r.bode));
    set.add("margins.csv", control::margins_csv(r.measured, r.closed_form));
    set.add("bode.png", bode_png(r, axis_, width_px, height_px));
    std::cout << "phase margin " << fixed_text(r.measured.phase_margin_deg, 1) << " deg at "
              << fixed_text(r.measured.gain_crossover_hz, 2) << " Hz, gain margin "
              << fixed_text(r.measured.gain_margin_db, 1) << " dB at "
              << fixed_text(r.measured.phase_crossover_hz, 2) << " Hz (closed form "
              << fixed_text(r.closed_form.phase_margin_deg, 1) << " deg, "
              << fixed_text(r.closed_form.gain_margin_db, 1) << " dB)";
  }
  set.commit();
  std::cout << "; wrote " << output_ << '\n';
  return base::kExitSuccess;
}

}  // namespace swath::apps

#include "swath/control/config.hpp"

#include <cmath>
#include <initializer_list>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"

namespace swath::control {
namespace {

using base::InputError;
using base::kInf;
using base::YamlMap;

// The index of the text at `key` among `names` (absent: `fallback`).
template <typename Enum>
Enum choice(const YamlMap& m, const char* key, Enum fallback,
            std::initializer_list<const char*> names) {
  if (!m.has(key)) return fallback;
  const std::string value = m.text(key, "");
  int index = 0;
  std::string known;
  for (const char* name : names) {
    if (value == name) return static_cast<Enum>(index);
    known += (index++ ? ", " : "") + std::string(name);
  }
  throw InputError(m.where(key) + " must be one of " + known + ", found '" + value + "'");
}

// A whole number at `key` in [lo, hi].
std::int64_t whole(const YamlMap& m, const char* key, std::int64_t fallback, double lo, double hi) {
  const double v = m.number(key, static_cast<double>(fallback), lo, hi);
  if (v != std::floor(v)) throw InputError(m.where(key) + " must be a whole number");
  return static_cast<std::int64_t>(v);
}

// [x, y, z] at `key`, each in [lo, hi] (open at lo when `open_lo`).
Vec3 triple(const YamlMap& m, const char* key, const Vec3& fallback, double lo, double hi,
            bool open_lo) {
  if (!m.has(key)) return fallback;
  const std::vector<double> v = m.numbers(key);
  if (v.size() != 3) throw InputError(m.where(key) + " must be a list of 3 numbers");
  for (const double x : v)
    if (x < lo || x > hi || (open_lo && x == lo))
      throw InputError(m.where(key) + " must hold numbers in " + (open_lo ? "(" : "[") +
                       std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return {v[0], v[1], v[2]};
}

PidGains read_pid(const YamlMap& m, PidGains g) {
  m.allow({"p", "i", "d", "i_limit", "d_lpf_hz"});
  g.p = m.number("p", g.p, 0, 1e4);
  g.i = m.number("i", g.i, 0, 1e4);
  g.d = m.number("d", g.d, 0, 1e4);
  g.i_limit = m.number("i_limit", g.i_limit, 0, 1e4);
  g.d_lpf_hz = m.number("d_lpf_hz", g.d_lpf_hz, 0, 1e5);
  return g;
}

EstimatorSettings read_estimator(const YamlMap& m) {
  m.allow({"type", "attitude_gain", "mag_gain", "bias_gain", "process_accel_m_s2_per_sqrt_hz",
           "fix_delay_s"});
  EstimatorSettings s;
  s.type = choice(m, "type", s.type, {"complementary", "truth"});
  s.attitude_gain_1_s = m.number("attitude_gain", s.attitude_gain_1_s, 0, 100);
  s.mag_gain_1_s = m.number("mag_gain", s.mag_gain_1_s, 0, 100);
  s.bias_gain_1_s = m.number("bias_gain", s.bias_gain_1_s, 0, 100);
  s.process_accel_m_s2_per_sqrt_hz =
      m.number("process_accel_m_s2_per_sqrt_hz", s.process_accel_m_s2_per_sqrt_hz, 0, 1e3, true);
  if (m.has("fix_delay_s")) s.fix_delay_s = m.number("fix_delay_s", 0, 0, 1);
  return s;
}

ControlLimits read_limits(const YamlMap& m) {
  m.allow({"max_speed_m_s", "max_climb_m_s", "max_accel_m_s2", "max_tilt_deg", "max_rate_dps",
           "crash_tilt_deg", "yaw_slew_dps"});
  ControlLimits l;
  l.max_speed_m_s = m.number("max_speed_m_s", l.max_speed_m_s, 0, 100, true);
  l.max_climb_m_s = m.number("max_climb_m_s", l.max_climb_m_s, 0, 50, true);
  l.max_accel_m_s2 = m.number("max_accel_m_s2", l.max_accel_m_s2, 0, 50, true);
  l.max_tilt_deg = m.number("max_tilt_deg", l.max_tilt_deg, 0, 80, true);
  l.max_rate_dps = triple(m, "max_rate_dps", l.max_rate_dps, 0, 3600, true);
  l.crash_tilt_deg = m.number("crash_tilt_deg", l.crash_tilt_deg, 0, 180, true);
  l.yaw_slew_dps = m.number("yaw_slew_dps", l.yaw_slew_dps, 0, 3600);
  if (l.crash_tilt_deg <= l.max_tilt_deg)
    throw InputError(m.where("crash_tilt_deg") + " must exceed max_tilt_deg");
  return l;
}

ControllerGains read_controller(const YamlMap& m) {
  m.allow({"position_p", "velocity_xy", "velocity_z", "attitude_p", "rate", "limits", "dt_mode",
           "change_threshold_us"});
  ControllerGains g;
  g.position_p_1_s = m.number("position_p", g.position_p_1_s, 0, 1e3);
  g.velocity_xy = read_pid(m.map("velocity_xy"), g.velocity_xy);
  g.velocity_z = read_pid(m.map("velocity_z"), g.velocity_z);
  g.attitude_p_1_s = triple(m, "attitude_p", g.attitude_p_1_s, 0, 1e3, false);
  const YamlMap rate = m.map("rate");
  rate.allow({"roll", "pitch", "yaw"});
  g.rate_roll = read_pid(rate.map("roll"), g.rate_roll);
  g.rate_pitch = read_pid(rate.map("pitch"), g.rate_pitch);
  g.rate_yaw = read_pid(rate.map("yaw"), g.rate_yaw);
  g.limits = read_limits(m.map("limits"));
  g.dt_mode = choice(m, "dt_mode", g.dt_mode, {"measured", "nominal"});
  g.change_threshold_us = m.number("change_threshold_us", g.change_threshold_us, 0, 1000, true);
  return g;
}

BackgroundTask read_background(const YamlMap& m) {
  m.allow({"name", "rate_hz", "cycles"});
  BackgroundTask t;
  t.name = m.text("name", "background");
  t.rate_hz = m.number("rate_hz", t.rate_hz, 0, 1e6, true);
  t.cycles = whole(m, "cycles", t.cycles, 0, 1e12);
  return t;
}

ComputerSettings read_computer(const YamlMap& m, const std::string& source) {
  m.allow({"clock_hz", "control_cycles", "dispatch_cycles", "driver_cycles", "trigger_check_cycles",
           "refit_cycles_per_point", "idle_w", "active_w", "control_preempts_background",
           "background"});
  ComputerSettings c;
  c.clock_hz = m.number("clock_hz", c.clock_hz, 1e3, 1e11);
  c.control_cycles = whole(m, "control_cycles", c.control_cycles, 0, 1e12);
  c.dispatch_cycles = whole(m, "dispatch_cycles", c.dispatch_cycles, 0, 1e12);
  c.driver_cycles = whole(m, "driver_cycles", c.driver_cycles, 0, 1e12);
  c.trigger_check_cycles = whole(m, "trigger_check_cycles", c.trigger_check_cycles, 0, 1e12);
  c.refit_cycles_per_point = whole(m, "refit_cycles_per_point", c.refit_cycles_per_point, 0, 1e9);
  c.idle_w = m.number("idle_w", c.idle_w, 0, 1e3);
  c.active_w = m.number("active_w", c.active_w, 0, 1e3);
  if (c.active_w < c.idle_w) throw InputError(m.where("active_w") + " must be at least idle_w");
  c.control_preempts_background =
      m.flag("control_preempts_background", c.control_preempts_background);
  if (m.has("background")) {
    const YAML::Node list = m.node()["background"];
    if (!list.IsSequence()) throw InputError(m.where("background") + " must be a list");
    c.background.clear();
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!list[k].IsMap()) throw InputError(m.where("background") + " must list mappings");
      const YamlMap item(list[k], source, "computer.background[" + std::to_string(k) + "]");
      c.background.push_back(read_background(item));
    }
  }
  return c;
}

double whole_ns_rate(const YamlMap& m, const char* key, double fallback, double hi) {
  const double rate = m.number(key, fallback, 0, hi, true);
  if (vehicle::period_of_rate(rate) == 0)
    throw InputError(m.where(key) + " must divide a second into a whole number of nanoseconds");
  return rate;
}

RunSettings read_run(const YamlMap& m) {
  m.allow({"metrics_from_s", "output_interval_s", "max_time_s", "setpoint_rate_hz", "max_step_s"});
  RunSettings r;
  r.metrics_from_s = m.number("metrics_from_s", r.metrics_from_s, 0, 86'400);
  r.output_interval_s = m.number("output_interval_s", r.output_interval_s, 0, 3600, true);
  r.max_time_s = m.number("max_time_s", r.max_time_s, 0, 86'400, true);
  r.setpoint_rate_hz = whole_ns_rate(m, "setpoint_rate_hz", r.setpoint_rate_hz, 1e4);
  r.max_step_s = m.number("max_step_s", r.max_step_s, 1e-5, 0.002, true);
  return r;
}

std::vector<InitialModel> read_initial_models(const YamlMap& m) {
  std::vector<InitialModel> models;
  if (!m.node() || m.node().IsNull()) return models;
  base::check_plain_unique_keys(m.node(), m.where("initial_models"));
  for (const auto& kv : m.node()) {
    const std::string name = kv.first.Scalar();
    const std::vector<double> beta = m.numbers(name.c_str());
    if (beta.size() != 2) throw InputError(m.where(name.c_str()) + " must be [beta1, beta2]");
    models.push_back({name, beta[0], beta[1]});
  }
  return models;
}

ReactiveSettings read_reactive(const YamlMap& m) {
  m.allow({"p_run", "boot_s", "boot_rate_hz", "failsafe_s", "failsafe_mode", "delta_reference",
           "trigger_signal", "setpoint_forces_execution", "accumulation", "fit", "initial_models",
           "oracle", "graph_execution"});
  ReactiveSettings r;
  r.p_run = m.number("p_run", r.p_run, 0, 1, true);
  if (r.p_run >= 1) throw InputError(m.where("p_run") + " must lie in (0, 1)");
  r.boot_s = m.number("boot_s", r.boot_s, 0, 86'400);
  if (m.has("boot_rate_hz")) r.boot_rate_hz = whole_ns_rate(m, "boot_rate_hz", 0, 1e5);
  r.failsafe_s = m.number("failsafe_s", r.failsafe_s, 0, 10, true);
  r.failsafe_mode = choice(m, "failsafe_mode", r.failsafe_mode, {"watchdog", "periodic"});
  r.delta_reference =
      choice(m, "delta_reference", r.delta_reference, {"last_execution", "last_sample"});
  r.trigger_signal = choice(m, "trigger_signal", r.trigger_signal, {"filtered", "raw"});
  r.setpoint_forces_execution = m.flag("setpoint_forces_execution", r.setpoint_forces_execution);
  const YamlMap acc = m.map("accumulation");
  acc.allow({"min_rate_hz", "max_wait_s"});
  r.accumulation_min_rate_hz = acc.number("min_rate_hz", r.accumulation_min_rate_hz, 0, 1e6);
  r.accumulation_max_wait_s = acc.number("max_wait_s", r.accumulation_max_wait_s, 0, 1);
  const YamlMap fit = m.map("fit");
  fit.allow({"method", "bins", "min_per_bin", "refit_period_s", "feedback", "dataset_capacity"});
  r.fit_method = choice(fit, "method", r.fit_method, {"logit_ols", "logit_wls", "mle"});
  r.fit_bins = static_cast<int>(whole(fit, "bins", r.fit_bins, 2, 1000));
  r.fit_min_per_bin = static_cast<int>(whole(fit, "min_per_bin", r.fit_min_per_bin, 1, 1e6));
  r.fit_refit_period_s = fit.number("refit_period_s", r.fit_refit_period_s, 0, 3600, true);
  r.fit_feedback = choice(fit, "feedback", r.fit_feedback, {"errors", "all", "none"});
  r.fit_dataset_capacity =
      static_cast<int>(whole(fit, "dataset_capacity", r.fit_dataset_capacity, 16, 1e7));
  r.initial_models = read_initial_models(m.map("initial_models"));
  r.oracle = m.flag("oracle", r.oracle);
  r.graph_execution = choice(m, "graph_execution", r.graph_execution, {"whole", "partial"});
  return r;
}

}  // namespace

VehicleControlConfig parse_vehicle_control(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] {
    const YamlMap root(base::load_yaml(text, source), source, "");
    root.allow({"name", "frame", "rotors", "propeller", "motor", "esc", "sensors", "estimator",
                "controller", "computer", "avionics_w", "battery"});
    VehicleControlConfig c;
    c.estimator = read_estimator(root.map("estimator"));
    c.controller = read_controller(root.map("controller"));
    c.computer = read_computer(root.map("computer"), source);
    return c;
  });
}

VehicleControlConfig read_vehicle_control(const std::string& path) {
  return parse_vehicle_control(
      base::read_text_file(path, "vehicle file", base::kMaxConfigFileBytes), path);
}

std::string apply_overrides(const std::string& text, const std::string& source,
                            const std::vector<Override>& overrides) {
  if (overrides.empty()) return text;
  return base::yaml_guard(source, [&] {
    YAML::Node root =
        text.empty() ? YAML::Node(YAML::NodeType::Map) : base::load_yaml(text, source);
    if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    for (const Override& o : overrides) {
      const std::string where = source + ": --set " + o.key + "=" + o.value;
      YAML::Node value;
      try {
        value = YAML::Load(o.value);
      } catch (const YAML::Exception&) {
        throw InputError(where + ": the value is not YAML (a number, a word or [a, b, c])");
      }
      // Walk the dotted key with fresh handles (yaml-cpp's operator= on a held handle would
      // overwrite the node it refers to, not rebind the handle).
      std::vector<std::string> parts;
      for (std::size_t start = 0;;) {
        const std::size_t dot = o.key.find('.', start);
        parts.push_back(o.key.substr(start, dot - start));
        if (dot == std::string::npos) break;
        start = dot + 1;
      }
      for (const std::string& part : parts)
        if (part.empty()) throw InputError(where + ": the key has an empty part");
      std::vector<YAML::Node> chain{root};
      for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
        YAML::Node next = chain.back()[parts[k]];
        if (!next.IsDefined() || next.IsNull()) {
          chain.back()[parts[k]] = YAML::Node(YAML::NodeType::Map);
          next = chain.back()[parts[k]];
        }
        if (!next.IsMap())
          throw InputError(where + ": " + parts[k] + " is not a mapping of keys in the file");
        chain.push_back(next);
      }
      if (!chain.back().IsMap()) throw InputError(where + ": the file is not a mapping of keys");
      chain.back()[parts.back()] = value;
    }
    YAML::Emitter out;
    out << root;
    return std::string(out.c_str()) + "\n";
  });
}

SchedulerConfig parse_scheduler_config(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] {
    const YamlMap root(base::load_yaml(text, source), source, "");
    root.allow({"mode", "rate_hz", "reactive", "run"});
    if (!root.has("mode"))
      throw InputError(source + ": 'mode' (time_triggered or reactive) is required");
    SchedulerConfig c;
    c.mode = choice(root, "mode", c.mode, {"time_triggered", "reactive"});
    c.rate_hz = whole_ns_rate(root, "rate_hz", c.rate_hz, 1e5);
    c.reactive = read_reactive(root.map("reactive"));
    c.run = read_run(root.map("run"));
    if (c.mode == SchedulerMode::reactive && c.reactive.boot_s >= c.run.max_time_s)
      throw InputError(root.where("reactive") + ": boot_s must be below run.max_time_s");
    if (c.mode == SchedulerMode::reactive && c.reactive.boot_s == 0 &&
        c.reactive.initial_models.empty())
      throw InputError(root.where("reactive") + ": boot_s 0 needs initial_models");
    return c;
  });
}

SchedulerConfig read_scheduler_config(const std::string& path) {
  return parse_scheduler_config(
      base::read_text_file(path, "scheduler file", base::kMaxConfigFileBytes), path);
}

}  // namespace swath::control

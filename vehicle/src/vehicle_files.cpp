#include "swath/vehicle/vehicle_files.hpp"

#include <algorithm>
#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"

namespace swath::vehicle {
namespace {

using base::InputError;
using base::kInf;
using base::YamlMap;

Vec3 vec3(const YamlMap& m, const char* key, Vec3 fallback, double lo, double hi) {
  if (!m.has(key)) return fallback;
  const std::vector<double> v = m.numbers(key);
  if (v.size() != 3) throw InputError(m.where(key) + " must be a list of 3 numbers [x, y, z]");
  for (double x : v)
    if (x < lo || x > hi)
      throw InputError(m.where(key) + " must hold numbers in [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "]");
  return {v[0], v[1], v[2]};
}

int spin_of(const YamlMap& m, const char* key, int fallback) {
  const std::string s = m.text(key, fallback > 0 ? "ccw" : "cw");
  if (s == "ccw") return +1;
  if (s == "cw") return -1;
  throw InputError(m.where(key) + " must be ccw or cw, found '" + s + "'");
}

void read_frame(const YamlMap& m, Frame& f) {
  m.allow({"mass_kg", "inertia_kg_m2", "drag_linear_n_per_m_s", "drag_cda_m2",
           "flapping_nm_per_m_s", "torque_noise"});
  f.mass_kg = m.number("mass_kg", f.mass_kg, 0.0, 1000.0, true);
  f.inertia_kg_m2 = vec3(m, "inertia_kg_m2", f.inertia_kg_m2, 1e-6, 1e4);
  f.drag_linear_n_per_m_s = vec3(m, "drag_linear_n_per_m_s", f.drag_linear_n_per_m_s, 0, 1e3);
  f.drag_cda_m2 = vec3(m, "drag_cda_m2", f.drag_cda_m2, 0, 100);
  f.flapping_nm_per_m_s = m.number("flapping_nm_per_m_s", f.flapping_nm_per_m_s, 0, 100);
  const YamlMap noise = m.map("torque_noise");
  noise.allow({"sigma_nm", "time_constant_s"});
  f.torque_noise_sigma_nm = noise.number("sigma_nm", f.torque_noise_sigma_nm, 0, 10);
  f.torque_noise_time_constant_s =
      noise.number("time_constant_s", f.torque_noise_time_constant_s, 0, 100, true);
}

std::vector<Rotor> read_rotors(const YamlMap& root, const std::string& source) {
  const YAML::Node node = root.node()["rotors"];
  if (node && node.IsSequence()) {
    std::vector<Rotor> rotors;
    if (node.size() == 0 || node.size() > kMaxRotors)
      throw InputError(root.where("rotors") + " must list 1 to 8 rotors");
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YamlMap r(node[i], source, "rotors[" + std::to_string(i) + "]");
      r.allow({"position_m", "spin", "efficiency"});
      if (!r.has("position_m"))
        throw InputError(root.where("rotors") + ": rotor " + std::to_string(i + 1) +
                         " needs position_m");
      rotors.push_back({vec3(r, "position_m", {}, -100, 100), spin_of(r, "spin", +1),
                        r.number("efficiency", 1.0, 0.0, 1.0, true)});
    }
    return rotors;
  }
  const YamlMap m = root.map("rotors");
  m.allow({"layout", "arm_m", "first_spin", "coaxial_lower_efficiency"});
  const std::string layout = m.text("layout", "quad_x");
  const double arm = m.number("arm_m", 0.225, 0.0, 100.0, true);
  const int spin = spin_of(m, "first_spin", +1);
  const double lower = m.number("coaxial_lower_efficiency", 0.8, 0.0, 1.0, true);
  if (layout == "quad_x") return rotor_layout(RotorLayout::quad_x, arm, spin, lower);
  if (layout == "hexa_x") return rotor_layout(RotorLayout::hexa_x, arm, spin, lower);
  if (layout == "y6") return rotor_layout(RotorLayout::y6, arm, spin, lower);
  throw InputError(m.where("layout") + " must be quad_x, hexa_x or y6, found '" + layout + "'");
}

void read_propulsion(const YamlMap& root, Propulsion& p) {
  const YamlMap prop = root.map("propeller");
  prop.allow({"thrust_coeff_n_s2", "torque_coeff_nm_s2", "max_speed_rad_s", "diameter_m",
              "induced_power_factor", "translational_lift"});
  p.thrust_coeff_n_s2 = prop.number("thrust_coeff_n_s2", p.thrust_coeff_n_s2, 0, 1, true);
  p.torque_coeff_nm_s2 = prop.number("torque_coeff_nm_s2", p.torque_coeff_nm_s2, 0, 1, true);
  p.max_speed_rad_s = prop.number("max_speed_rad_s", p.max_speed_rad_s, 0, 1e5, true);
  p.diameter_m = prop.number("diameter_m", p.diameter_m, 0, 10, true);
  p.induced_power_factor = prop.number("induced_power_factor", p.induced_power_factor, 1, 3);
  p.translational_lift = prop.flag("translational_lift", p.translational_lift);
  const YamlMap motor = root.map("motor");
  motor.allow({"time_constant_s", "rotor_inertia_kg_m2", "kv_rpm_per_v", "resistance_ohm",
               "no_load_current_a", "esc_efficiency"});
  p.time_constant_s = motor.number("time_constant_s", p.time_constant_s, 1e-4, 10);
  p.rotor_inertia_kg_m2 = motor.number("rotor_inertia_kg_m2", p.rotor_inertia_kg_m2, 0, 1);
  p.kv_rpm_per_v = motor.number("kv_rpm_per_v", p.kv_rpm_per_v, 0, 1e5, true);
  p.resistance_ohm = motor.number("resistance_ohm", p.resistance_ohm, 0, 100);
  p.no_load_current_a = motor.number("no_load_current_a", p.no_load_current_a, 0, 100);
  p.esc_efficiency = motor.number("esc_efficiency", p.esc_efficiency, 0, 1, true);
}

// Translational lift splits the hover shaft power into profile and induced parts; an induced
// part above the whole (a propeller better than momentum theory allows) means the coefficients
// and the diameter do not belong together.
void check_induced_share(const YamlMap& root, const Airframe& a) {
  const Propulsion& p = a.propulsion;
  if (!p.translational_lift) return;
  double share = 0;
  for (const Rotor& r : a.rotors)
    share = std::max(share, induced_power_share(p, r.efficiency, a.frame.air_density_kg_m3));
  if (share > 1.0)
    throw InputError(root.map("propeller").where("diameter_m") +
                     ": with translational_lift, κ T v_h / (k_Q Ω³) = " + std::to_string(share) +
                     " exceeds 1 (the induced power would exceed the shaft power k_Q Ω³): the "
                     "disk, thrust_coeff_n_s2 and torque_coeff_nm_s2 do not fit together");
}

void read_esc(const YamlMap& m, EscSettings& e) {
  m.allow({"pwm_min_us", "pwm_max_us", "resolution_us", "frame_rate_hz", "mapping"});
  e.pwm_min_us = m.number("pwm_min_us", e.pwm_min_us, 0, 1e5);
  e.pwm_max_us = m.number("pwm_max_us", e.pwm_max_us, 0, 1e5);
  if (!(e.pwm_max_us > e.pwm_min_us))
    throw InputError(m.where("pwm_max_us") + " must be greater than pwm_min_us");
  e.resolution_us = m.number("resolution_us", e.resolution_us, 0, 1000);
  e.frame_rate_hz = m.number("frame_rate_hz", e.frame_rate_hz, 0, 1e5);
  const std::string mapping = m.text("mapping", "thrust_linear");
  if (mapping != "thrust_linear" && mapping != "linear")
    throw InputError(m.where("mapping") + " must be thrust_linear or linear");
  e.thrust_linear = mapping == "thrust_linear";
}

SensorType sensor_type(const YamlMap& m) {
  const std::string t = m.text("type", "");
  if (t == "gyro") return SensorType::gyro;
  if (t == "accel") return SensorType::accel;
  if (t == "mag") return SensorType::mag;
  if (t == "baro") return SensorType::baro;
  if (t == "position") return SensorType::position;
  throw InputError(m.where("type") + " must be gyro, accel, mag, baro or position, found '" + t +
                   "'");
}

SensorSettings read_sensor(const YamlMap& m) {
  m.allow({"name", "type", "rate_hz", "period_us", "phase_s", "noise", "bias", "lsb", "range",
           "latency_s", "lpf_hz", "trigger", "velocity_noise_m_s", "markov"});
  SensorSettings s;
  s.type = sensor_type(m);
  s.name = m.text("name", m.text("type", ""));
  if (m.has("rate_hz") == m.has("period_us"))
    throw InputError(m.where("rate_hz") + ": give one of rate_hz and period_us");
  if (m.has("rate_hz")) {
    const double rate = m.number("rate_hz", 0, 0, 1e6, true);
    s.period_ns = period_of_rate(rate);
    if (s.period_ns == 0)
      throw InputError(m.where("rate_hz") + " " + std::to_string(rate) +
                       " Hz has no period of whole nanoseconds; give period_us instead");
  } else {
    s.period_ns = from_seconds(m.number("period_us", 0, 1, 1e9) * 1e-6);
  }
  s.phase_ns = from_seconds(m.number("phase_s", 0, 0, 1));
  s.noise = m.number("noise", 0, 0, 1e6);
  const YamlMap bias = m.map("bias");
  bias.allow({"constant", "random_walk_per_sqrt_s"});
  s.bias_constant = bias.number("constant", 0, -1e6, 1e6);
  s.bias_random_walk_per_sqrt_s = bias.number("random_walk_per_sqrt_s", 0, 0, 1e6);
  s.lsb = m.number("lsb", 0, 0, 1e6);
  s.range = m.number("range", 0, 0, 1e9);
  s.latency_s = m.number("latency_s", 0, 0, 10);
  s.lpf_hz = m.number("lpf_hz", 0, 0, 1e6);
  s.trigger = m.flag("trigger", false);
  s.velocity_noise_m_s = m.number("velocity_noise_m_s", 0, 0, 1e3);
  const YamlMap markov = m.map("markov");
  markov.allow({"sigma_m", "time_constant_s"});
  s.markov_sigma_m = markov.number("sigma_m", 0, 0, 1e4);
  s.markov_time_constant_s = markov.number("time_constant_s", 60, 0, 1e6, true);
  return s;
}

VehiclePhysics vehicle_from_yaml(const std::string& text, const std::string& source) {
  const YAML::Node root = base::load_yaml(text, source);
  if (!root.IsMap()) throw InputError(source + ": a vehicle file is a mapping of keys");
  const YamlMap m(root, source, "");
  m.allow({"name", "frame", "rotors", "propeller", "motor", "esc", "sensors", "avionics_w",
           "battery", "estimator", "controller", "computer"});
  VehiclePhysics v = default_vehicle();
  v.airframe.name = m.text("name", v.airframe.name);
  read_frame(m.map("frame"), v.airframe.frame);
  if (m.has("rotors")) v.airframe.rotors = read_rotors(m, source);
  read_propulsion(m, v.airframe.propulsion);
  check_induced_share(m, v.airframe);
  read_esc(m.map("esc"), v.esc);
  v.avionics_w = m.number("avionics_w", v.avionics_w, 0, 1e4);
  if (m.has("sensors")) {
    const YAML::Node list = root["sensors"];
    if (!list.IsSequence() || list.size() == 0 || list.size() > 32)
      throw InputError(m.where("sensors") + " must list 1 to 32 sensors");
    v.sensors.clear();
    for (std::size_t i = 0; i < list.size(); ++i)
      v.sensors.push_back(
          read_sensor(YamlMap(list[i], source, "sensors[" + std::to_string(i) + "]")));
  }
  v.warnings = m.warnings();
  return v;
}

Environment environment_from_yaml(const std::string& text, const std::string& source) {
  const YAML::Node root = base::load_yaml(text, source);
  if (!root.IsMap()) throw InputError(source + ": an environment file is a mapping of keys");
  const YamlMap m(root, source, "");
  m.allow({"name", "preset", "mean_wind", "turbulence", "gusts", "regions", "air_density_kg_m3",
           "gravity_m_s2"});
  Environment e = m.has("preset") ? environment_preset(m.text("preset", "calm")) : Environment{};
  e.name = m.text("name", source);
  const YamlMap w = m.map("mean_wind");
  w.allow({"speed_m_s", "from_deg", "reference_height_m", "roughness_m", "ramp_m_s_per_min"});
  MeanWind& mw = e.mean_wind;
  mw.speed_m_s = w.number("speed_m_s", mw.speed_m_s, 0, 100);
  mw.from_deg = w.number("from_deg", mw.from_deg, -360, 360);
  mw.reference_height_m = w.number("reference_height_m", mw.reference_height_m, 0, 1e4, true);
  mw.roughness_m = w.number("roughness_m", mw.roughness_m, 0, 10, true);
  if (!(mw.reference_height_m > mw.roughness_m))
    throw InputError(w.where("roughness_m") + " must be below reference_height_m");
  mw.ramp_m_s_per_min = w.number("ramp_m_s_per_min", mw.ramp_m_s_per_min, -100, 100);
  const YamlMap t = m.map("turbulence");
  t.allow({"model", "w20_m_s", "reference_speed_m_s", "update_hz"});
  const std::string model = t.text("model", e.dryden ? "dryden" : "none");
  if (model != "dryden" && model != "none")
    throw InputError(t.where("model") + " must be dryden or none");
  e.dryden = model == "dryden";
  e.w20_m_s = t.number("w20_m_s", e.w20_m_s, 0, 100);
  e.reference_speed_m_s = t.number("reference_speed_m_s", e.reference_speed_m_s, 0, 200);
  e.update_hz = t.number("update_hz", e.update_hz, 1, 1e4);
  const YamlMap g = m.map("gusts");
  g.allow({"rate_per_min", "amplitude_m_s", "rise_s", "hold_s", "vertical_share"});
  e.gusts.rate_per_min = g.number("rate_per_min", e.gusts.rate_per_min, 0, 600);
  auto range = [&](const char* key, std::array<double, 2>& r, double hi) {
    if (!g.has(key)) return;
    const std::vector<double> v = g.numbers(key);
    if (v.size() != 2 || v[0] < 0 || v[1] < v[0] || v[1] > hi)
      throw InputError(g.where(key) + " must be [lo, hi] with 0 <= lo <= hi <= " +
                       std::to_string(static_cast<int>(hi)));
    r = {v[0], v[1]};
  };
  range("amplitude_m_s", e.gusts.amplitude_m_s, 100);
  range("rise_s", e.gusts.rise_s, 600);
  range("hold_s", e.gusts.hold_s, 600);
  if (e.gusts.rise_s[0] <= 0 && e.gusts.rate_per_min > 0)
    throw InputError(g.where("rise_s") + " must be > 0");
  e.gusts.vertical_share = g.number("vertical_share", e.gusts.vertical_share, 0, 1);
  if (m.has("regions")) {
    const YAML::Node list = root["regions"];
    if (!list.IsSequence() || list.size() > 100)
      throw InputError(m.where("regions") + " must list at most 100 regions");
    e.regions.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const YamlMap r(list[i], source, "regions[" + std::to_string(i) + "]");
      r.allow({"center_m", "radius_m", "wind_m_s"});
      const std::vector<double> c = r.numbers("center_m");
      if (c.size() != 2) throw InputError(r.where("center_m") + " must be [east, north]");
      e.regions.push_back({{c[0], c[1]},
                           r.number("radius_m", 0, 0, 1e5, true),
                           vec3(r, "wind_m_s", {}, -100, 100)});
    }
  }
  e.air_density_kg_m3 = m.number("air_density_kg_m3", e.air_density_kg_m3, 0, 10, true);
  e.gravity_m_s2 = m.number("gravity_m_s2", e.gravity_m_s2, 0, 100, true);
  e.warnings = m.warnings();
  return e;
}

}  // namespace

std::vector<SensorSettings> default_sensors() {
  auto sensor = [](const char* name, SensorType type, SimTime period_ns) {
    SensorSettings s;
    s.name = name;
    s.type = type;
    s.period_ns = period_ns;
    s.trigger = true;
    return s;
  };
  SensorSettings gyro = sensor("gyro", SensorType::gyro, 1'000'000);
  gyro.noise = 0.01, gyro.bias_random_walk_per_sqrt_s = 1e-4, gyro.lsb = 1.065e-3;
  gyro.range = 34.9, gyro.lpf_hz = 80;
  SensorSettings accel = sensor("accel", SensorType::accel, 1'000'000);
  accel.noise = 0.3, accel.bias_random_walk_per_sqrt_s = 1e-3, accel.lsb = 4.79e-3;
  accel.range = 156.9, accel.lpf_hz = 30;
  SensorSettings mag = sensor("mag", SensorType::mag, 10'000'000);
  mag.noise = 0.01, mag.lsb = 2e-3, mag.range = 2;
  SensorSettings baro = sensor("baro", SensorType::baro, 20'000'000);
  baro.noise = 0.1, baro.bias_random_walk_per_sqrt_s = 1e-3, baro.lsb = 0.01, baro.lpf_hz = 5;
  SensorSettings gps = sensor("gps", SensorType::position, 100'000'000);
  gps.noise = 0.1, gps.velocity_noise_m_s = 0.1, gps.latency_s = 0.1;
  gps.markov_sigma_m = 0.5, gps.markov_time_constant_s = 60;
  return {gyro, accel, mag, baro, gps};
}

VehiclePhysics default_vehicle() {
  VehiclePhysics v;
  v.sensors = default_sensors();
  return v;
}

VehiclePhysics parse_vehicle(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] { return vehicle_from_yaml(text, source); });
}

Environment environment_preset(const std::string& name) {
  Environment e;
  e.name = name;
  if (name == "calm") return e;
  if (name == "lab") {
    e.dryden = true;
    e.w20_m_s = 0.5;
    e.regions = {{{5, 5}, 1.5, {0, 0, -1}}};  // the ceiling duct
    return e;
  }
  if (name == "rugby" || name == "arch") {
    const bool arch = name == "arch";
    e.mean_wind = {arch ? 4.1 : 2.6, arch ? 240.0 : 270.0, 6.1, arch ? 0.05 : 0.03,
                   arch ? 0.05 : 0.0};
    e.dryden = true;
    e.w20_m_s = e.mean_wind.speed_m_s;
    e.gusts.rate_per_min = arch ? 3 : 1;
    e.gusts.amplitude_m_s = arch ? std::array<double, 2>{1.5, 4} : std::array<double, 2>{1, 2.5};
    e.gusts.rise_s = arch ? std::array<double, 2>{0.3, 1.2} : std::array<double, 2>{0.5, 1.5};
    e.gusts.hold_s = {0, 2};
    e.gusts.vertical_share = arch ? 0.2 : 0.1;
    return e;
  }
  throw InputError("environment '" + name +
                   "': no such preset (calm, lab, rugby, arch), and not a file");
}

Environment parse_environment(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] { return environment_from_yaml(text, source); });
}

}  // namespace swath::vehicle

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"
#include "swath/vehicle/random.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::worlds {

using base::InputError;
using base::YamlMap;

double BaseWorld::sense_time_s(const std::string& name) const {
  return sensor(name).time_s;
}

const SensorSpec& BaseWorld::sensor(const std::string& name) const {
  for (const SensorSpec& s : sensors)
    if (s.name == name) return s;
  throw fleet::ActionFailed("unknown_sensor: this " + kind_ + " world has no sensor \"" + name +
                            "\"");
}

double BaseWorld::place_noise(const std::string& name, double x_m, double y_m) const {
  std::uint64_t key = seed ^ vehicle::fnv1a(name);
  key ^= static_cast<std::uint64_t>(std::llround(x_m * 1000.0)) * 0x9e3779b97f4a7c15ull;
  key ^= static_cast<std::uint64_t>(std::llround(y_m * 1000.0)) * 0xc2b2ae3d27d4eb4full;
  vehicle::SplitMix64 rng(key);
  return rng.normal();
}

fleet::Reading HotspotWorld::sense(const std::string& name, const Vec3& at, double) const {
  const SensorSpec& s = sensor(name);
  const double d = std::max(1.0, std::hypot(at.x - source_m.x, at.y - source_m.y));
  fleet::Reading r;
  r.sensor = name;
  r.values = {p0_dbm - 10.0 * exponent * std::log10(d) + s.noise * place_noise(name, at.x, at.y)};
  r.ref = "signal_dbm";
  return r;
}

std::array<double, 3> RoadWorld::nearest(double x, double y) const {
  std::array<double, 3> best{road_m.front()[0], road_m.front()[1], 0};
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < road_m.size(); ++i) {
    const auto& a = road_m[i];
    const auto& b = road_m[i + 1];
    const double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
    const double f =
        len2 > 0 ? std::clamp(((x - a[0]) * dx + (y - a[1]) * dy) / len2, 0.0, 1.0) : 0;
    const double px = a[0] + f * dx, py = a[1] + f * dy;
    const double dd = std::hypot(x - px, y - py);
    if (dd < best_d) best_d = dd, best = {px, py, std::atan2(dy, dx)};
  }
  return best;
}

fleet::Reading RoadWorld::sense(const std::string& name, const Vec3& at, double) const {
  const SensorSpec& s = sensor(name);
  const auto n = nearest(at.x, at.y);
  const double heading_deg = std::fmod(90.0 - n[2] * 180.0 / std::numbers::pi + 720.0, 360.0);
  fleet::Reading r;
  r.sensor = name;
  r.values = {n[0] + s.noise * place_noise(name + "/x", at.x, at.y),
              n[1] + s.noise * place_noise(name + "/y", at.x, at.y),
              heading_deg + s.noise_deg * place_noise(name + "/heading", at.x, at.y)};
  r.ref = "x_m,y_m,heading_deg";
  return r;
}

fleet::Reading SitesWorld::sense(const std::string& name, const Vec3& at, double) const {
  sensor(name);
  fleet::Reading r;
  r.sensor = name;
  r.values = {at.x, at.y};
  r.ref = "photo_x_m,photo_y_m";
  return r;
}

double RfFieldWorld::truth_dbm(double x, double y) const {
  double best = -1e9;
  for (const AccessPoint& a : access_points) {
    const double d = std::max(1.0, std::hypot(x - a.x_m, y - a.y_m));
    best = std::max(best, a.p0_dbm - 10.0 * a.exponent * std::log10(d));
  }
  // Random Fourier features of the RBF kernel exp(-d²/(2ℓ²)): w ~ N(0, 1/ℓ²), b ~ U(0, 2π),
  // shadow = σ √(2/M) Σ cos(w·p + b) has that covariance (Rahimi & Recht 2007).
  double shadow = 0;
  for (const auto& f : features) shadow += std::cos(f[0] * x + f[1] * y + f[2]);
  if (!features.empty())
    shadow *= shadowing_db * std::sqrt(2.0 / static_cast<double>(features.size()));
  return best + shadow;
}

fleet::Reading RfFieldWorld::sense(const std::string& name, const Vec3& at, double) const {
  const SensorSpec& s = sensor(name);
  fleet::Reading r;
  r.sensor = name;
  r.values = {truth_dbm(at.x, at.y) + s.noise * place_noise(name, at.x, at.y)};
  r.ref = "rssi_dbm";
  return r;
}

std::array<double, 2> TrackingWorld::walker_at(double t) const {
  // Integrated in 1 s steps (the path is smooth over seconds), the last step partial.
  double x = start_.x, y = start_.y;
  const int whole = static_cast<int>(std::floor(std::max(0.0, t)));
  auto heading = [&](double k) {
    double h = heading0;
    for (std::size_t i = 0; i < 3; ++i)
      h += turn_amp[i] * std::sin(turn_freq[i] * k + turn_phase[i]);
    return h;
  };
  // Beyond `area_radius_m` from the start the walker turns home (it walks about a field).
  auto step_heading = [&](int k) {
    const double h = heading(k);
    const double dx = x - start_.x, dy = y - start_.y;
    if (std::hypot(dx, dy) <= area_radius_m) return h;
    return std::atan2(-dy, -dx) + 0.5 * std::sin(h);
  };
  for (int k = 0; k < whole; ++k) {
    const double h = step_heading(k);
    x += walker_speed_m_s * std::cos(h);
    y += walker_speed_m_s * std::sin(h);
  }
  const double f = std::max(0.0, t) - whole;
  const double h = step_heading(whole);
  x += f * walker_speed_m_s * std::cos(h);
  y += f * walker_speed_m_s * std::sin(h);
  return {x, y};
}

fleet::Reading TrackingWorld::sense(const std::string& name, const Vec3& at, double t_s) const {
  sensor(name);
  const auto w = walker_at(t_s);
  fleet::Reading r;
  r.sensor = name;
  if (std::hypot(w[0] - at.x, w[1] - at.y) <= camera_range_m) r.values = {w[0], w[1]};
  r.ref = "walker_x_m,walker_y_m (empty: not in sight)";
  return r;
}

fleet::Reading StaticWorld::sense(const std::string& name, const Vec3& at, double) const {
  sensor(name);
  fleet::Reading r;
  r.sensor = name;
  r.values = {at.x, at.y};
  r.ref = "x_m,y_m";
  return r;
}

Vec3 SitesWorld::site(const std::string& name) const {
  for (const auto& [n, p] : sites)
    if (n == name) return p;
  throw fleet::ActionFailed("no site " + name);
}

namespace {

Vec3 xy(const YamlMap& m, const char* key, Vec3 fallback) {
  if (!m.has(key)) return fallback;
  const YamlMap p = m.map(key);
  p.allow({"x_m", "y_m"});
  return {p.number("x_m", 0, -1e5, 1e5), p.number("y_m", 0, -1e5, 1e5), 0};
}

void read_sensors(const YamlMap& root, BaseWorld& w, const std::vector<SensorSpec>& defaults) {
  w.sensors = defaults;
  if (!root.has("sensors")) return;
  const YamlMap s = root.map("sensors");
  for (const auto& kv : s.node()) {
    const std::string name = kv.first.as<std::string>();
    auto it = std::find_if(w.sensors.begin(), w.sensors.end(),
                           [&](const SensorSpec& x) { return x.name == name; });
    if (it == w.sensors.end())
      throw InputError(s.where(name.c_str()) + ": a " + w.kind_ + " world has no sensor \"" + name +
                       "\"");
    const YamlMap m = s.map(name.c_str());
    m.allow({"time_s", "noise", "noise_db", "noise_m", "noise_deg"});
    it->time_s = m.number("time_s", it->time_s, 0, 3600, true);
    it->noise = m.number("noise", it->noise, 0, 1e3);
    it->noise = m.number("noise_db", it->noise, 0, 1e3);
    it->noise = m.number("noise_m", it->noise, 0, 1e3);
    it->noise_deg = m.number("noise_deg", it->noise_deg, 0, 180);
  }
}

// A smooth random road: 200 m from the start, heading drifting as a sum of three sines.
std::vector<std::array<double, 2>> random_road(std::uint64_t seed, Vec3 start) {
  vehicle::SplitMix64 rng = vehicle::SplitMix64::stream(seed, "road");
  const double heading0 = rng.uniform(0, 2 * std::numbers::pi);
  std::array<double, 3> amp{}, freq{}, phase{};
  for (int i = 0; i < 3; ++i) {
    amp[static_cast<std::size_t>(i)] = rng.uniform(0.05, 0.25);
    freq[static_cast<std::size_t>(i)] = rng.uniform(0.005, 0.03);
    phase[static_cast<std::size_t>(i)] = rng.uniform(0, 2 * std::numbers::pi);
  }
  std::vector<std::array<double, 2>> out{{start.x, start.y}};
  double x = start.x, y = start.y;
  for (int i = 1; i <= 200; ++i) {
    double h = heading0;
    for (std::size_t k = 0; k < 3; ++k) h += amp[k] * std::sin(freq[k] * i + phase[k]);
    x += std::cos(h);
    y += std::sin(h);
    out.push_back({x, y});
  }
  return out;
}

void read_static_tasks(const YAML::Node& doc, const YamlMap& root, const std::string& source,
                       StaticWorld& w) {
  const YAML::Node list = doc["tasks"];
  if (!list || !list.IsSequence() || list.size() == 0)
    throw InputError(root.where("tasks") + ": a static world lists its tasks under 'tasks:'");
  if (list.size() > 10000) throw InputError(root.where("tasks") + ": more than 10,000 tasks");
  std::map<std::string, std::size_t> index;
  std::vector<std::vector<std::string>> after_names;
  std::vector<std::string> after_where;
  // Sensors: those listed, else a 2 s default for any sensor a task names.
  std::set<std::string> named;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string place = "tasks[" + std::to_string(i) + "]";
    if (!list[i].IsMap())
      throw InputError(source + ": " + base::yaml_line(list[i]) + ": " + place +
                       " is not a mapping");
    const YamlMap m(list[i], source, place);
    m.allow({"name", "kind", "same_drone", "interruptible", "after", "actions"});
    StaticWorld::Task t;
    t.name = m.text("name", "task-" + std::to_string(i + 1));
    t.kind = m.text("kind", t.name);
    t.flags.same_drone = m.flag("same_drone", false);
    t.flags.interruptible = m.flag("interruptible", true);
    if (!index.emplace(t.name, i).second)
      throw InputError(m.where("name") + ": the task name \"" + t.name + "\" is given twice");
    std::vector<std::string> after;
    if (const YAML::Node a = list[i]["after"]) {
      if (!a.IsSequence()) throw InputError(m.where("after") + ": a list of task names");
      for (const auto& n : a) after.push_back(n.as<std::string>());
    }
    after_names.push_back(after);
    after_where.push_back(m.where("after"));
    const YAML::Node acts = list[i]["actions"];
    if (!acts || !acts.IsSequence() || acts.size() == 0)
      throw InputError(m.where("actions") + ": a task needs a list of actions");
    for (std::size_t k = 0; k < acts.size(); ++k) {
      const std::string ap = place + ".actions[" + std::to_string(k) + "]";
      if (!acts[k].IsMap() || acts[k].size() != 1)
        throw InputError(source + ": " + base::yaml_line(acts[k]) + ": " + ap +
                         " is one of {fly_to: {x_m, y_m, alt_m}}, {sense: SENSOR}, {hover: S}, "
                         "{custom: {name, s}}");
      const YamlMap am(acts[k], source, ap);
      StaticWorld::Step step;
      if (am.has("fly_to")) {
        const YamlMap p = am.map("fly_to");
        p.allow({"x_m", "y_m", "alt_m"});
        step.type = 0;
        step.to = {p.number("x_m", 0, -1e5, 1e5), p.number("y_m", 0, -1e5, 1e5),
                   p.number("alt_m", 0, 0, 500)};
      } else if (am.has("sense")) {
        step.type = 1;
        step.name = am.text("sense", "");
        if (step.name.empty()) throw InputError(am.where("sense") + ": name the sensor");
        named.insert(step.name);
      } else if (am.has("hover")) {
        step.type = 2;
        step.seconds = am.number("hover", 0, 0, 86400);
      } else if (am.has("custom")) {
        const YamlMap c = am.map("custom");
        c.allow({"name", "s"});
        step.type = 3;
        step.name = c.text("name", "custom");
        step.seconds = c.number("s", 0, 0, 86400);
      } else {
        am.allow({"fly_to", "sense", "hover", "custom"});
      }
      t.steps.push_back(step);
    }
    w.tasks.push_back(std::move(t));
  }
  for (std::size_t i = 0; i < w.tasks.size(); ++i)
    for (const std::string& n : after_names[i]) {
      const auto it = index.find(n);
      if (it == index.end()) throw InputError(after_where[i] + ": no task named \"" + n + "\"");
      if (it->second == i) throw InputError(after_where[i] + ": a task cannot come after itself");
      w.tasks[i].after.push_back(it->second);
    }
  // No cycle: a topological order must exist (Kahn).
  std::vector<int> indegree(w.tasks.size(), 0);
  for (std::size_t i = 0; i < w.tasks.size(); ++i)
    indegree[i] = static_cast<int>(w.tasks[i].after.size());
  std::vector<std::size_t> ready;
  for (std::size_t i = 0; i < indegree.size(); ++i)
    if (indegree[i] == 0) ready.push_back(i);
  std::size_t seen = 0;
  while (!ready.empty()) {
    const std::size_t i = ready.back();
    ready.pop_back();
    ++seen;
    for (std::size_t j = 0; j < w.tasks.size(); ++j)
      for (std::size_t a : w.tasks[j].after)
        if (a == i && --indegree[j] == 0) ready.push_back(j);
  }
  if (seen != w.tasks.size())
    throw InputError(root.where("tasks") + ": the tasks' 'after' lists form a cycle");
  for (const std::string& n : named)
    if (std::none_of(w.sensors.begin(), w.sensors.end(),
                     [&](const SensorSpec& x) { return x.name == n; }))
      w.sensors.push_back({n, 2.0, 0.0, 0});
}

}  // namespace

namespace {

// The world of `kind` with its own scalar keys read (and every key of the file checked).
std::unique_ptr<BaseWorld> world_of_kind(const YamlMap& root, const std::string& kind) {
  if (kind == "hotspot") {
    root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "source", "p0_dbm",
                "exponent", "steps", "side_m", "step_m"});
    auto h = std::make_unique<HotspotWorld>();
    h->p0_dbm = root.number("p0_dbm", -30, -200, 100);
    h->exponent = root.number("exponent", 2.0, 0, 10, true);
    h->steps = static_cast<int>(root.number("steps", 10, 1, 10000));
    h->side_m = root.number("side_m", 10, 0, 1e4, true);
    h->step_m = root.number("step_m", 5, 0, 1e4, true);
    return h;
  }
  if (kind == "road") {
    root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "road", "steps", "step_m"});
    auto r = std::make_unique<RoadWorld>();
    r->steps = static_cast<int>(root.number("steps", 25, 1, 10000));
    r->step_m = root.number("step_m", 6, 0, 1e4, true);
    return r;
  }
  if (kind == "sites") {
    root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "sites", "area_m",
                "handling_s", "delivery_interruptible"});
    auto s = std::make_unique<SitesWorld>();
    s->handling_s = root.number("handling_s", 5, 0, 3600);
    s->delivery_interruptible = root.flag("delivery_interruptible", true);
    return s;
  }
  if (kind == "rf_field") {
    root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "access_points", "shadowing",
                "cell_m", "gp", "cancel_below_db"});
    auto f = std::make_unique<RfFieldWorld>();
    f->cell_m = root.number("cell_m", 5, 0.5, 1000);
    f->cancel_below_db = root.number("cancel_below_db", 3, 0, 100);
    const YamlMap sh = root.map("shadowing");
    sh.allow({"sigma_db", "correlation_m"});
    f->shadowing_db = sh.number("sigma_db", 4, 0, 50);
    f->correlation_m = sh.number("correlation_m", 15, 0.1, 1e4, true);
    const YamlMap gp = root.map("gp");
    gp.allow({"length_m", "sigma_f", "sigma_n_db"});
    f->gp_length_m = gp.number("length_m", 12, 0.1, 1e4, true);
    f->gp_sigma_f = gp.number("sigma_f", 6, 0, 100, true);
    f->gp_sigma_n_db = gp.number("sigma_n_db", 2, 0, 100, true);
    return f;
  }
  if (kind == "tracking") {
    root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "walker_speed_m_s",
                "camera_range_m", "duration_s", "area_radius_m"});
    auto t = std::make_unique<TrackingWorld>();
    t->walker_speed_m_s = root.number("walker_speed_m_s", 1.4, 0, 50);
    t->camera_range_m = root.number("camera_range_m", 15, 0, 1e4, true);
    t->duration_s = root.number("duration_s", 300, 1, 86400);
    t->area_radius_m = root.number("area_radius_m", 60, 1, 1e4);
    return t;
  }
  if (kind == "static") {
    root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "tasks"});
    return std::make_unique<StaticWorld>();
  }
  throw InputError(root.where("kind") + ": unknown world kind \"" + kind +
                   "\"; the kinds are hotspot, road, rf_field, sites, tracking and static");
}

// What every world has: seed (or the one given), origin, start, fence.
void read_common(const YamlMap& root, BaseWorld& w, std::optional<std::uint64_t> seed) {
  w.seed =
      seed ? *seed : static_cast<std::uint64_t>(root.number("seed", 1, 0, 9.007199254740992e15));
  if (root.has("origin")) {
    const YamlMap o = root.map("origin");
    o.allow({"lat", "lon", "alt"});
    w.origin = {o.number("lat", 0, -90, 90), o.number("lon", 0, -180, 180),
                o.number("alt", 0, -500, 9000)};
    w.has_origin = true;
  }
  w.start_ = xy(root, "start", {0, 0, 0});
  if (root.has("fence")) {
    const YamlMap f = root.map("fence");
    f.allow({"width_m", "height_m"});
    const double hw = f.number("width_m", 100, 0, 1e5, true) / 2;
    const double hh = f.number("height_m", 100, 0, 1e5, true) / 2;
    w.fence_ = {{-hw, -hh}, {hw, -hh}, {hw, hh}, {-hw, hh}};
  }
}

// A road as given ([x_m, y_m] points) or a random smooth one.
void read_road(const YAML::Node& doc, const YamlMap& root, const std::string& source,
               RoadWorld& r) {
  read_sensors(root, r, {{"road_camera", 1.0, 0.5, 3.0}});
  if (!root.has("road")) {
    r.road_m = random_road(r.seed, r.start_);
    return;
  }
  const YAML::Node pts = doc["road"];
  if (!pts.IsSequence() || pts.size() < 2)
    throw InputError(root.where("road") + ": a road is a list of at least two [x_m, y_m]");
  for (const auto& p : pts) {
    if (!p.IsSequence() || p.size() != 2)
      throw InputError(source + ": " + base::yaml_line(p) + ": a road point is [x_m, y_m]");
    const double px = p[0].as<double>(), py = p[1].as<double>();
    if (!std::isfinite(px) || !std::isfinite(py) || std::abs(px) > 1e5 || std::abs(py) > 1e5)
      throw InputError(source + ": " + base::yaml_line(p) +
                       ": a road point must be finite and within 100 km");
    r.road_m.push_back({px, py});
  }
}

// The field's extent and cells (at most 600: the app's GP refits on every reading, O(n³)), its
// access points (given or two random), the shadowing's random features.
void read_rf_field(const YAML::Node& doc, const YamlMap& root, const std::string& source,
                   RfFieldWorld& f, vehicle::SplitMix64& rng) {
  read_sensors(root, f, {{"rssi", 2.0, 2.0, 0}});
  if (f.fence_.empty()) f.fence_ = {{0, 0}, {50, 0}, {50, 70}, {0, 70}};
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (const auto& p : f.fence_)
    x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]),
    y1 = std::max(y1, p[1]);
  f.width_m = x1 - x0;
  f.height_m = y1 - y0;
  const double cells =
      std::floor(f.width_m / f.cell_m + 1e-9) * std::floor(f.height_m / f.cell_m + 1e-9);
  if (cells > 600)
    throw InputError(root.where("cell_m") + ": more than 600 cells (" +
                     std::to_string(static_cast<long long>(cells)) +
                     "); use larger cells or a smaller fence");
  if (root.has("access_points")) {
    const YAML::Node aps = doc["access_points"];
    if (!aps.IsSequence() || aps.size() == 0)
      throw InputError(root.where("access_points") + ": a list of {x_m, y_m, p0_dbm, exponent}");
    for (std::size_t i = 0; i < aps.size(); ++i) {
      const YamlMap a(aps[i], source, "access_points[" + std::to_string(i) + "]");
      a.allow({"x_m", "y_m", "p0_dbm", "exponent"});
      f.access_points.push_back({a.number("x_m", 0, -1e5, 1e5), a.number("y_m", 0, -1e5, 1e5),
                                 a.number("p0_dbm", -30, -200, 100),
                                 a.number("exponent", 2.5, 0, 10, true)});
    }
  } else {
    for (int i = 0; i < 2; ++i)
      f.access_points.push_back({rng.uniform(x0, x1), rng.uniform(y0, y1), -30, 2.5});
  }
  auto frng = vehicle::SplitMix64::stream(f.seed, "shadowing");
  for (int i = 0; i < 64; ++i)
    f.features.push_back({frng.normal() / f.correlation_m, frng.normal() / f.correlation_m,
                          frng.uniform(0, 2 * std::numbers::pi)});
  if (!root.has("start")) f.start_ = {x0, y0, 0};
}

// Sites A..F: as given, else A and F at the area's ends and the rest random in it.
void read_sites(const YamlMap& root, SitesWorld& s, vehicle::SplitMix64& rng) {
  read_sensors(root, s, {{"camera", 2.0, 0.0, 0}});
  const double area = root.number("area_m", 200, 0, 1e5, true);
  std::map<std::string, Vec3> given;
  if (root.has("sites")) {
    const YamlMap m = root.map("sites");
    m.allow({"A", "B", "C", "D", "E", "F"});
    for (const char* n : {"A", "B", "C", "D", "E", "F"})
      if (m.has(n)) given[n] = xy(m, n, {});
  }
  for (const char* n : {"A", "B", "C", "D", "E", "F"}) {
    Vec3 p;
    if (auto it = given.find(n); it != given.end()) {
      p = it->second;
    } else if (std::string(n) == "A") {
      p = {-area / 2, 0, 0};
    } else if (std::string(n) == "F") {
      p = {area / 2, 0, 0};
    } else {
      p = {rng.uniform(-area / 2, area / 2), rng.uniform(-area / 2, area / 2), 0};
    }
    s.sites.push_back({n, p});
  }
}

// The parts of each kind that need the common ones (start, fence, seed) or the random stream.
void read_kind_parts(const YAML::Node& doc, const YamlMap& root, const std::string& source,
                     BaseWorld& w) {
  vehicle::SplitMix64 rng = vehicle::SplitMix64::stream(w.seed, "world");
  if (auto* h = dynamic_cast<HotspotWorld*>(&w)) {
    read_sensors(root, w, {{"signal", 2.0, 1.0, 0}});
    const double bearing = rng.uniform(0, 2 * std::numbers::pi);
    h->source_m = xy(root, "source",
                     {w.start_.x + 60 * std::cos(bearing), w.start_.y + 60 * std::sin(bearing), 0});
  } else if (auto* r = dynamic_cast<RoadWorld*>(&w)) {
    read_road(doc, root, source, *r);
  } else if (auto* f = dynamic_cast<RfFieldWorld*>(&w)) {
    read_rf_field(doc, root, source, *f, rng);
  } else if (auto* t = dynamic_cast<TrackingWorld*>(&w)) {
    read_sensors(root, w, {{"camera", 0.5, 0.0, 0}});
    auto trng = vehicle::SplitMix64::stream(w.seed, "walker");
    t->heading0 = trng.uniform(0, 2 * std::numbers::pi);
    for (std::size_t i = 0; i < 3; ++i) {
      t->turn_amp[i] = trng.uniform(0.1, 0.5);
      t->turn_freq[i] = trng.uniform(0.01, 0.05);
      t->turn_phase[i] = trng.uniform(0, 2 * std::numbers::pi);
    }
  } else if (auto* st = dynamic_cast<StaticWorld*>(&w)) {
    std::vector<SensorSpec> listed;  // a static world's sensors are whatever it lists
    if (const YAML::Node sn = doc["sensors"]; sn && sn.IsMap())
      for (const auto& kv : sn) listed.push_back({kv.first.as<std::string>(), 2.0, 0.0, 0});
    read_sensors(root, w, listed);
    read_static_tasks(doc, root, source, *st);
  } else if (auto* s = dynamic_cast<SitesWorld*>(&w)) {
    read_sites(root, *s, rng);
  }
}

}  // namespace

std::unique_ptr<BaseWorld> parse_world(const std::string& text, const std::string& source,
                                       std::optional<std::uint64_t> seed) {
  return base::yaml_guard(source, [&]() -> std::unique_ptr<BaseWorld> {
    const YAML::Node doc = base::load_yaml(text, source);
    if (!doc.IsMap()) throw InputError(source + ": a world file is a YAML mapping (kind: ...)");
    const YamlMap root(doc, source, "");
    const std::string kind = root.text("kind", "");
    std::unique_ptr<BaseWorld> w = world_of_kind(root, kind);
    w->kind_ = kind;
    read_common(root, *w, seed);
    read_kind_parts(doc, root, source, *w);
    return w;
  });
}

std::unique_ptr<BaseWorld> read_world(const std::string& path) {
  return parse_world(base::read_text_file(path, "world file"), path);
}

const std::vector<std::string>& world_kinds() {
  static const std::vector<std::string> kinds{"hotspot", "road",   "rf_field",
                                              "sites",   "static", "tracking"};
  return kinds;
}

}  // namespace swath::worlds

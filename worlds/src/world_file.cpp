#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

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

}  // namespace

std::unique_ptr<BaseWorld> parse_world(const std::string& text, const std::string& source,
                                       std::optional<std::uint64_t> seed) {
  return base::yaml_guard(source, [&]() -> std::unique_ptr<BaseWorld> {
    const YAML::Node doc = base::load_yaml(text, source);
    if (!doc.IsMap()) throw InputError(source + ": a world file is a YAML mapping (kind: ...)");
    const YamlMap root(doc, source, "");
    const std::string kind = root.text("kind", "");
    std::unique_ptr<BaseWorld> w;
    if (kind == "hotspot") {
      root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "source", "p0_dbm",
                  "exponent", "steps", "side_m", "step_m"});
      auto h = std::make_unique<HotspotWorld>();
      h->p0_dbm = root.number("p0_dbm", -30, -200, 100);
      h->exponent = root.number("exponent", 2.0, 0, 10, true);
      h->steps = static_cast<int>(root.number("steps", 10, 1, 10000));
      h->side_m = root.number("side_m", 10, 0, 1e4, true);
      h->step_m = root.number("step_m", 5, 0, 1e4, true);
      w = std::move(h);
    } else if (kind == "road") {
      root.allow(
          {"kind", "origin", "seed", "fence", "start", "sensors", "road", "steps", "step_m"});
      auto r = std::make_unique<RoadWorld>();
      r->steps = static_cast<int>(root.number("steps", 25, 1, 10000));
      r->step_m = root.number("step_m", 6, 0, 1e4, true);
      w = std::move(r);
    } else if (kind == "sites") {
      root.allow({"kind", "origin", "seed", "fence", "start", "sensors", "sites", "area_m",
                  "handling_s", "delivery_interruptible"});
      auto s = std::make_unique<SitesWorld>();
      s->handling_s = root.number("handling_s", 5, 0, 3600);
      s->delivery_interruptible = root.flag("delivery_interruptible", true);
      w = std::move(s);
    } else {
      throw InputError(root.where("kind") + ": unknown world kind \"" + kind +
                       "\"; the kinds are hotspot, road and sites");
    }
    w->kind_ = kind;
    w->seed =
        seed ? *seed : static_cast<std::uint64_t>(root.number("seed", 1, 0, 9.007199254740992e15));
    if (root.has("origin")) {
      const YamlMap o = root.map("origin");
      o.allow({"lat", "lon", "alt"});
      w->origin = {o.number("lat", 0, -90, 90), o.number("lon", 0, -180, 180),
                   o.number("alt", 0, -500, 9000)};
    }
    w->start_ = xy(root, "start", {0, 0, 0});
    if (root.has("fence")) {
      const YamlMap f = root.map("fence");
      f.allow({"width_m", "height_m"});
      const double hw = f.number("width_m", 100, 0, 1e5, true) / 2;
      const double hh = f.number("height_m", 100, 0, 1e5, true) / 2;
      w->fence_ = {{-hw, -hh}, {hw, -hh}, {hw, hh}, {-hw, hh}};
    }
    vehicle::SplitMix64 rng = vehicle::SplitMix64::stream(w->seed, "world");
    if (auto* h = dynamic_cast<HotspotWorld*>(w.get())) {
      read_sensors(root, *w, {{"signal", 2.0, 1.0, 0}});
      const double bearing = rng.uniform(0, 2 * std::numbers::pi);
      h->source_m =
          xy(root, "source",
             {w->start_.x + 60 * std::cos(bearing), w->start_.y + 60 * std::sin(bearing), 0});
    } else if (auto* r = dynamic_cast<RoadWorld*>(w.get())) {
      read_sensors(root, *w, {{"road_camera", 1.0, 0.5, 3.0}});
      if (root.has("road")) {
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
          r->road_m.push_back({px, py});
        }
      } else {
        r->road_m = random_road(w->seed, w->start_);
      }
    } else if (auto* s = dynamic_cast<SitesWorld*>(w.get())) {
      read_sensors(root, *w, {{"camera", 2.0, 0.0, 0}});
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
        s->sites.push_back({n, p});
      }
    }
    return w;
  });
}

std::unique_ptr<BaseWorld> read_world(const std::string& path) {
  return parse_world(base::read_text_file(path, "world file"), path);
}

}  // namespace swath::worlds

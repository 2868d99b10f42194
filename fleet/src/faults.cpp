#include "swath/fleet/faults.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"

namespace swath::fleet {

using base::InputError;
using base::YamlMap;

namespace {

FaultKind kind_of(const std::string& name, const std::string& where) {
  for (FaultKind k : {FaultKind::link_loss, FaultKind::battery_drop, FaultKind::motor_failure,
                      FaultKind::sensor_failure})
    if (name == fault_name(k)) return k;
  throw InputError(where + ": unknown fault kind \"" + name +
                   "\"; the kinds are link_loss, battery_drop, motor_failure, sensor_failure");
}

void sort_faults(std::vector<FaultEvent>& f) {
  std::stable_sort(f.begin(), f.end(), [](const FaultEvent& a, const FaultEvent& b) {
    return a.t_s != b.t_s ? a.t_s < b.t_s : a.drone < b.drone;
  });
}

}  // namespace

std::vector<FaultEvent> random_faults(std::uint64_t seed, double per_drone_per_hour,
                                      const std::vector<FaultKind>& kinds,
                                      const std::vector<std::string>& drones, double horizon_s,
                                      double duration_s) {
  std::vector<FaultEvent> out;
  if (!(per_drone_per_hour > 0) || kinds.empty()) return out;
  for (std::size_t d = 0; d < drones.size(); ++d) {
    auto rng = vehicle::SplitMix64::stream(seed, "faults/" + drones[d]);
    for (double t = rng.exponential(per_drone_per_hour / 3600.0); t < horizon_s;
         t += rng.exponential(per_drone_per_hour / 3600.0)) {
      FaultEvent f;
      f.t_s = t;
      f.drone = static_cast<int>(d);
      f.kind = kinds[static_cast<std::size_t>(rng.below(kinds.size()))];
      f.duration_s = duration_s;
      f.soc = rng.uniform(0.05, 0.5);
      out.push_back(f);
      if (out.size() > 100000) break;
    }
  }
  sort_faults(out);
  return out;
}

std::vector<FaultEvent> parse_faults(const std::string& text, const std::string& source,
                                     const std::vector<std::string>& drones, double horizon_s) {
  return base::yaml_guard(source, [&] {
    const YAML::Node doc = base::load_yaml(text, source);
    std::vector<FaultEvent> out;
    if (doc.IsMap()) {
      const YamlMap root(doc, source, "");
      root.allow({"random"});
      if (!root.has("random"))
        throw InputError(source + ": a faults file is a list of faults or {random: ...}");
      const YamlMap r = root.map("random");
      r.allow({"per_drone_per_hour", "kinds", "seed", "duration_s"});
      std::vector<FaultKind> kinds;
      const YAML::Node ks = r.node()["kinds"];
      if (ks) {
        if (!ks.IsSequence()) throw InputError(r.where("kinds") + ": a list of fault kinds");
        for (const auto& k : ks) kinds.push_back(kind_of(k.as<std::string>(), r.where("kinds")));
      } else {
        kinds = {FaultKind::link_loss, FaultKind::battery_drop, FaultKind::motor_failure,
                 FaultKind::sensor_failure};
      }
      const double rate = r.number("per_drone_per_hour", 1, 0, 3600);
      return random_faults(static_cast<std::uint64_t>(r.number("seed", 1, 0, 9.007199254740992e15)),
                           rate, kinds, drones, horizon_s,
                           r.number("duration_s", 10, 0, 86400, true));
    }
    if (!doc.IsSequence())
      throw InputError(source + ": a faults file is a list of faults or {random: ...}");
    for (std::size_t i = 0; i < doc.size(); ++i) {
      const std::string place = "faults[" + std::to_string(i) + "]";
      if (!doc[i].IsMap())
        throw InputError(source + ": " + base::yaml_line(doc[i]) + ": " + place +
                         " is not a mapping");
      const YamlMap m(doc[i], source, place);
      m.allow({"t_s", "drone", "kind", "duration_s", "soc"});
      FaultEvent f;
      if (!m.has("t_s")) throw InputError(m.where("kind") + ": a fault needs t_s");
      f.t_s = m.number("t_s", 0, 0, 604800);
      const std::string name = m.text("drone", "");
      const auto it = std::find(drones.begin(), drones.end(), name);
      if (it == drones.end()) {
        std::string known;
        for (const auto& d : drones) known += (known.empty() ? "" : ", ") + d;
        throw InputError(m.where("drone") + ": no drone \"" + name + "\" in the fleet (" + known +
                         ")");
      }
      f.drone = static_cast<int>(it - drones.begin());
      f.kind = kind_of(m.text("kind", ""), m.where("kind"));
      f.duration_s = m.number("duration_s", 10, 0, 86400, true);
      if (f.kind == FaultKind::battery_drop) {
        if (!m.has("soc"))
          throw InputError(m.where("kind") + ": a battery_drop needs soc, the charge it falls to");
        f.soc = m.number("soc", 0, 0, 1);
      }
      out.push_back(f);
    }
    sort_faults(out);
    return out;
  });
}

std::vector<FaultEvent> read_faults(const std::string& path, const std::vector<std::string>& drones,
                                    double horizon_s) {
  return parse_faults(base::read_text_file(path, "faults file"), path, drones, horizon_s);
}

}  // namespace swath::fleet

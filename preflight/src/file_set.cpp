// verify_files(): a written file set (a plan directory, or swath plan's output before writing),
// its drones, their twins and launch times; and the report's text and JSON.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::preflight {
namespace {

using base::fixed_text;
using Files = std::vector<std::pair<std::string, std::string>>;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string stem_of(const std::string& name, const std::string& tail) {
  return name.substr(0, name.size() - tail.size());
}

// What summary.json says of each file: its launch offset (absent: 0) and, for a sortie, the drone
// that flies it.
struct Launch {
  double offset_s = 0.0;
  std::string sorties_of;
};

std::map<std::string, Launch> launches(const Files& files) {
  std::map<std::string, Launch> out;
  for (const auto& [name, text] : files) {
    if (name != "summary.json" && !ends_with(name, "/summary.json")) continue;
    const nlohmann::json root = base::parse_json_document(text, name);
    const nlohmann::json* drones = base::json_find(root, "drones");
    if (drones == nullptr || !drones->is_array()) continue;
    for (const auto& d : *drones) {
      const nlohmann::json* file = base::json_find(d, "file");
      if (file == nullptr || !file->is_string()) continue;
      const nlohmann::json* offset = base::json_find(d, "launch_offset_s");
      Launch launch{offset && offset->is_number() ? offset->get<double>() : 0.0, ""};
      out[file->get<std::string>()] = launch;
      const nlohmann::json* sorties = base::json_find(d, "sorties");
      for (std::size_t k = 0; sorties && sorties->is_array() && k < sorties->size(); ++k) {
        const nlohmann::json* sortie_file = base::json_find((*sorties)[k], "file");
        if (sortie_file && sortie_file->is_string())
          out[sortie_file->get<std::string>()] = {launch.offset_s, file->get<std::string>()};
      }
    }
  }
  return out;
}

// The waypoints (NAV_WAYPOINT) of a mission with their altitude above home, for comparing twins.
struct Waypoint {
  geometry::GeoPoint at;
  double above_home_m;
  bool terrain;  ///< in the terrain frame: without a DEM its height above home is unknown
};

// Through the flight model's own conversion: a terrain-frame .plan item is its height above the
// DEM's ground there, plus that ground above home's, as its Litchi and DJI twins give it.
std::vector<Waypoint> waypoints(const missions::Mission& m, const geometry::Ground* ground) {
  const HeightConverter heights(m, ground);
  std::vector<Waypoint> out;
  for (const missions::Item& item : m.items)
    if (item.command == static_cast<int>(mavlink::Cmd::nav_waypoint))
      out.push_back({item.position, heights.above_home_m(item),
                     item.altitude_frame == missions::AltitudeFrame::terrain});
  return out;
}

// Heights in the terrain frame and above home compare only over the ground's heights.
bool heights_comparable(const Waypoint& a, const Waypoint& b, const geometry::Ground* ground) {
  return ground != nullptr || a.terrain == b.terrain;
}

// A twin agrees when it flies the .plan's waypoints, in order, at the same heights (to the
// writers' rounding); a Litchi or DJI file may add its last row at home (the landing). Returns
// how many heights could not be compared (terrain frame against above home, without a DEM).
std::size_t check_twin(const missions::Mission& plan, const missions::Mission& twin,
                       const geometry::Ground* ground, Report& report) {
  const std::vector<Waypoint> a = waypoints(plan, ground), b = waypoints(twin, ground);
  // Litchi and DJI files add their landing point at home as a last waypoint.
  const bool litchi = twin.format == "Litchi CSV" || twin.format == "DJI WPML";
  std::string problem;
  std::size_t k = 0, unknown_heights = 0;
  for (; k < std::min(a.size(), b.size()) && problem.empty(); ++k) {
    const double apart_m = geometry::geodesic_distance_m(a[k].at, b[k].at);
    if (apart_m > 0.01)
      problem = "waypoint " + std::to_string(k + 1) + " lies " + fixed_text(apart_m, 2) +
                " m from the .plan's";
    else if (!heights_comparable(a[k], b[k], ground))
      ++unknown_heights;
    else if (std::abs(a[k].above_home_m - b[k].above_home_m) > 0.01)
      problem = "waypoint " + std::to_string(k + 1) + " flies at " +
                fixed_text(b[k].above_home_m, 2) + " m above home, the .plan's at " +
                fixed_text(a[k].above_home_m, 2) + " m";
  }
  if (problem.empty() && a.size() != b.size() && !(litchi && b.size() == a.size() + 1))
    problem = std::to_string(b.size()) + " waypoints, the .plan " + std::to_string(a.size());
  if (problem.empty()) return unknown_heights;
  report.violations.push_back({"agreement", twin.source, std::nullopt, 0.0,
                               twin.source + " differs from " + plan.source + ": " + problem});
  return unknown_heights;
}

// The terrain frame's heights above home are the DEM's: without one they are not compared.
std::string unknown_heights_text(std::size_t unknown_heights) {
  if (unknown_heights == 0) return "";
  return " (" + std::to_string(unknown_heights) +
         " heights in the terrain frame not compared: no DEM, --terrain)";
}

bool is_fence_file(const std::string& name) {
  return name == "fence.waypoints" || name == "rally.waypoints" ||
         ends_with(name, "/fence.waypoints") || ends_with(name, "/rally.waypoints");
}

}  // namespace

Report verify_files(const Files& files, const CheckOptions& options) {
  // Each name's text where the set holds it (the first of a name given twice): not a copy of
  // every file (a plan's photos.geojson is megabytes).
  std::map<std::string, const std::string*> by_name;
  for (const auto& [name, text] : files) by_name.try_emplace(name, &text);
  std::vector<std::string> drones;  // file names, in the set's order
  bool any_plan = false;
  for (const auto& [name, text] : files)
    any_plan = any_plan || (ends_with(name, ".plan") && !ends_with(name, "-survey.plan"));
  for (const auto& [name, text] : files) {
    const bool plan = ends_with(name, ".plan") && !ends_with(name, "-survey.plan");
    const bool other = ends_with(name, ".waypoints")
                           ? !is_fence_file(name)
                           : ends_with(name, "-litchi.csv") || ends_with(name, ".kmz");
    if (any_plan ? plan : other) drones.push_back(name);
  }
  if (drones.empty())
    throw base::InputError(
        "no mission file among the files given (.plan, .waypoints, -litchi.csv or .kmz)");
  const auto by_file = launches(files);
  std::vector<DroneFile> set;
  std::vector<std::pair<std::size_t, missions::Mission>> twins;
  for (const std::string& name : drones) {
    DroneFile d{missions::parse_mission(*by_name.at(name), name), 0.0, ""};
    for (const auto& [fence_name, text] : files)
      if (is_fence_file(fence_name)) missions::add_wpl_fences(d.mission, text, fence_name);
    const std::string base_name = name.substr(name.find_last_of('/') + 1);
    const std::string stem = stem_of(base_name, base_name.substr(base_name.find_last_of('.')));
    if (const auto it = by_file.find(stem); it != by_file.end()) {
      d.launch_offset_s = it->second.offset_s;
      d.sorties_of = it->second.sorties_of;
    }
    if (ends_with(name, ".plan")) {
      const std::string dir_stem = stem_of(name, ".plan");
      for (const char* tail : {".waypoints", "-litchi.csv", "-survey.plan", ".kmz"})
        if (const auto t = by_name.find(dir_stem + tail); t != by_name.end())
          twins.push_back({set.size(), missions::parse_mission(*t->second, t->first)});
    }
    set.push_back(std::move(d));
  }
  Report report = verify(set, options);
  std::size_t unknown_heights = 0;
  for (const auto& [index, twin] : twins) {
    report.files.push_back(twin.source);
    unknown_heights += check_twin(set[index].mission, twin, options.ground.get(), report);
  }
  std::size_t disagree = 0;
  for (const Violation& v : report.violations) disagree += v.check == "agreement";
  if (!twins.empty())
    report.figures.push_back({"agreement", true, static_cast<double>(disagree),
                              std::to_string(twins.size() - disagree) + " of " +
                                  std::to_string(twins.size()) +
                                  " twin files (.waypoints, -litchi.csv, -survey.plan, .kmz) fly "
                                  "their .plan's waypoints" +
                                  unknown_heights_text(unknown_heights)});
  return report;
}

std::string report_text(const Report& report) {
  std::string out = "swath verify: " + std::to_string(report.files.size()) + " file(s):";
  for (const std::string& f : report.files) out += " " + f;
  out += "\n";
  for (const Figure& f : report.figures) {
    std::string check = f.check;
    check.resize(std::max<std::size_t>(check.size(), 11), ' ');
    out += "  " + check + (f.ran ? "" : "not checked: ") + f.text + "\n";
  }
  for (const Violation& v : report.violations) {
    out += "  VIOLATION " + v.check + ": " + v.text;
    if (v.at)
      out += " at " + fixed_text(v.at->lat_deg, 7) + ", " + fixed_text(v.at->lon_deg, 7) +
             " (lat, lon)";
    out += "\n";
  }
  out += report.ok()
             ? "  result     every check holds\n"
             : "  result     " + std::to_string(report.violations.size()) + " violation(s)\n";
  return out;
}

std::string report_json(const Report& report) {
  nlohmann::ordered_json j;
  j["ok"] = report.ok();
  j["files"] = report.files;
  nlohmann::ordered_json checks = nlohmann::ordered_json::array();
  for (const Figure& f : report.figures)
    checks.push_back({{"check", f.check},
                      {"ran", f.ran},
                      {"value", f.value && std::isfinite(*f.value)
                                    ? nlohmann::ordered_json(base::round_to(*f.value, 3))
                                    : nlohmann::ordered_json()},
                      {"text", f.text}});
  j["checks"] = checks;
  nlohmann::ordered_json violations = nlohmann::ordered_json::array();
  for (const Violation& v : report.violations) {
    nlohmann::ordered_json o{{"check", v.check},
                             {"place", v.place},
                             {"amount", base::round_to(v.amount, 3)},
                             {"text", v.text}};
    o["lat_deg"] =
        v.at ? nlohmann::ordered_json(base::round_to(v.at->lat_deg, 9)) : nlohmann::ordered_json();
    o["lon_deg"] =
        v.at ? nlohmann::ordered_json(base::round_to(v.at->lon_deg, 9)) : nlohmann::ordered_json();
    violations.push_back(o);
  }
  j["violations"] = violations;
  return base::json_text(j, 2) + "\n";
}

}  // namespace swath::preflight

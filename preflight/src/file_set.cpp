// verify_files(): a written file set (a plan directory, or swath plan's output before writing),
// its drones, their twins and launch times; and the report's text and JSON.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

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

// What summary.json says of each file: its launch offset (absent: 0; a sortie's own, else its
// drone's) and, for a sortie, the drone that flies it.
struct Launch {
  double offset_s = 0.0;
  std::string sorties_of;
  std::size_t sortie = 0;  ///< from 1, in the summary's order
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
        const nlohmann::json* own = base::json_find((*sorties)[k], "launch_offset_s");
        if (sortie_file && sortie_file->is_string())
          out[sortie_file->get<std::string>()] = {
              own && own->is_number() ? own->get<double>() : launch.offset_s,
              file->get<std::string>(), k + 1};
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
  const missions::Mission* file;
  std::size_t number;  ///< in its file, from 1
};

// Through the flight model's own conversion: a terrain-frame .plan item is its height above the
// DEM's ground there, plus that ground above home's, as its Litchi and DJI twins give it.
std::vector<Waypoint> waypoints(const missions::Mission& m, const geometry::Ground* ground) {
  const HeightConverter heights(m, ground);
  std::vector<Waypoint> out;
  for (const missions::Item& item : m.items)
    if (item.command == static_cast<int>(mavlink::Cmd::nav_waypoint))
      out.push_back({item.position, heights.above_home_m(item),
                     item.altitude_frame == missions::AltitudeFrame::terrain, &m, out.size() + 1});
  return out;
}

bool same_point(const Waypoint& a, const Waypoint& b) {
  return geometry::geodesic_distance_m(a.at, b.at) <= 0.01 &&
         std::abs(a.above_home_m - b.above_home_m) <= 0.01;
}

// How many waypoints the end of `out` and the start of `next` share mirrored: a part of a split
// Litchi flight that cannot fly home straight from where it stops carries a way home round the
// zones, and the next part the same way back out reversed, up to the point it resumes at, which
// both hold. 0: none; 1: the next part starts where the one before ended.
std::size_t mirrored(const std::vector<Waypoint>& out, const std::vector<Waypoint>& next) {
  std::size_t k = 0;
  while (k < out.size() && k < next.size() && same_point(out[out.size() - 1 - k], next[k])) ++k;
  return k;
}

// A twin's waypoints: the parts of a split Litchi flight joined, each part after the first
// starting where the one before ended (that waypoint once), the ways home and back out between
// them left out (they are flown and checked as the parts' own legs, not the .plan's).
std::vector<Waypoint> joined_waypoints(const std::vector<missions::Mission>& parts,
                                       const geometry::Ground* ground) {
  std::vector<Waypoint> out;
  for (const missions::Mission& part : parts) {
    const std::vector<Waypoint> w = waypoints(part, ground);
    const std::size_t shared = mirrored(out, w);
    if (shared > 1) out.resize(out.size() - (shared - 1));
    out.insert(out.end(), w.begin() + static_cast<std::ptrdiff_t>(shared), w.end());
  }
  return out;
}

// A .plan's twin: one file, or the parts of a split Litchi flight.
struct Twin {
  std::size_t drone;  ///< the .plan's index among the drones
  std::vector<missions::Mission> parts;
};

std::string twin_name(const Twin& twin) {
  const auto& parts = twin.parts;
  return parts.size() == 1 ? parts[0].source + " differs"
                           : parts.front().source + " to " + parts.back().source + " differ";
}

// Where a waypoint of the twin is: the .plan's number too when it lies in a later part.
std::string waypoint_name(const Waypoint& w, std::size_t plan_number) {
  const std::string own = "waypoint " + std::to_string(w.number);
  return w.number == plan_number ? own : own + " (the .plan's " + std::to_string(plan_number) + ")";
}

// Heights in the terrain frame and above home compare only over the ground's heights.
bool heights_comparable(const Waypoint& a, const Waypoint& b, const geometry::Ground* ground) {
  return ground != nullptr || a.terrain == b.terrain;
}

// DJI's waypoint spacing as the Litchi and DJI writers keep it (docs/swath-plan.md): a .plan
// waypoint closer than 0.5 m to one flown is merged into it, a .plan leg longer than 2,000 m is
// flown through points on it. Allowed here with the writers' rounding.
// The writers merge below 0.51 m (common.hpp kDjiMergeBelow_m); 1 cm more for their rounding.
constexpr double kMergedWithin_m = 0.51 + 0.01;
constexpr double kOnLeg_m = 0.05;

double apart_3d_m(const Waypoint& a, const Waypoint& b) {
  return std::hypot(geometry::geodesic_distance_m(a.at, b.at), a.above_home_m - b.above_home_m);
}

// Whether w lies on the .plan's leg from a to b (strictly between its ends, at its height there):
// a point a Litchi or DJI file splits a long leg with.
bool on_leg(const Waypoint& w, const Waypoint& a, const Waypoint& b) {
  const geometry::LocalFrame frame(a.at);
  const geometry::Point2 p = frame.to_local(w.at), q = frame.to_local(b.at);
  const double length_m = std::hypot(q.x, q.y);
  if (!(length_m > 0)) return false;
  const double t = (p.x * q.x + p.y * q.y) / (length_m * length_m);
  const double off_m = std::abs(p.x * q.y - p.y * q.x) / length_m;
  const double height_m = a.above_home_m + (b.above_home_m - a.above_home_m) * t;
  return t > 0 && t < 1 && off_m <= kOnLeg_m && std::abs(w.above_home_m - height_m) <= 0.01;
}

// The twin's waypoints b set against the .plan's a, in order: each pair, or for Litchi and DJI
// files a .plan waypoint merged into a neighbour flown (skipped), a point on a long .plan leg or a
// first point above home (passed). Stops at the first pair that is neither: k and j are the indices
// reached there.
struct Matching {
  std::size_t k = 0, j = 0;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  ///< (a's, b's) at the same place
};

Matching matched(const std::vector<Waypoint>& a, const std::vector<Waypoint>& b, bool dji,
                 const geometry::GeoPoint& home) {
  Matching m;
  std::size_t& k = m.k;
  std::size_t& j = m.j;
  while (k < a.size() && j < b.size()) {
    if (dji && j > 0 && apart_3d_m(a[k], b[j - 1]) <= kMergedWithin_m &&
        geometry::geodesic_distance_m(a[k].at, b[j].at) > 0.01) {
      ++k;  // merged into the point flown before
    } else if (geometry::geodesic_distance_m(a[k].at, b[j].at) <= 0.01) {
      m.pairs.push_back({k++, j++});
    } else if (dji && j == 0 && geometry::geodesic_distance_m(b[0].at, home) <= 0.01) {
      ++j;  // the rise above home to the .plan's take-off altitude that the flight starts with
    } else if (dji && apart_3d_m(a[k], b[j]) <= kMergedWithin_m) {
      ++k;  // merged into the point flown next
    } else if (dji && k > 0 && on_leg(b[j], a[k - 1], a[k])) {
      ++j;
    } else {
      break;
    }
  }
  // The .plan's last waypoints merged into the file's last.
  while (dji && k < a.size() && j == b.size() && j > 0 &&
         apart_3d_m(a[k], b[j - 1]) <= kMergedWithin_m)
    ++k;
  return m;
}

// A twin agrees when it flies the .plan's waypoints, in order, at the same heights (to the
// writers' rounding); a Litchi or DJI file may add its last row at home (the landing), and keeps
// DJI's waypoint spacing (matched()). Returns how many heights could not be compared
// (terrain frame against above home, without a DEM).
std::size_t check_twin(const missions::Mission& plan, const Twin& twin,
                       const geometry::Ground* ground, Report& report) {
  const std::vector<Waypoint> a = waypoints(plan, ground), b = joined_waypoints(twin.parts, ground);
  // Litchi and DJI files add their landing point at home as a last waypoint.
  const std::string& format = twin.parts.front().format;
  const bool litchi = format == "Litchi CSV" || format == "DJI WPML";
  std::string problem;
  const missions::Mission* in = &twin.parts.front();
  std::size_t unknown_heights = 0;
  const Matching m = matched(a, b, litchi, plan.home);
  for (const auto& [k, j] : m.pairs) {
    in = b[j].file;
    if (!heights_comparable(a[k], b[j], ground)) {
      ++unknown_heights;
    } else if (std::abs(a[k].above_home_m - b[j].above_home_m) > 0.01) {
      problem = waypoint_name(b[j], k + 1) + " flies at " + fixed_text(b[j].above_home_m, 2) +
                " m above home, the .plan's at " + fixed_text(a[k].above_home_m, 2) + " m";
      break;
    }
  }
  const std::size_t k_end = m.k, j_end = m.j;
  if (problem.empty() && k_end < a.size() && j_end < b.size()) {
    in = b[j_end].file;
    problem = waypoint_name(b[j_end], k_end + 1) + " lies " +
              fixed_text(geometry::geodesic_distance_m(a[k_end].at, b[j_end].at), 2) +
              " m from the .plan's";
  }
  // The one row a Litchi or DJI file may add is its landing at home, nowhere else.
  const bool one_more = litchi && k_end == a.size() && j_end + 1 == b.size();
  const bool lands_at_home =
      one_more && geometry::geodesic_distance_m(b.back().at, plan.home) <= 0.01;
  if (problem.empty() && one_more && !lands_at_home) {
    in = b.back().file;
    problem = waypoint_name(b.back(), b.size()) + ", past the .plan's last, lies " +
              fixed_text(geometry::geodesic_distance_m(b.back().at, plan.home), 2) +
              " m from its home (only a landing at home may be added)";
  }
  if (!problem.empty()) {
    report.violations.push_back({"agreement", in->source, std::nullopt, 0.0,
                                 in->source + " differs from " + plan.source + ": " + problem});
  } else if ((k_end != a.size() || j_end != b.size()) && !lands_at_home) {
    report.violations.push_back({"agreement", twin.parts.front().source, std::nullopt, 0.0,
                                 twin_name(twin) + " from " + plan.source + ": " +
                                     std::to_string(b.size()) + " waypoints, the .plan " +
                                     std::to_string(a.size())});
  }
  return unknown_heights;
}

// A part of a split Litchi flight, NAME-litchi-N.csv (a Litchi mission holds at most 99
// waypoints): `flight` is its path less "-litchi-N.csv".
struct LitchiPart {
  std::string flight;
  int number = 0;
};

std::optional<LitchiPart> litchi_part(const std::string& name) {
  if (!ends_with(name, ".csv")) return std::nullopt;
  const std::string stem = stem_of(name, ".csv");
  const std::size_t dash = stem.find_last_of('-');
  const std::string digits = dash == std::string::npos ? "" : stem.substr(dash + 1);
  const bool number =
      !digits.empty() && digits.size() < 6 &&
      std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!number || !ends_with(stem.substr(0, dash), "-litchi")) return std::nullopt;
  return LitchiPart{stem_of(stem.substr(0, dash), "-litchi"), std::stoi(digits)};
}

// The names of a split Litchi flight's parts in the set, in part order (-10 after -9).
std::vector<std::string> litchi_parts(const Files& files, const std::string& flight) {
  std::vector<std::pair<int, std::string>> parts;
  for (const auto& [name, text] : files)
    if (const auto p = litchi_part(name); p && p->flight == flight)
      parts.push_back({p->number, name});
  std::sort(parts.begin(), parts.end());
  parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
  std::vector<std::string> out;
  for (auto& [number, name] : parts) out.push_back(std::move(name));
  return out;
}

// The terrain frame's heights above home are the DEM's: without one they are not compared.
std::string unknown_heights_text(std::size_t unknown_heights) {
  if (unknown_heights == 0) return "";
  return " (" + std::to_string(unknown_heights) +
         " heights in the terrain frame not compared: no DEM, --terrain)";
}

bool is_plan(const std::string& name) {
  return ends_with(name, ".plan") && !ends_with(name, "-survey.plan");
}

// A fence or rally file by its content (Mission Planner saves them under any name).
bool is_fence_file(const std::string& name, const std::string& text) {
  return ends_with(name, ".waypoints") && missions::is_wpl_fence_file(text);
}

// The drones' files in the set's order: each .plan, or without one the other mission files, the
// parts of a split Litchi flight together in part order.
std::vector<std::string> drone_names(const Files& files) {
  bool any_plan = false;
  for (const auto& [name, text] : files) any_plan = any_plan || is_plan(name);
  std::vector<std::string> out;
  std::set<std::string> split_flights;
  for (const auto& [name, text] : files) {
    if (any_plan) {
      if (is_plan(name)) out.push_back(name);
    } else if (const auto part = litchi_part(name)) {
      if (split_flights.insert(part->flight).second)
        for (std::string& p : litchi_parts(files, part->flight)) out.push_back(std::move(p));
    } else if (ends_with(name, ".waypoints")
                   ? !is_fence_file(name, text)
                   : ends_with(name, "-litchi.csv") || ends_with(name, ".kmz")) {
      out.push_back(name);
    }
  }
  return out;
}

// When the file flies, by its stem in summary.json; the parts of a split Litchi flight by the
// flight's stem, in turn as sorties of it.
void set_launch(DroneFile& d, const std::string& name,
                const std::map<std::string, Launch>& by_file) {
  const auto part = litchi_part(name);
  const std::string path = part ? part->flight + ".csv" : name;
  const std::string base_name = path.substr(path.find_last_of('/') + 1);
  const std::string stem = stem_of(base_name, base_name.substr(base_name.find_last_of('.')));
  if (const auto it = by_file.find(stem); it != by_file.end()) {
    d.launch_offset_s = it->second.offset_s;
    d.sorties_of = it->second.sorties_of;
    d.sortie = it->second.sortie;
  }
  if (part && d.sorties_of.empty()) d.sorties_of = stem + "-litchi";
}

// A twin of the .plan (a .waypoints, Litchi or DJI file, a part of a split Litchi flight) as its
// drone flies it in the .plan's place: the pilot may load either, so each is checked as a flight
// of its own. It keeps to the .plan's fences and rally points (a DJI aircraft knows none of them:
// the check is the only one that does). A Litchi or DJI file holds no home (a KMZ's first
// waypoint is no take-off point), so it takes off where the .plan does, climbs, flies to its first
// row and returns home. A .waypoints or -survey.plan file flies from its own home on the .plan's
// vehicle: a WPL file cannot say its autopilot or that it is a fixed wing (which never stops at
// a waypoint: no stopping margin).
DroneFile flown_in_place(const DroneFile& plan, missions::Mission twin, std::string sorties_of) {
  const missions::Mission& m = plan.mission;
  if (twin.format == "Litchi CSV" || twin.format == "DJI WPML") {
    twin.home = m.home;
  } else {
    twin.autopilot = m.autopilot;
    twin.fixed_wing = m.fixed_wing;
  }
  twin.inclusion_fences = m.inclusion_fences;
  twin.exclusion_fences = m.exclusion_fences;
  twin.inclusion_circles = m.inclusion_circles;
  twin.exclusion_circles = m.exclusion_circles;
  twin.rally_points = m.rally_points;
  const std::string drone = plan.drone.empty()
                                ? (plan.sorties_of.empty() ? plan.mission.source : plan.sorties_of)
                                : plan.drone;
  DroneFile d;
  d.mission = std::move(twin);
  d.launch_offset_s = plan.launch_offset_s;
  d.sorties_of = std::move(sorties_of);
  d.instead = true;
  d.drone = drone;
  return d;
}

}  // namespace

Report verify_files(const Files& files, const CheckOptions& options) {
  // Each name's text where the set holds it (the first of a name given twice): not a copy of
  // every file (a plan's photos.geojson is megabytes).
  std::map<std::string, const std::string*> by_name;
  for (const auto& [name, text] : files) by_name.try_emplace(name, &text);
  const std::vector<std::string> drones = drone_names(files);
  if (drones.empty())
    throw base::InputError(
        "no mission file among the files given (.plan, .waypoints, -litchi.csv, -litchi-N.csv or "
        ".kmz)");
  const auto by_file = launches(files);
  std::vector<DroneFile> set, instead;
  std::vector<Twin> twins;
  std::map<std::string, geometry::GeoPoint> split_homes;  // a split flight's: its first part's
  for (const std::string& name : drones) {
    DroneFile d;
    d.mission = missions::parse_mission(*by_name.at(name), name);
    for (const auto& [fence_name, text] : files)
      if (is_fence_file(fence_name, text)) missions::add_wpl_fences(d.mission, text, fence_name);
    set_launch(d, name, by_file);
    if (const auto part = litchi_part(name))
      d.mission.home = split_homes.try_emplace(part->flight, d.mission.home).first->second;
    if (is_plan(name)) {
      const std::string dir_stem = stem_of(name, ".plan");
      for (const char* tail : {".waypoints", "-litchi.csv", "-survey.plan", ".kmz"})
        if (const auto t = by_name.find(dir_stem + tail); t != by_name.end()) {
          twins.push_back({set.size(), {missions::parse_mission(*t->second, t->first)}});
          instead.push_back(flown_in_place(d, twins.back().parts[0], ""));
        }
      // Litchi flies each part as a mission of its own, one after the other.
      Twin split{set.size(), {}};
      for (const std::string& p : litchi_parts(files, dir_stem)) {
        split.parts.push_back(missions::parse_mission(*by_name.at(p), p));
        instead.push_back(flown_in_place(d, split.parts.back(), name + " in Litchi parts"));
      }
      if (!split.parts.empty()) twins.push_back(std::move(split));
    }
    set.push_back(std::move(d));
  }
  for (DroneFile& d : instead) set.push_back(std::move(d));
  Report report = verify(set, options);
  std::size_t unknown_heights = 0;
  for (const Twin& twin : twins) {
    unknown_heights += check_twin(set[twin.drone].mission, twin, options.ground.get(), report);
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
  for (const std::string& w : report.warnings) out += "  warning    " + w + "\n";
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
  j["warnings"] = report.warnings;
  return base::json_text(j, 2) + "\n";
}

}  // namespace swath::preflight

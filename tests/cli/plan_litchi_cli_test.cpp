// swath plan --litchi where a split flight's part cannot fly home straight: a no-fly zone lies
// between home and where the part stops, so the part carries a way home round the zone and the
// next part the way back out (docs/swath-plan.md). The written CSVs are read back here and every
// straight leg Litchi flies (row to row, home to the first row, the last row home) is measured
// against the zone by this file's own geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Xy {
  double x, y;
};

// East and north metres about (lat0, lon0) by WGS84's radii of curvature there: within a
// millimetre over the few hundred metres of these fields.
struct Frame {
  double lat0, lon0, m_per_deg_lat, m_per_deg_lon;
  Frame(double lat, double lon) : lat0(lat), lon0(lon) {
    const double a = 6378137.0, e2 = 6.69437999014e-3, s = std::sin(lat * M_PI / 180);
    const double w = 1 - e2 * s * s;
    m_per_deg_lat = a * (1 - e2) / std::pow(w, 1.5) * M_PI / 180;
    m_per_deg_lon = a / std::sqrt(w) * std::cos(lat * M_PI / 180) * M_PI / 180;
  }
  Xy local(double lat, double lon) const {
    return {(lon - lon0) * m_per_deg_lon, (lat - lat0) * m_per_deg_lat};
  }
  std::string lon_lat(Xy p) const {
    std::ostringstream o;
    o.precision(13);
    o << "[" << lon0 + p.x / m_per_deg_lon << "," << lat0 + p.y / m_per_deg_lat << "]";
    return o.str();
  }
  std::string polygon(const std::vector<Xy>& ring) const {
    std::string s = R"({"type":"Polygon","coordinates":[[)";
    for (const Xy& p : ring) s += lon_lat(p) + ",";
    return s + lon_lat(ring.front()) + "]]}";
  }
};

double cross(Xy o, Xy a, Xy b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double point_segment_m(Xy p, Xy a, Xy b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  const double t =
      len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

bool segments_cross(Xy a, Xy b, Xy c, Xy d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

bool inside(Xy p, const std::vector<Xy>& ring) {  // even-odd ray cast
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
        p.x < ring[j].x + (p.y - ring[j].y) * (ring[i].x - ring[j].x) / (ring[i].y - ring[j].y))
      in = !in;
  return in;
}

// Least distance from the segment a-b to the polygon `zone` (0 where it enters it).
double segment_zone_m(Xy a, Xy b, const std::vector<Xy>& zone) {
  if (inside(a, zone) || inside(b, zone)) return 0.0;
  double least = 1e18;
  for (std::size_t i = 0, j = zone.size() - 1; i < zone.size(); j = i++) {
    if (segments_cross(a, b, zone[j], zone[i])) return 0.0;
    least = std::min({least, point_segment_m(a, zone[j], zone[i]),
                      point_segment_m(b, zone[j], zone[i]), point_segment_m(zone[i], a, b)});
  }
  return least;
}

struct Row {
  Xy at;
  std::string photo_time, photo_distance;
};

std::vector<Row> litchi_rows(const std::string& path, const Frame& frame) {
  const auto rows = csv_rows(read_text(path));
  EXPECT_GE(rows.size(), 2u) << path;
  std::map<std::string, std::size_t> column;
  for (std::size_t k = 0; k < rows.at(0).size(); ++k) column[rows[0][k]] = k;
  std::vector<Row> out;
  for (std::size_t r = 1; r < rows.size(); ++r)
    out.push_back({frame.local(std::stod(rows[r].at(column.at("latitude"))),
                               std::stod(rows[r].at(column.at("longitude")))),
                   rows[r].at(column.at("photo_timeinterval")),
                   rows[r].at(column.at("photo_distinterval"))});
  return out;
}

// The Litchi files of the flight whose .plan is STEM.plan, in the order they are flown.
std::vector<std::string> litchi_files(const std::string& stem) {
  if (fs::exists(stem + "-litchi.csv")) return {stem + "-litchi.csv"};
  std::vector<std::string> out;
  for (int k = 1; fs::exists(stem + "-litchi-" + std::to_string(k) + ".csv"); ++k)
    out.push_back(stem + "-litchi-" + std::to_string(k) + ".csv");
  return out;
}

struct Case {
  std::string name;
  std::vector<Xy> area, zone;
  Xy home;
  std::string options;
};

// Plans the case with --litchi and checks every straight leg of every Litchi file against the
// zone; returns how many rows the files carry that are none of the .plan's waypoints (the ways
// home and out).
int check_case(const Case& c) {
  const double clearance_m = 5.0;
  const Frame frame(47.0, 8.0);
  const std::string dir = fresh_dir("litchi-way-" + c.name);
  fs::create_directories(dir);
  std::ofstream(dir + "/area.geojson") << frame.polygon(c.area);
  std::ofstream(dir + "/zone.geojson") << frame.polygon(c.zone);
  std::ostringstream home;
  home.precision(13);
  home << frame.lat0 + c.home.y / frame.m_per_deg_lat << ","
       << frame.lon0 + c.home.x / frame.m_per_deg_lon;
  const std::string out = dir + "/out";
  // swath plan's own check of its files is left off (and restored) so that they are judged here
  // and by swath verify below, each on its own.
  const char* was = std::getenv("SWATH_PLAN_VERIFY");
  const std::string saved = was ? was : "";
  setenv("SWATH_PLAN_VERIFY", "0", 1);
  const CliRun run =
      run_swath("plan " + dir + "/area.geojson --camera dji-mavic-3e --exclude " + dir +
                "/zone.geojson --home " + home.str() + " " + c.options + " --litchi -o " + out);
  was ? setenv("SWATH_PLAN_VERIFY", saved.c_str(), 1) : unsetenv("SWATH_PLAN_VERIFY");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  int added = 0, files = 0;
  if (!fs::is_directory(out)) return -1;
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".plan") continue;
    const std::string stem = out + "/" + name.substr(0, name.size() - 5);
    const json plan = json::parse(read_text(stem + ".plan"));
    const json& h = plan["mission"]["plannedHomePosition"];
    const Xy plan_home = frame.local(h[0].get<double>(), h[1].get<double>());
    std::vector<Xy> waypoints;
    for (const json& item : plan["mission"]["items"])
      if (item["command"] == 16)
        waypoints.push_back(
            frame.local(item["params"][4].get<double>(), item["params"][5].get<double>()));
    const auto is_waypoint = [&](Xy p) {
      return std::any_of(waypoints.begin(), waypoints.end(),
                         [&](Xy w) { return std::hypot(w.x - p.x, w.y - p.y) < 0.01; });
    };
    for (const std::string& file : litchi_files(stem)) {
      SCOPED_TRACE(file);
      ++files;
      const std::vector<Row> rows = litchi_rows(file, frame);
      EXPECT_LE(rows.size(), 99u);
      // Litchi flies from home to the first row, row to row, and home from the last row.
      std::vector<Xy> flown{plan_home};
      for (const Row& r : rows) flown.push_back(r.at);
      flown.push_back(plan_home);
      for (std::size_t k = 0; k + 1 < flown.size(); ++k)
        EXPECT_GE(segment_zone_m(flown[k], flown[k + 1], c.zone), clearance_m - 0.02)
            << "leg " << k << " of " << flown.size() - 1;
      // A row that is none of the .plan's waypoints is a way home or out: no photos on the legs
      // it starts or ends.
      for (std::size_t k = 0; k < rows.size(); ++k) {
        if (is_waypoint(rows[k].at)) continue;
        ++added;
        for (std::size_t j : {k, k > 0 ? k - 1 : k})
          EXPECT_TRUE(rows[j].photo_time == "-1" && rows[j].photo_distance == "-1") << "row " << j;
      }
    }
  }
  EXPECT_GT(files, 1) << "a flight of several Litchi files";
  const CliRun verified = run_swath("verify " + out);
  EXPECT_EQ(verified.exit_code, 0) << verified.out;
  return added;
}

// Two drones over a field a zone crosses: the parts that stop north of it fly home round it. A
// sortied L-shaped field with a zone between home and the field and a tight fence. Both were
// refused before the parts carried their ways home ("return to launch after
// drone-1-litchi-2.csv's last item enters no-fly zone").
TEST(PlanCli, LitchiPartsFlyHomeRoundTheZonesTheyCannotCrossStraight) {
  const std::vector<Case> cases{
      {"drones",
       {{0, 0}, {600, 0}, {600, 600}, {0, 600}},
       {{100, 250}, {500, 250}, {500, 350}, {100, 350}},
       {300, -40},
       "--altitude 40 --drones 2 --waypoint-spacing 30"},
      {"sorties",
       {{0, 0}, {660, 0}, {660, 575}, {0, 575}},
       {{266, -60}, {488, -60}, {488, -25}, {266, -25}},
       {362, -100},
       "--altitude 40 --sorties auto --endurance 900 --waypoint-spacing 10 --fence-margin 10"},
      {"l-shape",
       {{0, 0}, {394, 0}, {394, 171}, {197, 171}, {197, 341}, {0, 341}},
       {{106, -60}, {179, -60}, {179, -25}, {106, -25}},
       {139, -100},
       "--altitude 40 --waypoint-spacing 40"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    EXPECT_GT(check_case(c), 0) << "the case needs a way home round the zone";
  }
}

// Home in the middle of 30 nested C-shaped zones, their openings alternating north and south:
// the way home from anywhere outside them bends about a hundred times, more than a Litchi
// mission holds on top of the work, so --litchi refuses in one sentence and writes nothing,
// while the same plan without it is written.
TEST(PlanCli, LitchiRefusesAFlightWhoseWayHomeDoesNotFitInAMission) {
  const Frame frame(47.0, 8.0);
  const std::string dir = fresh_dir("litchi-way-maze");
  fs::create_directories(dir);
  std::string zones = R"({"type":"FeatureCollection","features":[)";
  for (int k = 0; k < 30; ++k) {
    const double a = 10.0 + 10.0 * k, b = a + 2.0, g = 3.0, s = k % 2 == 0 ? 1.0 : -1.0;
    const std::vector<Xy> c{{-g, s * b}, {-b, s * b},  {-b, -s * b}, {b, -s * b},
                            {b, s * b},  {g, s * b},   {g, s * a},   {a, s * a},
                            {a, -s * a}, {-a, -s * a}, {-a, s * a},  {-g, s * a}};
    zones += std::string(k ? "," : "") + R"({"type":"Feature","properties":{},"geometry":)" +
             frame.polygon(c) + "}";
  }
  std::ofstream(dir + "/zones.geojson") << zones << "]}";
  std::ofstream(dir + "/area.geojson")
      << frame.polygon({{330, -100}, {530, -100}, {530, 100}, {330, 100}});
  const std::string plan = "plan " + dir + "/area.geojson --camera dji-mavic-3e --altitude 40 " +
                           "--exclude " + dir + "/zones.geojson --clearance 1 --speed 2 --home " +
                           "47,8 -o " + dir;
  const CliRun refused = run_swath(plan + "/refused --litchi");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("swath plan: --litchi: drone-1's flight cannot be cut into Litchi "
                             "missions of at most 99 waypoints: from none of its waypoints "),
            std::string::npos)
      << refused.err;
  // One sentence, the last line said (warnings about the plan's fence may come before it).
  const std::size_t line = refused.err.rfind('\n', refused.err.size() - 2);
  EXPECT_EQ(refused.err.compare(line + 1, 22, "swath plan: --litchi: "), 0) << refused.err;
  EXPECT_FALSE(fs::exists(dir + "/refused/drone-1.plan"));
  const CliRun planned = run_swath(plan + "/planned");
  EXPECT_EQ(planned.exit_code, 0) << planned.err;
  EXPECT_TRUE(fs::exists(dir + "/planned/drone-1.plan"));
}

}  // namespace
}  // namespace swath::test

// plan.html in a real browser: headless Chromium opens the page swath wrote, and what it drew is
// checked against the plan's own files, read here independently of the page's script.
// - --dump-dom: the page's self-check (#swath-check): no script error, no request made, and each
//   layer's feature count, compared with counts parsed from mission.geojson, photos.csv,
//   waypoints.csv, summary.json and the .plan files.
// - --screenshot: the area layer alone, each pixel compared with where Web Mercator and Leaflet's
//   fitBounds (zoomSnap 0, 20 px padding) put the area: fill inside, background outside.
// Without Chromium (/usr/bin/chromium or $SWATH_CHROMIUM) the browser tests skip, saying so.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <regex>

#include "chromium.hpp"
#include "command.hpp"
#include "plan_command.hpp"
#include "swath/geometry/imagery.hpp"
#include "swath/render/image.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using namespace swath::html_test;

// Chromium headless, offline: every host name fails to resolve, so a request could reach nothing
// even if one were made (the page's own record of requests is what is checked).
std::string browser(const fs::path& profile, const std::string& mode, const std::string& url) {
  return "'" + chromium() + "' --headless --no-sandbox --disable-gpu --no-first-run " +
         "--no-default-browser-check --user-data-dir='" + profile.string() +
         "' --host-resolver-rules='MAP * ~NOTFOUND' --virtual-time-budget=10000 " + mode + " '" +
         url + "'";
}

// The DOM Chromium dumps after the page ran; `fragment` is the address's part after '#'.
std::string dom(const fs::path& page, const std::string& fragment = "") {
  const std::string url =
      "file://" + fs::absolute(page).string() + (fragment.empty() ? "" : "#" + fragment);
  return run(browser(page.parent_path() / "profile", "--dump-dom", url) + " 2>/dev/null").out;
}

// The page's self-check, read from the DOM.
json self_check(const fs::path& page) {
  return swath::html_test::self_check(dom(page));
}

std::vector<std::vector<std::string>> csv(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(slurp(path));
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// Each layer's feature count as the plan's files give it.
std::map<std::string, int> expected_layers(const fs::path& dir) {
  std::map<std::string, int> n;
  const json mission = json::parse(slurp(dir / "mission.geojson"));
  for (const json& f : mission["features"]) {
    const std::string role = f["properties"]["role"];
    if (role == "area") ++n["area"];
    if (role == "no_fly") ++n["no_fly"];
    if (role == "region") ++n["regions"];
    if (role == "home") ++n["homes"];
    if (role == "path") ++n["path-" + std::to_string(f["properties"]["drone"].get<int>())];
  }
  const json summary = json::parse(slurp(dir / "summary.json"));
  if (summary["flight"]["clearance_m"].get<double>() > 0) n["clearance"] = n["no_fly"];
  for (const json& d : summary["drones"]) n["resume"] += static_cast<int>(d["sorties"].size());
  const auto photos = csv(dir / "photos.csv");
  n["photos"] = n["footprints"] = static_cast<int>(photos.size()) - 1;
  const auto waypoints = csv(dir / "waypoints.csv");
  for (std::size_t k = 1; k < waypoints.size(); ++k)
    if (waypoints[k].back() == "waypoint") ++n["waypoints"];
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".plan") continue;
    const json plan = json::parse(slurp(entry.path()));
    n["fences"] +=
        static_cast<int>(plan["geoFence"]["polygons"].size() + plan["geoFence"]["circles"].size());
    n["rally"] += static_cast<int>(plan["rallyPoints"]["points"].size());
  }
  return n;
}

// The layers the page reports, those with no feature left out (the page lists no empty layer).
std::map<std::string, int> drawn_layers(const json& check) {
  std::map<std::string, int> n;
  for (const auto& [key, count] : check["layers"].items())
    if (count.get<int>() > 0) n[key] = count.get<int>();
  return n;
}

std::map<std::string, int> without_empty(std::map<std::string, int> n) {
  std::erase_if(n, [](const auto& kv) { return kv.second == 0; });
  return n;
}

// `basemap`: the basemap layer's count (0: the page has none).
void expect_clean_page(const fs::path& dir, const std::string& what, int basemap = 0) {
  const json check = self_check(dir / "plan.html");
  ASSERT_TRUE(check.is_object()) << what << ": no self-check in the page's DOM";
  EXPECT_EQ(check["errors"], json::array()) << what;
  EXPECT_EQ(check["resources"], json::array()) << what << ": the page made requests";
  std::map<std::string, int> expected = without_empty(expected_layers(dir));
  if (basemap > 0) expected["basemap"] = basemap;
  EXPECT_EQ(drawn_layers(check), expected) << what;
  std::cout << what << ": page " << fs::file_size(dir / "plan.html") << " bytes, script "
            << check["script_ms"] << " ms (virtual time)\n";
}

// `swath plan ARGS -o DIR`, which must succeed.
void plan_into(const fs::path& dir, const std::string& args) {
  const ShellRun plan = run("'" SWATH_BINARY "' plan " + args + " -o '" + dir.string() + "'");
  ASSERT_EQ(plan.exit_code, 0) << plan.out;
}

const std::string kMeadowFleet =
    "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --fleet "
    "share/fleets/three-quads.yaml --division region --balance makespan --exclude "
    "share/zones/meadow-mast.geojson --clearance 10 --html";

TEST(PlanPage, MeadowFleetDrawsEveryLayerWithoutErrorsOrRequests) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("meadow-fleet");
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, kMeadowFleet));
  expect_clean_page(dir, "meadow, three quads, a mast");
  EXPECT_LT(fs::file_size(dir / "plan.html"), 1'000'000u);
}

TEST(PlanPage, SortiesShowTheirResumePoints) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("sorties");
  ASSERT_NO_FATAL_FAILURE(plan_into(dir,
                                    "share/fields/meadow.geojson --camera sony-ilce-qx1 "
                                    "--altitude 40 --sorties auto --endurance 420 --html"));
  ASSERT_GT(expected_layers(dir)["resume"], 1);
  expect_clean_page(dir, "meadow in sorties");
}

double segment_distance(std::array<double, 2> p, std::array<double, 2> a, std::array<double, 2> b);

// The waypoint nearest a no-fly zone (found here over all waypoints, distances in GeographicLib's
// local Cartesian frame), selected as a click would: the panel shows its item, height, clearance.
TEST(PlanPage, SelectedWaypointShowsItsItemHeightAndClearance) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("select");
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, kMeadowFleet));
  const json mission = json::parse(slurp(dir / "mission.geojson"));
  std::vector<json> zones;
  for (const json& f : mission["features"])
    if (f["properties"]["role"] == "no_fly") zones.push_back(f["geometry"]["coordinates"][0]);
  ASSERT_EQ(zones.size(), 1u);
  const GeographicLib::LocalCartesian frame(zones[0][0][1], zones[0][0][0], 0);
  const auto local = [&frame](double lat, double lon) {
    double x, y, z;
    frame.Forward(lat, lon, 0, x, y, z);
    return std::array<double, 2>{x, y};
  };
  const auto waypoints = csv(dir / "waypoints.csv");
  double nearest_m = 1e9;
  std::vector<std::string> chosen;
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    const auto& w = waypoints[k];  // drone,flight,seq,lat,lon,alt_m,x_m,y_m,action
    if (w[8] != "waypoint") continue;
    const auto p = local(std::stod(w[3]), std::stod(w[4]));
    for (std::size_t i = 0; i + 1 < zones[0].size(); ++i) {
      const double d = segment_distance(p, local(zones[0][i][1], zones[0][i][0]),
                                        local(zones[0][i + 1][1], zones[0][i + 1][0]));
      if (d < nearest_m) nearest_m = d, chosen = w;
    }
  }
  ASSERT_FALSE(chosen.empty());
  const std::string page = dom(dir / "plan.html", "select=" + chosen[1] + ":" + chosen[2]);
  const std::size_t at = page.find("<div id=\"selected\">");
  ASSERT_NE(at, std::string::npos);
  const std::string panel = page.substr(at, page.find("</div>", at) - at);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      panel, m,
      std::regex("<td>flight</td><td>([^<]*)</td></tr><tr><td>item</td><td>([0-9]+)</td></tr>"
                 "<tr><td>height \\(relative\\)</td><td>([0-9.]+) m</td></tr><tr><td>clearance"
                 "</td><td>([0-9.]+) m to the nearest no-fly zone")))
      << panel;
  EXPECT_EQ(m[1], chosen[1]);
  EXPECT_EQ(m[2], chosen[2]);
  EXPECT_NEAR(std::stod(m[3]), std::stod(chosen[5]), 0.051);
  EXPECT_NEAR(std::stod(m[4]), nearest_m, 0.1);
  EXPECT_GE(nearest_m, 10 - 0.01);  // --clearance 10
}

// With --terrain the panel draws each flight's waypoint heights along its path: as many points
// as the flight has waypoints, from the lowest to the highest height waypoints.csv gives.
TEST(PlanPage, TerrainPlanShowsHeightsAlongEachPath) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("terrain");
  ASSERT_NO_FATAL_FAILURE(plan_into(dir,
                                    "share/fields/meadow.geojson --camera sony-ilce-qx1 "
                                    "--altitude 60 --terrain share/dems/meadow-hill.asc --html"));
  expect_clean_page(dir, "meadow over its hill");
  std::map<std::string, int> expected;
  std::map<std::string, std::pair<double, double>> heights;  // lowest, highest
  const auto waypoints = csv(dir / "waypoints.csv");
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    const auto& w = waypoints[k];  // drone,flight,seq,lat,lon,alt_m,x_m,y_m,action
    if (w[8] != "waypoint") continue;
    ++expected[w[1]];
    auto [it, fresh] = heights.try_emplace(w[1], std::stod(w[5]), std::stod(w[5]));
    it->second = {std::min(it->second.first, std::stod(w[5])),
                  std::max(it->second.second, std::stod(w[5]))};
  }
  const json check = self_check(dir / "plan.html");
  ASSERT_TRUE(check.is_object());
  const auto profiles = check["profiles"].get<std::map<std::string, int>>();
  EXPECT_EQ(profiles, expected);
  const std::string page = dom(dir / "plan.html");
  const std::size_t at = page.find("<div id=\"profiles\">");
  ASSERT_NE(at, std::string::npos);
  const std::string panel = page.substr(at, 4000);
  for (const auto& [flight, range] : heights) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(panel, m, std::regex(flight + ": ([0-9.]+) to ([0-9.]+) m over")))
        << panel;
    EXPECT_NEAR(std::stod(m[1]), range.first, 0.051);
    EXPECT_NEAR(std::stod(m[2]), range.second, 0.051);
    EXPECT_GT(range.second - range.first, 5.0);  // the hill is followed
  }
}

// Names come from the user's files: the page shows them as text, never as HTML (an <img> in a
// drone's name would be a request).
TEST(PlanPage, DroneNamesAreText) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("names");
  fs::create_directories(dir.parent_path() / "fleet");
  std::string fleet = slurp(fs::path(SWATH_SOURCE_DIR) / "share/fleets/three-quads.yaml");
  fleet.replace(fleet.find("name: alpha"), 11, "name: \"<img src=planted.png>\"");
  std::ofstream(dir.parent_path() / "fleet/evil.yaml") << fleet;
  ASSERT_NO_FATAL_FAILURE(plan_into(dir,
                                    "share/fields/meadow.geojson --camera sony-ilce-qx1 "
                                    "--altitude 60 --html --fleet '" +
                                        (dir.parent_path() / "fleet/evil.yaml").string() + "'"));
  expect_clean_page(dir, "a drone named <img src=planted.png>");
  EXPECT_NE(dom(dir / "plan.html").find("Path &lt;img src=planted.png&gt;"), std::string::npos);
}

// A page with a basemap does fetch its tiles: the check above would see requests.
TEST(PlanPage, BasemapUrlIsTheOnlyThingFetched) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("basemap");
  ASSERT_NO_FATAL_FAILURE(
      plan_into(dir,
                "share/fields/meadow.geojson --camera sony-ilce-qx1 "
                "--altitude 60 --html --basemap-url 'http://127.0.0.1:9/{z}/{x}/{y}.png'"));
  const json check = self_check(dir / "plan.html");
  ASSERT_TRUE(check.is_object());
  ASSERT_FALSE(check["resources"].empty());
  for (const json& url : check["resources"])
    EXPECT_EQ(url.get<std::string>().rfind("http://127.0.0.1:9/", 0), 0u) << url;
}

// Web Mercator, radians: x east, y north.
std::array<double, 2> mercator(double lon_deg, double lat_deg) {
  const double k = std::numbers::pi / 180;
  return {lon_deg * k, std::log(std::tan(std::numbers::pi / 4 + lat_deg * k / 2))};
}

double segment_distance(std::array<double, 2> p, std::array<double, 2> a, std::array<double, 2> b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
  const double t =
      len2 > 0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// The page's view, as Leaflet draws it in a 1200 x 900 window: the bounds of every position in
// mission.geojson in Web Mercator, fitted into the map (x from 300, the side panel's width) 20 px
// from its edges, centred (fitBounds, zoomSnap 0).
struct PageView {
  double scale = 0, cx = 0, cy = 0;
  std::array<double, 2> pixel(double lon_deg, double lat_deg) const {
    const auto m = mercator(lon_deg, lat_deg);
    return {300 + 900 / 2.0 + (m[0] - cx) * scale, 900 / 2.0 - (m[1] - cy) * scale};
  }
};

PageView page_view(const fs::path& dir) {
  const json mission = json::parse(slurp(dir / "mission.geojson"));
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  const auto grow = [&](const json& position) {
    const auto m = mercator(position[0], position[1]);
    x0 = std::min(x0, m[0]), x1 = std::max(x1, m[0]), y0 = std::min(y0, m[1]),
    y1 = std::max(y1, m[1]);
  };
  for (const json& f : mission["features"]) {
    const json& g = f["geometry"];
    if (g["type"] == "Point") grow(g["coordinates"]);
    if (g["type"] == "LineString")
      for (const json& p : g["coordinates"]) grow(p);
    if (g["type"] == "Polygon")
      for (const json& ring : g["coordinates"])
        for (const json& p : ring) grow(p);
  }
  const double map_w = 900, map_h = 900, pad = 20;
  return {std::min((map_w - 2 * pad) / (x1 - x0), (map_h - 2 * pad) / (y1 - y0)), (x0 + x1) / 2,
          (y0 + y1) / 2};
}

// Chromium's 1200 x 900 screenshot of DIR/plan.html showing the layers `layers` names.
swath::render::Image screenshot(const fs::path& dir, const std::string& layers) {
  const fs::path png = dir / ("shot-" + layers + ".png");
  const ShellRun shot =
      run(browser(dir / "profile",
                  "--hide-scrollbars --force-device-scale-factor=1 "
                  "--window-size=1200,900 --screenshot='" +
                      png.string() + "'",
                  "file://" + fs::absolute(dir / "plan.html").string() + "#layers=" + layers));
  EXPECT_TRUE(fs::exists(png)) << shot.out;
  return fs::exists(png) ? swath::render::decode_png(slurp(png)) : swath::render::Image{};
}

TEST(PlanPage, ScreenshotShowsTheAreaWhereTheDataPutsIt) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("vineyard");
  ASSERT_NO_FATAL_FAILURE(
      plan_into(dir,
                "share/fields/vineyard.kml --camera "
                "dji-phantom-4-pro --altitude 60 --home 46.2276,7.5917 --html"));
  const swath::render::Image image = screenshot(dir, "area");
  ASSERT_EQ(image.width, 1200);
  ASSERT_EQ(image.height, 900);
  const PageView view = page_view(dir);
  std::vector<std::vector<std::array<double, 2>>> rings;  // the area's, in pixels
  const json mission = json::parse(slurp(dir / "mission.geojson"));
  for (const json& f : mission["features"])
    if (f["properties"]["role"] == "area")
      for (const json& ring : f["geometry"]["coordinates"]) {
        rings.emplace_back();
        for (const json& p : ring) rings.back().push_back(view.pixel(p[0], p[1]));
      }
  ASSERT_FALSE(rings.empty());

  // Every 5th pixel at least 3 px from the area's edges and clear of the zoom buttons: inside
  // the area (even-odd over its rings: holes are outside) the fill, #7fbf5f at half opacity over
  // white; outside white.
  int inside_n = 0, inside_ok = 0, outside_n = 0, outside_ok = 0;
  std::string wrong;  // the first pixels that are not what the data says
  for (int y = 2; y < 900; y += 5)
    for (int x = 302; x < 1200; x += 5) {
      if (x < 360 && y < 90) continue;
      const std::array<double, 2> p{x + 0.5, y + 0.5};
      bool inside = false;
      double edge = 1e9;
      for (const auto& r : rings)
        for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
          if ((r[i][1] > p[1]) != (r[j][1] > p[1]) &&
              p[0] < (r[j][0] - r[i][0]) * (p[1] - r[i][1]) / (r[j][1] - r[i][1]) + r[i][0])
            inside = !inside;
          edge = std::min(edge, segment_distance(p, r[i], r[j]));
        }
      if (edge < 3) continue;
      const int red = image.at(x, y, 0), green = image.at(x, y, 1), blue = image.at(x, y, 2);
      const bool ok = inside ? std::abs(red - 191) <= 12 && std::abs(green - 223) <= 12 &&
                                   std::abs(blue - 175) <= 12
                             : red >= 248 && green >= 248 && blue >= 248;
      (inside ? inside_n : outside_n) += 1;
      (inside ? inside_ok : outside_ok) += ok;
      if (!ok && wrong.size() < 400)
        wrong += " (" + std::to_string(x) + "," + std::to_string(y) + (inside ? " in" : " out") +
                 ": " + std::to_string(red) + "," + std::to_string(green) + "," +
                 std::to_string(blue) + ")";
    }
  EXPECT_GT(inside_n, 1000);
  EXPECT_GT(outside_n, 1000);
  EXPECT_GE(inside_ok, inside_n * 99 / 100) << inside_ok << " of " << inside_n << wrong;
  EXPECT_GE(outside_ok, outside_n * 99 / 100) << outside_ok << " of " << outside_n << wrong;
}

// No browser needed: the same plan gives the same page from `plan --html` and `render --html`.
TEST(PlanPage, RenderWritesThePageThePlanWrote) {
  const fs::path dir = scratch("render");
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, kMeadowFleet));
  const std::string written = slurp(dir / "plan.html");
  fs::remove(dir / "plan.html");
  const ShellRun render = run("'" SWATH_BINARY "' render " + dir.string() + " --html");
  ASSERT_EQ(render.exit_code, 0) << render.out;
  EXPECT_EQ(render.out, "swath render: wrote " + (dir / "plan.html").string() + "\n");
  EXPECT_EQ(slurp(dir / "plan.html"), written);
  EXPECT_FALSE(fs::exists(dir / "coverage.png"));
}

TEST(PlanPage, BadBasemapUrlIsRefusedAndNothingWritten) {
  const fs::path dir = scratch("bad-url");
  const ShellRun plan = run("'" SWATH_BINARY
                            "' plan share/fields/meadow.geojson --camera sony-ilce-qx1 "
                            "--altitude 60 --html --basemap-url 'ftp://tiles/{z}/{x}/{y}.png' -o " +
                            dir.string());
  EXPECT_EQ(plan.exit_code, 2) << plan.out;
  EXPECT_NE(plan.out.find("--basemap-url ftp://tiles/{z}/{x}/{y}.png: not an XYZ tile template"),
            std::string::npos)
      << plan.out;
  EXPECT_FALSE(fs::exists(dir));
  const ShellRun alone = run("'" SWATH_BINARY
                             "' plan share/fields/meadow.geojson --camera sony-ilce-qx1 "
                             "--altitude 60 --basemap-url 'https://t/{z}/{x}/{y}.png' -o " +
                             dir.string());
  EXPECT_EQ(alone.exit_code, 2) << alone.out;
  EXPECT_FALSE(fs::exists(dir));
}

// ---- --basemap: the user's raster behind the plan ----------------------------------------------

// Three squares of 12 m (red, green, blue) on dark grey ground, at places inside the meadow.
struct Mark {
  double lat_deg, lon_deg;
  int channel;  // 0 red, 1 green, 2 blue
};
const std::array<Mark, 3> kMarks{
    {{47.3980, 8.5410, 0}, {47.3992, 8.5430, 1}, {47.3978, 8.5440, 2}}};

// An orthophoto of the meadow as GDAL would read one: an RGB GeoTIFF in UTM zone 32N (EPSG:32632),
// 1 m pixels, the squares placed by GeographicLib's UTM (not by GDAL, which swath uses to read it).
// `blank`: the same raster all white, no squares.
void write_ortho(const fs::path& path, bool blank = false, double pixel_m = 1) {
  GDALAllRegister();
  double e0 = 1e9, n1 = -1e9, e1 = -1e9, n0 = 1e9;
  for (const auto& [lat, lon] : {std::pair{47.3965, 8.5385}, std::pair{47.4015, 8.5465}}) {
    int zone;
    bool north;
    double e, n;
    GeographicLib::UTMUPS::Forward(lat, lon, zone, north, e, n, 32);
    e0 = std::min(e0, e - 100), e1 = std::max(e1, e + 100);
    n0 = std::min(n0, n - 100), n1 = std::max(n1, n + 100);
  }
  e0 = std::floor(e0), n1 = std::ceil(n1);
  const int w = static_cast<int>((e1 - e0) / pixel_m), h = static_cast<int>((n1 - n0) / pixel_m);
  std::vector<std::vector<std::uint8_t>> bands(
      3, std::vector<std::uint8_t>(w * h, static_cast<std::uint8_t>(blank ? 255 : 40)));
  for (const Mark& m : kMarks) {
    if (blank) break;
    int zone;
    bool north;
    double e, n;
    GeographicLib::UTMUPS::Forward(m.lat_deg, m.lon_deg, zone, north, e, n, 32);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double pe = e0 + (i + 0.5) * pixel_m, pn = n1 - (j + 0.5) * pixel_m;  // its centre
        if (std::abs(pe - e) < 6 && std::abs(pn - n) < 6)
          for (int b = 0; b < 3; ++b)
            bands[b][j * w + i] = static_cast<std::uint8_t>(b == m.channel ? 255 : 0);
      }
  }
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(gtiff, nullptr);
  const char* options[] = {"COMPRESS=DEFLATE", nullptr};
  GDALDataset* d = gtiff->Create(path.c_str(), w, h, 3, GDT_Byte, const_cast<char**>(options));
  ASSERT_NE(d, nullptr);
  double gt[6] = {e0, pixel_m, 0, n1, 0, -pixel_m};
  d->SetGeoTransform(gt);
  OGRSpatialReference utm;
  utm.importFromEPSG(32632);
  d->SetSpatialRef(&utm);
  for (int b = 0; b < 3; ++b)
    ASSERT_EQ(d->GetRasterBand(b + 1)->RasterIO(GF_Write, 0, 0, w, h, bands[b].data(), w, h,
                                                GDT_Byte, 0, 0),
              CE_None);
  GDALClose(d);
}

// The centre of the square of colour `channel` in the page's screenshot (the basemap alone): the
// pixels right of the side panel (300 px) where `channel` is strong (>= 200) and the others weak
// (<= 110); NaN when fewer than `least`.
std::array<double, 2> square_on_page(const swath::render::Image& image, int channel, int least) {
  double sx = 0, sy = 0;
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 300; x < image.width; ++x) {
      bool ok = true;
      for (int c = 0; c < 3; ++c)
        ok = ok && (c == channel ? image.at(x, y, c) >= 200 : image.at(x, y, c) <= 110);
      if (ok) sx += x + 0.5, sy += y + 0.5, ++n;
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return n >= least ? std::array<double, 2>{sx / n, sy / n} : std::array<double, 2>{nan, nan};
}

// The centre of the square of colour `channel` in coverage.png, from what the basemap changed
// against the same picture over a blank (white) basemap: every layer is blended linearly over the
// backdrop, so there the difference is (255 - the raster) times what the layers let through in
// each channel alike: small in `channel` and large in the two others only where the square is.
// NaN when fewer than `least` pixels say so.
std::array<double, 2> square_in_picture(const swath::render::Image& image,
                                        const swath::render::Image& blank, int channel, int least) {
  double sx = 0, sy = 0;
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      bool ok = true;
      for (int c = 0; c < 3; ++c) {
        const int diff = blank.at(x, y, c) - image.at(x, y, c);
        ok = ok && (c == channel ? std::abs(diff) <= 12 : diff >= 60);
      }
      if (ok) sx += x + 0.5, sy += y + 0.5, ++n;
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return n >= least ? std::array<double, 2>{sx / n, sy / n} : std::array<double, 2>{nan, nan};
}

const std::string kMeadow = "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60";

// The page's data (SWATH_DATA) as swath inlined it.
json page_data(const fs::path& page) {
  const std::string html = slurp(page);
  const std::string open = "<script>const SWATH_DATA = ";
  const std::size_t at = html.find(open);
  if (at == std::string::npos) return json();
  const std::size_t end = html.find(";</script>", at);
  return json::parse(html.substr(at + open.size(), end - at - open.size()), nullptr, false);
}

// The XYZ tile (column, row) at zoom z that holds a position.
std::array<int, 2> tile_of(double lon_deg, double lat_deg, int z) {
  const auto m = mercator(lon_deg, lat_deg);
  const double n = std::ldexp(1.0, z);
  return {static_cast<int>(std::floor((m[0] + std::numbers::pi) / (2 * std::numbers::pi) * n)),
          static_cast<int>(std::floor((std::numbers::pi - m[1]) / (2 * std::numbers::pi) * n))};
}

// In the page (Chromium's screenshot, the basemap alone): each square where Web Mercator and
// Leaflet's fitBounds put its coordinates, within 3 px.
TEST(Basemap, PageShowsTheRasterWhereItsCoordinatesSay) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("basemap-page");
  fs::create_directories(scratch_root());
  const fs::path ortho = scratch_root() / "ortho-page.tif";
  ASSERT_NO_FATAL_FAILURE(write_ortho(ortho));
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, kMeadow + " --html --basemap '" + ortho.string() + "'"));
  const json basemap = page_data(dir / "plan.html")["basemap_tiles"];
  ASSERT_TRUE(basemap.is_object());
  expect_clean_page(dir, "meadow over its orthophoto", static_cast<int>(basemap["tiles"].size()));
  // swath render writes the same page from the plan's files.
  const std::string written = slurp(dir / "plan.html");
  const ShellRun render = run("'" SWATH_BINARY "' render '" + dir.string() +
                              "' --html --basemap '" + ortho.string() + "'");
  ASSERT_EQ(render.exit_code, 0) << render.out;
  EXPECT_TRUE(slurp(dir / "plan.html") == written) << "swath render --html --basemap differs";
  const swath::render::Image image = screenshot(dir, "basemap");
  ASSERT_EQ(image.width, 1200);
  const PageView view = page_view(dir);
  for (const Mark& m : kMarks) {
    const auto expected = view.pixel(m.lon_deg, m.lat_deg);
    const auto found = square_on_page(image, m.channel, 20);
    EXPECT_NEAR(found[0], expected[0], 3) << "square " << m.channel;
    EXPECT_NEAR(found[1], expected[1], 3) << "square " << m.channel;
  }
}

// The map's pixels (right of the side panel, clear of the zoom buttons) that are the raster's dark
// ground (40, 40, 40) or one of its squares: a channel of 200 or more with the others at most 110.
int raster_pixels(const swath::render::Image& image) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 300; x < image.width; ++x) {
      if (x < 360 && y < 90) continue;
      const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
      const bool ground = std::max({r, g, b}) <= 60;
      const bool square = (r >= 200 && g <= 110 && b <= 110) ||
                          (g >= 200 && r <= 110 && b <= 110) || (b >= 200 && r <= 110 && g <= 110);
      n += ground || square;
    }
  return n;
}

// The basemap is a layer like the others: its box in the panel, turned off (the address flips it
// as a click does), takes the raster off the map and leaves the plan's layers drawn.
TEST(Basemap, TheBasemapIsALayerThePilotTurnsOff) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("basemap-toggle");
  fs::create_directories(scratch_root());
  const fs::path ortho = scratch_root() / "ortho-toggle.tif";
  ASSERT_NO_FATAL_FAILURE(write_ortho(ortho));
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, kMeadow + " --html --basemap '" + ortho.string() + "'"));
  const std::string page = dom(dir / "plan.html");
  EXPECT_NE(page.find("data-layer=\"basemap\" checked"), std::string::npos)
      << "no basemap box, or not on at first";
  const swath::render::Image on = screenshot(dir, "basemap,area");
  const swath::render::Image off = screenshot(dir, "area");
  ASSERT_EQ(on.width, 1200);
  ASSERT_EQ(off.width, 1200);
  EXPECT_GT(raster_pixels(on), 100'000);  // the ground around the area, about half the map
  EXPECT_EQ(raster_pixels(off), 0);
  // Off, the area alone: its fill where the data puts it (as without a basemap).
  const PageView view = page_view(dir);
  const auto centre = view.pixel(8.5425, 47.3990);  // inside the meadow
  EXPECT_NEAR(off.at(int(centre[0]), int(centre[1]), 0), 191, 12);
  EXPECT_NEAR(off.at(int(centre[0]), int(centre[1]), 1), 223, 12);
}

// A raster of 0.25 m pixels: its tiles at two zoom levels, the finer one the last within the
// page's budget (128 tiles of 256 px), the one finer still (the raster's own) left out and the
// panel saying so. At each level (the page's zoom, #zoom=Z, about the fitted view's centre) each
// square where Web Mercator puts its coordinates, within 3 px.
TEST(Basemap, TilesAtTwoZoomLevelsWithinTheBudget) {
  REQUIRE_CHROMIUM();
  const fs::path dir = scratch("basemap-tiles");
  fs::create_directories(scratch_root());
  const fs::path ortho = scratch_root() / "ortho-fine.tif";
  ASSERT_NO_FATAL_FAILURE(write_ortho(ortho, false, 0.25));
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, kMeadow + " --html --basemap '" + ortho.string() + "'"));
  const json basemap = page_data(dir / "plan.html")["basemap_tiles"];
  ASSERT_TRUE(basemap.is_object());
  const int lo = basemap["min_zoom"], hi = basemap["max_zoom"];
  // The raster's own level: the first whose pixel (Web Mercator's, on the ground here) is no
  // larger than 0.25 m.
  const double ground_px_z0_m =
      2 * std::numbers::pi * 6378137.0 * std::cos(47.399 * std::numbers::pi / 180) / 256;
  const int native = static_cast<int>(std::ceil(std::log2(ground_px_z0_m / 0.25)));
  EXPECT_EQ(native, 19);
  EXPECT_LT(hi, native);
  EXPECT_TRUE(basemap["capped"].get<bool>());
  ASSERT_GE(hi, lo + 1) << "one level only";
  EXPECT_LE(basemap["tiles"].size(), 128u);
  std::map<int, int> per_level;
  for (const auto& [key, url] : basemap["tiles"].items()) ++per_level[std::stoi(key)];
  // Every level has the tiles under the three squares; the level left out would not have fit.
  for (int z = lo; z <= hi; ++z)
    for (const Mark& m : kMarks) {
      const auto t = tile_of(m.lon_deg, m.lat_deg, z);
      EXPECT_TRUE(basemap["tiles"].contains(std::to_string(z) + "/" + std::to_string(t[0]) + "/" +
                                            std::to_string(t[1])))
          << "zoom " << z << " square " << m.channel;
    }
  EXPECT_GT(static_cast<int>(basemap["tiles"].size()) + 3 * per_level[hi], 128)
      << "the next level (about 4 times the finest's tiles) would have fitted";
  const std::string panel = dom(dir / "plan.html");
  EXPECT_NE(panel.find("finer levels left out: the page's size budget"), std::string::npos);
  std::cout << "0.25 m raster: zoom " << lo << " to " << hi << ", " << basemap["tiles"].size()
            << " tiles, page " << fs::file_size(dir / "plan.html") << " bytes\n";
  EXPECT_LT(fs::file_size(dir / "plan.html"), 12'000'000u);
  expect_clean_page(dir, "meadow over a 0.25 m raster", static_cast<int>(basemap["tiles"].size()));

  const PageView fitted = page_view(dir);
  for (const int z : {lo, hi}) {
    PageView view = fitted;
    view.scale = 256 * std::ldexp(1.0, z) / (2 * std::numbers::pi);  // px per radian
    const swath::render::Image image = screenshot(dir, "basemap&zoom=" + std::to_string(z));
    ASSERT_EQ(image.width, 1200);
    for (const Mark& m : kMarks) {
      const auto expected = view.pixel(m.lon_deg, m.lat_deg);
      const auto found = square_on_page(image, m.channel, 20);
      EXPECT_NEAR(found[0], expected[0], 3) << "zoom " << z << " square " << m.channel;
      EXPECT_NEAR(found[1], expected[1], 3) << "zoom " << z << " square " << m.channel;
    }
  }
}

// With --render and --html the raster is opened once for both (and every zoom level of the
// page's tiles): swath's plan command run in this process, GDAL's opens of the raster counted.
TEST(Basemap, RenderAndHtmlOpenTheRasterOnce) {
  const fs::path dir = scratch("basemap-once");
  fs::create_directories(scratch_root());
  const fs::path ortho = scratch_root() / "ortho-once.tif";
  ASSERT_NO_FATAL_FAILURE(write_ortho(ortho, false, 0.5));
  ASSERT_EQ(swath::geometry::imagery_opens(ortho.string()), 0u);
  std::vector<std::string> args{"swath",     "plan",          "share/fields/meadow.geojson",
                                "--camera",  "sony-ilce-qx1", "--altitude",
                                "60",        "--render",      "--html",
                                "--basemap", ortho.string(),  "-o",
                                dir.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  std::vector<std::unique_ptr<swath::apps::Command>> commands;
  commands.push_back(std::make_unique<swath::apps::PlanCommand>());
  const fs::path here = fs::current_path();
  fs::current_path(SWATH_SOURCE_DIR);
  const int code = swath::apps::run_program("swath", "", "", commands,
                                            static_cast<int>(argv.size()), argv.data());
  fs::current_path(here);
  ASSERT_EQ(code, 0);
  const json basemap = page_data(dir / "plan.html")["basemap_tiles"];
  ASSERT_TRUE(basemap.is_object());
  EXPECT_GE(basemap["max_zoom"].get<int>(), basemap["min_zoom"].get<int>() + 1);
  EXPECT_TRUE(fs::exists(dir / "coverage.png"));
  EXPECT_EQ(swath::geometry::imagery_opens(ortho.string()), 1u);
}

// In coverage.png: the squares' centres (square_in_picture) fit one scale and offset from
// east/north metres (GeographicLib's local frame) to pixels, north up, within 3 px; and that fit
// puts the area's corners on its outline as drawn without a basemap (the imagery sits under the
// plan, not merely consistent with itself).
TEST(Basemap, CoveragePictureShowsTheRasterUnderThePlan) {
  const fs::path plain_dir = scratch("basemap-plain"), blank_dir = scratch("basemap-blank"),
                 dir = scratch("basemap-png");
  fs::create_directories(scratch_root());
  const fs::path ortho = scratch_root() / "ortho-png.tif", white = scratch_root() / "white.tif";
  ASSERT_NO_FATAL_FAILURE(write_ortho(ortho));
  ASSERT_NO_FATAL_FAILURE(write_ortho(white, true));
  const std::string args = kMeadow + " --render --size 1200x900";
  ASSERT_NO_FATAL_FAILURE(plan_into(plain_dir, args));
  ASSERT_NO_FATAL_FAILURE(plan_into(blank_dir, args + " --basemap '" + white.string() + "'"));
  ASSERT_NO_FATAL_FAILURE(plan_into(dir, args + " --basemap '" + ortho.string() + "'"));
  const auto plain = swath::render::decode_png(slurp(plain_dir / "coverage.png"));
  const auto blank = swath::render::decode_png(slurp(blank_dir / "coverage.png"));
  const auto image = swath::render::decode_png(slurp(dir / "coverage.png"));
  ASSERT_EQ(image.width, plain.width);
  ASSERT_EQ(image.width, blank.width);
  // swath render draws the same picture from the plan's files.
  const ShellRun render =
      run("'" SWATH_BINARY "' render '" + dir.string() + "' --size 1200x900 --coverage '" +
          (dir / "again.png").string() + "' --basemap '" + ortho.string() + "'");
  ASSERT_EQ(render.exit_code, 0) << render.out;
  EXPECT_TRUE(slurp(dir / "again.png") == slurp(dir / "coverage.png"))
      << "swath render --basemap draws another picture";
  const GeographicLib::LocalCartesian frame(kMarks[0].lat_deg, kMarks[0].lon_deg, 0);
  const auto local = [&frame](double lat, double lon) {
    double x, y, z;
    frame.Forward(lat, lon, 0, x, y, z);
    return std::array<double, 2>{x, y};
  };
  // Least squares for px = ox + s e, py = oy - s n over the three squares.
  std::array<std::array<double, 2>, 3> en, px;
  for (std::size_t k = 0; k < 3; ++k) {
    en[k] = local(kMarks[k].lat_deg, kMarks[k].lon_deg);
    px[k] = square_in_picture(image, blank, kMarks[k].channel, 20);
    ASSERT_FALSE(std::isnan(px[k][0])) << "square " << k << " not in coverage.png";
  }
  double me = 0, mn = 0, mx = 0, my = 0;
  for (std::size_t k = 0; k < 3; ++k)
    me += en[k][0] / 3, mn += en[k][1] / 3, mx += px[k][0] / 3, my += px[k][1] / 3;
  double num = 0, den = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    num += (en[k][0] - me) * (px[k][0] - mx) - (en[k][1] - mn) * (px[k][1] - my);
    den += (en[k][0] - me) * (en[k][0] - me) + (en[k][1] - mn) * (en[k][1] - mn);
  }
  const double s = num / den, ox = mx - s * me, oy = my + s * mn;
  ASSERT_GT(s, 0.5);  // px per m: the meadow fills most of the picture
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(px[k][0], ox + s * en[k][0], 3) << "square " << k;
    EXPECT_NEAR(px[k][1], oy - s * en[k][1], 3) << "square " << k;
  }
  // The area where the fit puts it: over a basemap its fill is see-through, so the pixels that
  // differ between the plain picture and the one over the white raster are the area's (but where
  // opaque paths and markers cover it); their bounds against the area's corners through the fit.
  double lo_x = 1e9, hi_x = -1e9, lo_y = 1e9, hi_y = -1e9;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      int diff = 0;
      for (int c = 0; c < 3; ++c)
        diff = std::max(diff, std::abs(plain.at(x, y, c) - blank.at(x, y, c)));
      if (diff <= 8) continue;
      lo_x = std::min(lo_x, x + 0.5), hi_x = std::max(hi_x, x + 0.5);
      lo_y = std::min(lo_y, y + 0.5), hi_y = std::max(hi_y, y + 0.5);
    }
  double fit_lo_x = 1e9, fit_hi_x = -1e9, fit_lo_y = 1e9, fit_hi_y = -1e9;
  const json mission = json::parse(slurp(dir / "mission.geojson"));
  for (const json& f : mission["features"])
    if (f["properties"]["role"] == "area")
      for (const json& p : f["geometry"]["coordinates"][0]) {
        const auto e = local(p[1], p[0]);
        fit_lo_x = std::min(fit_lo_x, ox + s * e[0]), fit_hi_x = std::max(fit_hi_x, ox + s * e[0]);
        fit_lo_y = std::min(fit_lo_y, oy - s * e[1]), fit_hi_y = std::max(fit_hi_y, oy - s * e[1]);
      }
  EXPECT_NEAR(lo_x, fit_lo_x, 3);
  EXPECT_NEAR(hi_x, fit_hi_x, 3);
  EXPECT_NEAR(lo_y, fit_lo_y, 3);
  EXPECT_NEAR(hi_y, fit_hi_y, 3);
}

// A raster that cannot be read, has no georeference or lies elsewhere: one sentence, exit 2,
// nothing written.
TEST(Basemap, BadRastersAreRefusedAndNothingWritten) {
  fs::create_directories(scratch_root());
  const fs::path text = scratch_root() / "not-a-raster.tif";
  std::ofstream(text) << "not a raster\n";
  const fs::path bare = scratch_root() / "bare.asc";  // an ASCII grid has no CRS without a .prj
  std::ofstream(bare) << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n";
  const fs::path far = scratch_root() / "far.tif";
  ASSERT_NO_FATAL_FAILURE(write_ortho(far));
  const std::vector<std::pair<std::string, std::string>> cases{
      {kMeadow + " --render --basemap '" + text.string() + "'", "not a raster GDAL reads"},
      {kMeadow + " --html --basemap '" + bare.string() + "'", "has no georeference"},
      {"share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --html --basemap '" +
           far.string() + "'",
       "does not overlap the plan"},
      {"share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --render --basemap '" +
           far.string() + "'",
       "does not overlap the plan"},
      {kMeadow + " --basemap '" + far.string() + "'", "give --render or --html"}};
  for (const auto& [args, says] : cases) {
    const fs::path dir = scratch("basemap-refused");
    const ShellRun plan =
        run("'" SWATH_BINARY "' plan " + args + " -o '" + dir.string() + "' 2>&1");
    EXPECT_EQ(plan.exit_code, 2) << args << "\n" << plan.out;
    EXPECT_NE(plan.out.find(says), std::string::npos) << plan.out;
    EXPECT_EQ(std::count(plan.out.begin(), plan.out.end(), '\n'), 1) << plan.out;
    EXPECT_FALSE(fs::exists(dir)) << args;
  }
}

}  // namespace

#include "coverage_image.hpp"

#include "map_furniture.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::apps {
namespace {

using geometry::Point2;
using nlohmann::json;
using render::Color;

const Color kArea{0.85f, 0.93f, 0.82f, 1};
const Color kOutline{0.25f, 0.45f, 0.25f, 1};
const Color kFootprint{0.15f, 0.35f, 0.85f, 0.16f};
const Color kDrone[] = {{0.85f, 0.15f, 0.1f, 1}, {0.55f, 0.1f, 0.75f, 1}, {0.95f, 0.55f, 0.0f, 1},
                        {0.0f, 0.55f, 0.55f, 1}, {0.5f, 0.35f, 0.1f, 1},  {0.9f, 0.2f, 0.6f, 1}};

Color drone_color(int drone) {
  return kDrone[(drone - 1 + 6 * 1000) % 6];
}

std::vector<Point2> ring_of(const json& coordinates, const geometry::LocalFrame& frame) {
  std::vector<Point2> ring;
  for (const json& c : coordinates)
    ring.push_back(frame.to_local({c[1].get<double>(), c[0].get<double>(), 0}));
  if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  return ring;
}

std::string duration(double s) {
  const long t = std::lround(s);
  return std::to_string(t / 60) + ":" + (t % 60 < 10 ? "0" : "") + std::to_string(t % 60);
}

}  // namespace

CoverageImage coverage_image(const std::string& geojson_text, const std::string& summary_text,
                             int width_px, int height_px, const std::string& source) {
  json g, s;
  try {
    g = json::parse(geojson_text);
    s = json::parse(summary_text);
  } catch (const json::exception& e) {
    throw base::InputError(source + ": not a swath plan (" + std::string(e.what()) + ")");
  }
  if (!g.contains("features") || !s.contains("drones"))
    throw base::InputError(
        source + ": not a swath plan (mission.geojson needs features, summary.json drones)");
  // A local frame at the first area vertex: drawing in metres, north up.
  const json* area = nullptr;
  for (const json& f : g["features"])
    if (f["properties"]["role"] == "area" && !area) area = &f;
  if (!area) throw base::InputError(source + ": mission.geojson has no area");
  const json& first = (*area)["geometry"]["coordinates"][0][0];
  const geometry::LocalFrame frame({first[1].get<double>(), first[0].get<double>(), 0});

  CoverageImage out;
  render::Scene& scene = out.scene;
  MapBounds bounds;
  auto grow = [&](Point2 p) { bounds.add(p); };
  for (const json& f : g["features"]) {
    const std::string role = f["properties"]["role"];
    const json& geom = f["geometry"];
    if (role == "area") {
      render::FilledPolygon p{{}, kArea, kOutline, 1.5};
      for (const json& ring : geom["coordinates"]) {
        p.rings.push_back(ring_of(ring, frame));
        for (const Point2& q : p.rings.back()) grow(q);
      }
      scene.polygons.push_back(p);
    } else if (role == "region") {
      render::FilledPolygon p{{ring_of(geom["coordinates"][0], frame)},
                              {0, 0, 0, 0},
                              drone_color(f["properties"]["drone"]),
                              2};
      scene.polygons.push_back(p);
    } else if (role == "sweep") {
      const auto line = ring_of(geom["coordinates"], frame);
      if (line.size() == 2)
        scene.strips.push_back(
            {line[0], line[1], f["properties"]["footprint_width_m"].get<double>(), kFootprint});
    } else if (role == "path") {
      std::vector<Point2> pts;
      for (const json& c : geom["coordinates"])
        pts.push_back(frame.to_local({c[1].get<double>(), c[0].get<double>(), 0}));
      for (const Point2& q : pts) grow(q);
      scene.polylines.push_back({pts, 2.0, drone_color(f["properties"]["drone"]), 90});
    } else if (role == "home") {
      const Point2 h = frame.to_local(
          {geom["coordinates"][1].get<double>(), geom["coordinates"][0].get<double>(), 0});
      grow(h);
      scene.markers.push_back({h, 12, {0.1f, 0.1f, 0.1f, 1}, render::MarkerShape::triangle});
    }
  }
  // Room for the title lines above and the scale bar and legend below.
  const int text_h = std::max(12, height_px / 50);
  const int drones = static_cast<int>(s["drones"].size());
  const int title_lines = 1 + std::min(drones, 6);
  out.view = render::fit(bounds.lo, bounds.hi, width_px, height_px,
                         std::max(height_px / 12, title_lines * (text_h + 6) + 16));
  const render::View& v = out.view;

  // Title: coverage, lines, each drone's path and time.
  const json& c = s["coverage"];
  const std::string title = "coverage " +
                            base::fixed_text(100 * c["covered_fraction"].get<double>(), 2) +
                            " %   " + std::to_string(s["sweep"]["lines"].get<int>()) + " lines";
  scene.labels.push_back({10, text_h + 8, title, double(text_h), {0.1f, 0.1f, 0.1f, 1}});
  int line = 2;
  for (const json& d : s["drones"]) {
    if (line > title_lines) break;
    const std::string text = "drone " + std::to_string(d["drone"].get<int>()) + ": " +
                             base::fixed_text(d["path_length_m"].get<double>() / 1000, 2) +
                             " km, " + duration(d["flight_time_s"].get<double>());
    scene.labels.push_back(
        {10, line++ * (text_h + 6) + 8, text, double(text_h), drone_color(d["drone"].get<int>())});
  }

  const ScaleBar bar = add_scale_bar(scene, v, width_px, height_px, text_h);
  out.scale_bar_m = bar.length_m;
  out.scale_bar_px = bar.length_px;
  out.scale_bar_start_px = bar.start_px;
  add_north_arrow(scene, width_px, 2.5 * text_h + 20, text_h);

  // Legend, bottom right: swatch and name per entry.
  std::vector<std::pair<Color, std::string>> legend{
      {kArea, "area"}, {{0.15f, 0.35f, 0.85f, 0.35f}, "camera footprint"}};
  for (const json& d : s["drones"]) {
    const int id = d["drone"].get<int>();
    std::string name = "drone ";
    name += std::to_string(id);
    if (d.contains("name") && d["name"].get<std::string>() != "drone-" + std::to_string(id)) {
      name += ' ';
      name += d["name"].get<std::string>();
    }
    legend.push_back({drone_color(id), name});
  }
  double y = height_px - 20.0 - static_cast<double>(legend.size() - 1) * (text_h + 8.0);
  std::size_t longest = 0;
  for (const auto& entry : legend) longest = std::max(longest, entry.second.size());
  // Hershey simplex glyphs are at most about 0.7 of the text height wide.
  const double x = width_px - 16.0 - text_h - 6 - 0.72 * text_h * static_cast<double>(longest);
  for (const auto& [color, name] : legend) {
    scene.screen_polygons.push_back(
        {{{{x, y - text_h}, {x + text_h, y - text_h}, {x + text_h, y}, {x, y}}}, color});
    scene.labels.push_back({static_cast<int>(x + text_h + 6),
                            static_cast<int>(y),
                            name,
                            double(text_h),
                            {0.1f, 0.1f, 0.1f, 1}});
    y += text_h + 8;
  }
  return out;
}

}  // namespace swath::apps

#include "coverage_image.hpp"

#include "map_furniture.hpp"

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::apps {
namespace {

using geometry::Point2;
using render::Color;

const Color kArea{0.85f, 0.93f, 0.82f, 1};
const Color kOutline{0.25f, 0.45f, 0.25f, 1};
const Color kFootprint{0.15f, 0.35f, 0.85f, 0.16f};
const Color kDrone[] = {{0.85f, 0.15f, 0.1f, 1}, {0.55f, 0.1f, 0.75f, 1}, {0.95f, 0.55f, 0.0f, 1},
                        {0.0f, 0.55f, 0.55f, 1}, {0.5f, 0.35f, 0.1f, 1},  {0.9f, 0.2f, 0.6f, 1}};

Color drone_color(int drone) {
  return kDrone[(drone - 1 + 6 * 1000) % 6];
}

std::vector<Point2> local(const std::vector<geometry::GeoPoint>& points,
                          const geometry::LocalFrame& frame) {
  std::vector<Point2> out;
  for (const geometry::GeoPoint& g : points) out.push_back(frame.to_local(g));
  return out;
}

std::string duration(double s) {
  const long t = std::lround(s);
  return std::to_string(t / 60) + ":" + (t % 60 < 10 ? "0" : "") + std::to_string(t % 60);
}

}  // namespace

CoverageImage coverage_image(const planning::PlanFeatures& features,
                             const planning::PlanFigures& figures, int width_px, int height_px) {
  // A local frame at the first area vertex: drawing in metres, north up.
  const geometry::LocalFrame frame(features.area.front().front());
  CoverageImage out;
  render::Scene& scene = out.scene;
  MapBounds bounds;
  auto grow = [&](const std::vector<Point2>& points) {
    for (const Point2& p : points) bounds.add(p);
  };
  render::FilledPolygon area{{}, kArea, kOutline, 1.5};
  for (const auto& ring : features.area) {
    area.rings.push_back(local(ring, frame));
    grow(area.rings.back());
  }
  scene.polygons.push_back(area);
  for (const auto& piece : features.area_pieces) {
    render::FilledPolygon p{{local(piece, frame)}, kArea, kOutline, 1.5};
    grow(p.rings.back());
    scene.polygons.push_back(p);
  }
  for (const auto& r : features.regions)
    scene.polygons.push_back({{local(r.ring, frame)}, {0, 0, 0, 0}, drone_color(r.drone), 2});
  for (const auto& sw : features.sweeps)
    scene.strips.push_back(
        {frame.to_local(sw.start), frame.to_local(sw.end), sw.footprint_width_m, kFootprint});
  for (const auto& path : features.paths) {
    const std::vector<Point2> points = local(path.points, frame);
    grow(points);
    scene.polylines.push_back({points, 2.0, drone_color(path.drone), 90});
  }
  const Point2 home = frame.to_local(features.home);
  grow({home});
  scene.markers.push_back({home, 12, {0.1f, 0.1f, 0.1f, 1}, render::MarkerShape::triangle});
  // Room for the title lines above and the scale bar and legend below.
  const int text_h = std::max(12, height_px / 50);
  const int drones = static_cast<int>(figures.drones.size());
  const int title_lines = 1 + std::min(drones, 6);
  out.view = render::fit(bounds.lo, bounds.hi, width_px, height_px,
                         std::max(height_px / 12, title_lines * (text_h + 6) + 16));
  const render::View& v = out.view;

  // Title: coverage, lines, each drone's path and time.
  const std::string title = "coverage " + base::fixed_text(100 * figures.covered_fraction, 2) +
                            " %   " + std::to_string(figures.lines) + " lines";
  scene.labels.push_back({10, text_h + 8, title, double(text_h), {0.1f, 0.1f, 0.1f, 1}});
  int line = 2;
  for (const auto& d : figures.drones) {
    if (line > title_lines) break;
    const std::string text = "drone " + std::to_string(d.drone) + ": " +
                             base::fixed_text(d.path_length_m / 1000, 2) + " km, " +
                             duration(d.flight_time_s);
    scene.labels.push_back(
        {10, line++ * (text_h + 6) + 8, text, double(text_h), drone_color(d.drone)});
  }

  const ScaleBar bar = add_scale_bar(scene, v, width_px, height_px, text_h);
  out.scale_bar_m = bar.length_m;
  out.scale_bar_px = bar.length_px;
  out.scale_bar_start_px = bar.start_px;
  add_north_arrow(scene, width_px, 2.5 * text_h + 20, text_h);

  // Legend, bottom right: swatch and name per entry.
  std::vector<std::pair<Color, std::string>> legend{
      {kArea, "area"}, {{0.15f, 0.35f, 0.85f, 0.35f}, "camera footprint"}};
  for (const auto& d : figures.drones) {
    std::string name = "drone ";
    name += std::to_string(d.drone);
    if (!d.name.empty() && d.name != "drone-" + std::to_string(d.drone)) {
      name += ' ';
      name += d.name;
    }
    legend.push_back({drone_color(d.drone), name});
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

#include "fleet_images.hpp"

#include <algorithm>
#include <cmath>

#include "map_furniture.hpp"
#include "swath/base/number_text.hpp"
#include "swath/render/legend.hpp"

namespace swath::apps {

using geometry::Point2;
using render::Color;

namespace {
const Color kInk{0.1f, 0.1f, 0.1f, 1};
const Color kFence{0.35f, 0.55f, 0.3f, 1};
const Color kWorld{0.55f, 0.45f, 0.35f, 1};
const Color kSensed{0.1f, 0.1f, 0.1f, 1};
const Color kCancelled{0.6f, 0.6f, 0.6f, 1};
}  // namespace

render::Color drone_color(std::size_t i) {
  static const Color colors[] = {{0.1f, 0.3f, 0.85f, 1},  {0.9f, 0.45f, 0.0f, 1},
                                 {0.55f, 0.1f, 0.65f, 1}, {0.0f, 0.6f, 0.6f, 1},
                                 {0.8f, 0.1f, 0.3f, 1},   {0.4f, 0.6f, 0.1f, 1}};
  return colors[i % std::size(colors)];
}

render::Color mode_color(const std::string& mode) {
  if (mode == "flying") return {0.2f, 0.45f, 0.9f, 1};
  if (mode == "positioning") return {0.45f, 0.8f, 0.95f, 1};  // speculation: to a forecast
  if (mode == "acting") return {0.1f, 0.65f, 0.25f, 1};
  if (mode == "hovering") return {0.75f, 0.75f, 0.75f, 1};
  if (mode == "held") return {0.95f, 0.8f, 0.2f, 1};
  if (mode == "returning") return {0.55f, 0.35f, 0.8f, 1};
  if (mode == "charging") return {0.95f, 0.55f, 0.1f, 1};
  if (mode == "lost") return {0.85f, 0.1f, 0.1f, 1};
  if (mode == "unreachable") return {0.4f, 0.1f, 0.1f, 1};
  return {1, 1, 1, 1};  // landed: the background
}

FleetPicture tracks_picture(const worlds::BaseWorld& world, const fleet::RunRecord& record,
                            int width_px, int height_px) {
  FleetPicture out;
  render::Scene& scene = out.scene;
  MapBounds box;
  for (const auto& p : world.fence()) box.add({p[0], p[1]});
  for (const auto& d : record.drones)
    for (const auto& s : d.track) box.add({s[1], s[2]});
  box.add({world.start().x, world.start().y});
  // The world's own layer.
  if (const auto* road = dynamic_cast<const worlds::RoadWorld*>(&world)) {
    render::Polyline line;
    for (const auto& p : road->road_m) line.points.push_back({p[0], p[1]}), box.add({p[0], p[1]});
    line.width_px = 6;
    line.color = {0.8f, 0.75f, 0.65f, 1};
    scene.polylines.push_back(line);
  } else if (const auto* hot = dynamic_cast<const worlds::HotspotWorld*>(&world)) {
    box.add({hot->source_m.x, hot->source_m.y});
    scene.markers.push_back({{hot->source_m.x, hot->source_m.y},
                             18,
                             {0.85f, 0.1f, 0.1f, 1},
                             render::MarkerShape::triangle});
  } else if (const auto* sites = dynamic_cast<const worlds::SitesWorld*>(&world)) {
    for (const auto& [name, p] : sites->sites) {
      box.add({p.x, p.y});
      scene.markers.push_back({{p.x, p.y}, 14, kWorld, render::MarkerShape::square});
    }
  } else if (const auto* walk = dynamic_cast<const worlds::TrackingWorld*>(&world)) {
    render::Polyline line;
    for (double t = 0; t <= walk->duration_s; t += 1.0) {
      const auto p = walk->walker_at(t);
      line.points.push_back({p[0], p[1]});
      box.add({p[0], p[1]});
    }
    line.width_px = 5;
    line.color = {0.8f, 0.75f, 0.65f, 1};
    scene.polylines.push_back(line);
  } else if (const auto* rf = dynamic_cast<const worlds::RfFieldWorld*>(&world)) {
    for (const auto& a : rf->access_points) {
      box.add({a.x_m, a.y_m});
      scene.markers.push_back({{a.x_m, a.y_m}, 16, kWorld, render::MarkerShape::triangle});
    }
  }
  if (box.lo.x > box.hi.x) box.add({0, 0});
  box.add({box.lo.x - 5, box.lo.y - 5});
  box.add({box.hi.x + 5, box.hi.y + 5});
  out.view = render::fit(box.lo, box.hi, width_px, height_px, 60);
  if (!world.fence().empty()) {
    render::Polyline f;
    for (const auto& p : world.fence()) f.points.push_back({p[0], p[1]});
    f.points.push_back(f.points.front());
    f.width_px = 2;
    f.color = kFence;
    scene.polylines.push_back(f);
  }
  for (std::size_t i = 0; i < record.drones.size(); ++i) {
    render::Polyline line;
    for (const auto& s : record.drones[i].track) {
      const Point2 p{s[1], s[2]};
      if (line.points.empty() ||
          std::hypot(p.x - line.points.back().x, p.y - line.points.back().y) > 1e-6)
        line.points.push_back(p);
    }
    line.width_px = 2.5;
    line.color = drone_color(i);
    line.arrow_every_px = 120;
    if (line.points.size() >= 2) scene.polylines.push_back(line);
    if (!record.drones[i].track.empty())
      scene.markers.push_back(
          {{record.drones[i].track.front()[1], record.drones[i].track.front()[2]},
           12,
           drone_color(i),
           render::MarkerShape::square});
  }
  for (const auto& s : record.served) scene.markers.push_back({{s[1], s[2]}, 7, kSensed});
  for (const auto& s : record.cancelled) scene.markers.push_back({{s[1], s[2]}, 7, kCancelled});
  const int text_h = std::max(12, height_px / 50);
  add_scale_bar(scene, out.view, width_px, height_px, text_h);
  add_north_arrow(scene, width_px, 40.0, text_h);
  // The legend: each drone's colour and name (its home the square at the track's start), then
  // the markers; bottom right, clear of the north arrow and the scale bar.
  std::vector<render::LegendEntry> legend;
  for (std::size_t i = 0; i < record.drones.size(); ++i)
    legend.push_back({record.drones[i].name, render::SwatchKind::line, drone_color(i)});
  if (!record.served.empty()) legend.push_back({"sensed", render::SwatchKind::marker, kSensed});
  if (!record.cancelled.empty())
    legend.push_back({"cancelled", render::SwatchKind::marker, kCancelled});
  render::add_legend(scene, legend, {8.0, 8.0, width_px - 8.0, height_px - 8.0},
                     render::Corner::bottom_right, 0.8 * text_h);
  return out;
}

double gantt_x_px(double t_s, double end_s, int width_px) {
  return 120.0 + (width_px - 150.0) * (end_s > 0 ? t_s / end_s : 0.0);
}

double gantt_row_centre_px(std::size_t drone, std::size_t drones, int height_px) {
  const double row = (height_px - 80.0) / static_cast<double>(std::max<std::size_t>(1, drones));
  return 40.0 + row * (static_cast<double>(drone) + 0.5);
}

FleetPicture gantt_picture(const fleet::RunRecord& record, int width_px, int height_px) {
  FleetPicture out;
  out.view = render::View{1.0, 0.0, 0.0, width_px, height_px};
  render::Scene& scene = out.scene;
  const std::size_t n = record.drones.size();
  const double row = (height_px - 80.0) / static_cast<double>(std::max<std::size_t>(1, n));
  const int text_h = std::max(12, static_cast<int>(std::min(row * 0.4, 18.0)));
  for (std::size_t i = 0; i < n; ++i) {
    const double c = gantt_row_centre_px(i, n, height_px), h = row * 0.35;
    for (const auto& s : record.drones[i].spans) {
      if (s.mode == "landed") continue;
      const double x0 = gantt_x_px(s.t0_s, record.end_s, width_px);
      const double x1 = std::max(x0 + 1.0, gantt_x_px(s.t1_s, record.end_s, width_px));
      scene.screen_polygons.push_back(
          {{{{x0, c - h}, {x1, c - h}, {x1, c + h}, {x0, c + h}}}, mode_color(s.mode)});
    }
    scene.labels.push_back({10, static_cast<int>(c + text_h / 3), record.drones[i].name,
                            static_cast<double>(text_h), drone_color(i)});
  }
  // Time axis with ticks at round seconds.
  const double y = height_px - 34.0;
  scene.screen_polylines.push_back({{{120, y}, {width_px - 30.0, y}}, 1.5, kInk, 0});
  // About six ticks, fewer when their labels would touch (narrow pictures).
  const double label_px =
      render::text_extent(base::fixed_text(record.end_s, 0) + " s", text_h).width_px + 16;
  // At least 1 px of axis: in a picture narrower than 150 px the step must still grow to an end.
  const double axis_px = std::max(width_px - 150.0, 1.0);
  const double ticks = std::clamp(std::floor(axis_px / label_px), 1.0, 6.0);
  double step = nice_length(std::max(1.0, record.end_s / ticks));
  while (step / std::max(record.end_s, 1e-9) * axis_px < label_px) step = nice_length(step * 2.5);
  for (double t = 0; t <= record.end_s + 1e-9; t += step) {
    const double x = gantt_x_px(t, record.end_s, width_px);
    scene.screen_polylines.push_back({{{x, y}, {x, y + 6}}, 1.5, kInk, 0});
    const std::string label = base::fixed_text(t, 0) + " s";
    const double right = width_px - 4 - render::text_extent(label, text_h).width_px;
    scene.labels.push_back({static_cast<int>(std::min(x - 10, right)),
                            static_cast<int>(y) + 8 + text_h, label, static_cast<double>(text_h),
                            kInk});
  }
  // Legend along the top: beside the names' column when it fits, else from the left edge with
  // its text smaller (down to 10 px), else on more lines (it was cut off at 1,200 px).
  const std::vector<const char*> modes{"flying",    "positioning", "acting", "hovering",   "held",
                                       "returning", "charging",    "lost",   "unreachable"};
  int legend_h = text_h;
  auto item_width = [&](const char* m) { return 30 + render::text_extent(m, legend_h).width_px; };
  auto legend_width = [&] {
    double w = 0;
    for (const char* m : modes) w += item_width(m);
    return w;
  };
  while (legend_h > 10 && legend_width() > width_px - 20.0) --legend_h;
  const double left = legend_width() <= width_px - 130.0 ? 120.0 : 10.0;
  double x = left, top = 10;
  for (const char* m : modes) {
    if (x > left && x + item_width(m) - 12 > width_px - 10.0) x = left, top += legend_h + 6;
    scene.screen_polygons.push_back(
        {{{{x, top}, {x + 14, top}, {x + 14, top + 14}, {x, top + 14}}}, mode_color(m)});
    scene.labels.push_back({static_cast<int>(x) + 18, static_cast<int>(top) + 13, m,
                            static_cast<double>(legend_h), kInk});
    x += item_width(m);
  }
  return out;
}

}  // namespace swath::apps

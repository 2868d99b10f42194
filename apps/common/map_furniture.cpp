#include "map_furniture.hpp"

#include <cmath>
#include <cstdio>

#include "swath/base/input_error.hpp"

#include "swath/base/number_text.hpp"

namespace swath::apps {

using geometry::Point2;

std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), " %d x %d %c", &w, &h, &tail) != 2 || w < 64 || h < 64 ||
      w > 5000 || h > 5000)
    throw base::InputError("--size '" + text +
                           "': expected WxH pixels, each 64 to 5000, e.g. 1600x1200");
  return {w, h};
}

double nice_length(double metres) {
  const double p = std::pow(10.0, std::floor(std::log10(metres)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= metres) return m * p;
  return p;
}

ScaleBar add_scale_bar(render::Scene& scene, const render::View& view, int width_px, int height_px,
                       int text_h) {
  ScaleBar bar;
  bar.length_m = nice_length(width_px / 4.0 / view.px_per_m);
  bar.length_px = bar.length_m * view.px_per_m;
  bar.start_px = {20, height_px - 20.0};
  const Point2 a = bar.start_px, b = a + Point2{bar.length_px, 0};
  scene.screen_polylines.push_back({{a, b}, 4, {0.1f, 0.1f, 0.1f, 1}});
  scene.labels.push_back({static_cast<int>(a.x),
                          static_cast<int>(a.y) - 8,
                          base::fixed_text(bar.length_m, 0) + " m",
                          double(text_h),
                          {0.1f, 0.1f, 0.1f, 1}});
  return bar;
}

void add_north_arrow(render::Scene& scene, int width_px, double y_px, int text_h) {
  const double nx = width_px - 30.0, ny = y_px;
  scene.screen_polygons.push_back(
      {{{{nx, ny - 18}, {nx + 8, ny + 6}, {nx, ny}, {nx - 8, ny + 6}}}, {0.1f, 0.1f, 0.1f, 1}});
  scene.labels.push_back({static_cast<int>(nx) - text_h / 3,
                          static_cast<int>(ny) + text_h + 10,
                          "N",
                          double(text_h),
                          {0.1f, 0.1f, 0.1f, 1}});
}

}  // namespace swath::apps

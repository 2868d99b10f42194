#include "basemap.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "swath/base/input_error.hpp"
#include "swath/geometry/imagery.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::apps {
namespace {

std::string no_overlap(const std::string& path, const std::string& what) {
  return path + ": the raster does not overlap the plan (nothing of it lies within " + what +
         "); is it the right file, with the right CRS?";
}

// Web Mercator (EPSG:3857) on the sphere Leaflet uses, metres.
constexpr double kEarth_m = 6'378'137.0;
constexpr double kDeg = std::numbers::pi / 180;

double mercator_y_m(double lat_deg) {
  return kEarth_m * std::log(std::tan(std::numbers::pi / 4 + lat_deg * kDeg / 2));
}
double latitude_deg(double y_m) {
  return (2 * std::atan(std::exp(y_m / kEarth_m)) - std::numbers::pi / 2) / kDeg;
}

struct GeoBounds {
  double west = 1e9, east = -1e9, south = 1e9, north = -1e9;
  void add(double lon, double lat) {
    west = std::min(west, lon), east = std::max(east, lon);
    south = std::min(south, lat), north = std::max(north, lat);
  }
};

// Every position of a GeoJSON geometry's coordinates, however deeply nested.
void add_positions(const nlohmann::json& c, GeoBounds& b) {
  if (!c.is_array() || c.empty()) return;
  if (c[0].is_number() && c.size() >= 2 && c[1].is_number()) {
    b.add(c[0].get<double>(), c[1].get<double>());
    return;
  }
  for (const auto& e : c) add_positions(e, b);
}

GeoBounds mission_bounds(const std::string& mission_geojson) {
  GeoBounds b;
  const nlohmann::json j = nlohmann::json::parse(mission_geojson, nullptr, false);
  if (j.is_object() && j.contains("features") && j["features"].is_array())
    for (const auto& f : j["features"])
      if (f.is_object() && f.contains("geometry") && f["geometry"].is_object())
        add_positions(f["geometry"].value("coordinates", nlohmann::json()), b);
  return b;
}

}  // namespace

void put_basemap_under(CoverageImage& image, const std::string& path) {
  const render::View& v = image.view;
  const geometry::LocalFrame frame(image.frame_origin);
  const geometry::Imagery picture =
      geometry::imagery(path, v.width_px, v.height_px, [&](double x_px, double y_px) {
        return frame.to_geo({v.origin_x_m + x_px / v.px_per_m, v.origin_y_m - y_px / v.px_per_m});
      });
  if (picture.covered_px == 0) throw base::InputError(no_overlap(path, "the plan's picture"));
  render::Backdrop& b = image.scene.backdrop;
  b.width_px = v.width_px, b.height_px = v.height_px;
  b.rgb.resize(3 * static_cast<std::size_t>(v.width_px) * v.height_px);
  for (std::size_t k = 0, n = b.rgb.size() / 3; k < n; ++k) {
    const double a = picture.rgba[4 * k + 3] / 255.0;  // over white
    for (std::size_t c = 0; c < 3; ++c)
      b.rgb[3 * k + c] =
          static_cast<std::uint8_t>(std::lround(picture.rgba[4 * k + c] * a + 255 * (1 - a)));
  }
  // The title, scale bar and north arrow are ink drawn on the background: white behind them.
  const double text_h = std::max(12, v.height_px / 50);  // as coverage_image() sizes them
  const double bar_x = image.scale_bar_start_px.x, bar_y = image.scale_bar_start_px.y;
  const render::PixelBox furniture[] = {
      {0, 0, image.title_box.right_px + 6, image.title_box.bottom_px + 4},
      {bar_x - 8, bar_y - 2.5 * text_h - 8, bar_x + image.scale_bar_px + 4 * text_h, bar_y + 8},
      {v.width_px - 5 * text_h, 0, double(v.width_px), 6 * text_h + 30}};
  for (const render::PixelBox& box : furniture)
    for (int y = std::max(0, int(box.top_px)); y < std::min(v.height_px, int(box.bottom_px)); ++y)
      for (int x = std::max(0, int(box.left_px)); x < std::min(v.width_px, int(box.right_px)); ++x)
        for (std::size_t c = 0; c < 3; ++c)
          b.rgb[3 * (static_cast<std::size_t>(y) * v.width_px + x) + c] = 255;
  // The area's fill would hide the imagery: the ground shows through it.
  for (render::FilledPolygon& p : image.scene.polygons)
    if (p.fill.a >= 1) p.fill.a = 0.3f;
}

namespace {

// The XYZ tiles of zoom z over Mercator bounds [x0, x1] x [y0, y1] (metres): columns and rows.
struct TileRange {
  int z = 0, x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // inclusive; y from the north
  int count() const { return (x1 - x0 + 1) * (y1 - y0 + 1); }
};
constexpr double kWorld_m = 2 * std::numbers::pi * kEarth_m;  // Web Mercator's span

double tile_px_m(int z) {
  return kWorld_m / 256 / std::ldexp(1.0, z);
}

TileRange tile_range(int z, double x0, double x1, double y0, double y1) {
  const double tile_m = 256 * tile_px_m(z);
  const int last = static_cast<int>(std::ldexp(1.0, z)) - 1;
  const auto index = [&](double m) {
    return std::clamp(static_cast<int>(std::floor(m / tile_m)), 0, last);
  };
  return {z, index(x0 + kWorld_m / 2), index(x1 + kWorld_m / 2), index(kWorld_m / 2 - y1),
          index(kWorld_m / 2 - y0)};
}

// The tiles of one level that show something of the raster: one picture of the whole range (one
// read of the raster's window), cut into 256 px tiles.
void add_level(const TileRange& r, const std::string& path, std::vector<web::MapTile>& tiles) {
  const int w = 256 * (r.x1 - r.x0 + 1), h = 256 * (r.y1 - r.y0 + 1);
  const double px_m = tile_px_m(r.z);
  const double left_m = r.x0 * 256 * px_m - kWorld_m / 2, top_m = kWorld_m / 2 - r.y0 * 256 * px_m;
  const geometry::Imagery level = geometry::imagery(path, w, h, [&](double x_px, double y_px) {
    return geometry::GeoPoint{latitude_deg(top_m - y_px * px_m),
                              (left_m + x_px * px_m) / kEarth_m / kDeg};
  });
  for (int ty = r.y0; ty <= r.y1; ++ty)
    for (int tx = r.x0; tx <= r.x1; ++tx) {
      geometry::Imagery tile;
      tile.width = tile.height = 256;
      tile.rgba.resize(4 * 256 * 256);
      for (int j = 0; j < 256; ++j) {
        const std::size_t from = 4 * ((static_cast<std::size_t>(ty - r.y0) * 256 + j) * w +
                                      static_cast<std::size_t>(tx - r.x0) * 256);
        std::copy_n(level.rgba.begin() + static_cast<std::ptrdiff_t>(from), 4 * 256,
                    tile.rgba.begin() + 4 * 256 * j);
      }
      for (std::size_t k = 3; k < tile.rgba.size(); k += 4) tile.covered_px += tile.rgba[k] > 0;
      if (tile.covered_px > 0) tiles.push_back({r.z, tx, ty, geometry::imagery_png(tile)});
    }
}

}  // namespace

BasemapZooms basemap_zooms(double span_m, double raster_px_m, int budget_tiles,
                           const std::function<int(int z)>& tiles_at) {
  BasemapZooms out;
  // Coarsest: the plan's bounds about a window's width (1,024 px) across.
  out.min_zoom = std::clamp(static_cast<int>(std::floor(std::log2(4 * kWorld_m / span_m))), 0,
                            kBasemapMaxZoom);
  // Finest: a tile pixel no larger than the raster's (in Mercator metres at the plan).
  out.native_zoom =
      std::clamp(static_cast<int>(std::ceil(std::log2(kWorld_m / 256 / raster_px_m) - 1e-9)),
                 out.min_zoom, kBasemapMaxZoom);
  int total = tiles_at(out.min_zoom);
  out.max_zoom = out.min_zoom;
  while (out.max_zoom < out.native_zoom && total + tiles_at(out.max_zoom + 1) <= budget_tiles)
    total += tiles_at(++out.max_zoom);
  return out;
}

web::MapTiles page_basemap(const std::string& mission_geojson, const std::string& path) {
  const GeoBounds plan = mission_bounds(mission_geojson);
  if (plan.west > plan.east) throw base::InputError(no_overlap(path, "an empty plan"));
  // In Web Mercator metres, a quarter of the span more on each side (at least 50 m on the ground).
  const double scale = 1 / std::cos((plan.south + plan.north) / 2 * kDeg);  // Mercator m per m
  double x0 = kEarth_m * plan.west * kDeg, x1 = kEarth_m * plan.east * kDeg;
  double y0 = mercator_y_m(plan.south), y1 = mercator_y_m(plan.north);
  const double margin_x = std::max(0.25 * (x1 - x0), 50 * scale);
  const double margin_y = std::max(0.25 * (y1 - y0), 50 * scale);
  x0 -= margin_x, x1 += margin_x, y0 -= margin_y, y1 += margin_y;
  const double raster_px_m = std::max(geometry::imagery_pixel_m(path), 1e-3);
  const BasemapZooms zooms =
      basemap_zooms(std::max(x1 - x0, y1 - y0), raster_px_m * scale, kBasemapBudgetTiles,
                    [&](int z) { return tile_range(z, x0, x1, y0, y1).count(); });
  web::MapTiles out;
  out.min_zoom = zooms.min_zoom, out.max_zoom = zooms.max_zoom;
  out.capped = zooms.max_zoom < zooms.native_zoom;
  out.finest_px_m = std::round(tile_px_m(zooms.max_zoom) / scale * 100) / 100;
  out.raster_px_m = std::round(raster_px_m * 100) / 100;
  out.south_deg = latitude_deg(y0), out.north_deg = latitude_deg(y1);
  out.west_deg = x0 / kEarth_m / kDeg, out.east_deg = x1 / kEarth_m / kDeg;
  for (int z = zooms.min_zoom; z <= zooms.max_zoom; ++z)
    add_level(tile_range(z, x0, x1, y0, y1), path, out.tiles);
  if (out.tiles.empty()) throw base::InputError(no_overlap(path, "the plan's bounds"));
  return out;
}

}  // namespace swath::apps

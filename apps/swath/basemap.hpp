#pragma once
// --basemap FILE: the user's own raster (an orthophoto, any CRS GDAL knows) behind the plan, in
// coverage.png's local frame and in plan.html's Web Mercator (docs/swath-plan.md).

#include <functional>
#include <string>

#include "coverage_image.hpp"
#include "swath/web/plan_page.hpp"

namespace swath::apps {

/// plan.html's basemap holds at most this many 256 px tiles over all its zoom levels (8 Mpx; a
/// photograph's PNG is some bytes a pixel, base64 a third more): finer levels that would pass it
/// are left out, and the map scales up the finest level kept (docs/swath-plan.md).
inline constexpr int kBasemapBudgetTiles = 128;
/// The finest zoom level made (about 4 cm a pixel at the equator).
inline constexpr int kBasemapMaxZoom = 22;

struct BasemapZooms {
  int min_zoom = 0;     ///< the plan's bounds about 1,024 px across
  int max_zoom = 0;     ///< the finest level within the budget
  int native_zoom = 0;  ///< the first level whose pixel is no larger than the raster's
};

/// The zoom levels of the page's tiles: from the level where `span_m` (the bounds' larger side,
/// Web Mercator metres) is about 1,024 px, to the raster's own pixel (`raster_px_m`, Mercator
/// metres), as far as the tiles (`tiles_at(z)` at level z, summed) stay within `budget_tiles`.
BasemapZooms basemap_zooms(double span_m, double raster_px_m, int budget_tiles,
                           const std::function<int(int z)>& tiles_at);

/// Draws the raster under the picture (white where it has no data) and makes the area's opaque
/// fill see-through. Throws InputError when the raster cannot be read, has no georeference or
/// shows nothing within the picture.
void put_basemap_under(CoverageImage& image, const std::string& path);

/// The raster as Web Mercator tiles (basemap_zooms's levels, kBasemapBudgetTiles) over the
/// bounds of every position in mission.geojson, a quarter of their span more on each side. Throws
/// InputError as put_basemap_under, "nothing within" being the plan's bounds.
web::MapTiles page_basemap(const std::string& mission_geojson, const std::string& path);

}  // namespace swath::apps

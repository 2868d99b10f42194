#pragma once
// --basemap FILE: the user's own raster (an orthophoto, any CRS GDAL knows) behind the plan, in
// coverage.png's local frame and in plan.html's Web Mercator (docs/swath-plan.md).

#include <string>

#include "coverage_image.hpp"
#include "swath/web/plan_page.hpp"

namespace swath::apps {

/// plan.html's basemap image is at most this many pixels a side; a finer raster is averaged down.
inline constexpr int kBasemapMaxSide_px = 2048;

/// Draws the raster under the picture (white where it has no data) and makes the area's opaque
/// fill see-through. Throws InputError when the raster cannot be read, has no georeference or
/// shows nothing within the picture.
void put_basemap_under(CoverageImage& image, const std::string& path);

/// The raster reprojected to Web Mercator over the bounds of every position in mission.geojson
/// (a quarter of their span more on each side), at the raster's own resolution up to
/// kBasemapMaxSide_px a side. Throws InputError as put_basemap_under, "nothing within" being the
/// plan's bounds.
web::MapImage page_basemap(const std::string& mission_geojson, const std::string& path);

}  // namespace swath::apps

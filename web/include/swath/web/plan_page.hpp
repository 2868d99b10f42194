#pragma once
// plan.html: one self-contained page (Leaflet, the page's script and the plan's files inlined)
// that shows a plan on a map. The page reads the files exactly as swath wrote them.

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace swath::web {

/// One 256 px tile of the XYZ (slippy map) scheme in Web Mercator: zoom z, column x from the
/// antimeridian eastwards, row y from the north.
struct MapTile {
  int z = 0, x = 0, y = 0;
  std::string png;  ///< PNG bytes; inlined as a data: address
};

/// The user's imagery as tiles at zoom levels min_zoom to max_zoom, between the bounds; tiles
/// that show nothing of the raster are left out.
struct MapTiles {
  int min_zoom = 0, max_zoom = 0;
  double south_deg = 0, west_deg = 0, north_deg = 0, east_deg = 0;
  double finest_px_m = 0;  ///< a pixel of max_zoom's tiles on the ground at the plan, metres
  double raster_px_m = 0;  ///< the raster's own pixel on the ground, metres
  bool capped = false;     ///< finer levels were left out to keep the page's size
  std::vector<MapTile> tiles;
};

struct PlanPage {
  std::string title;  ///< the page's title and heading, e.g. the plan directory
  /// The plan's files by name (mission.geojson, summary.json, photos.csv, waypoints.csv and the
  /// flights' .plan files), their text as written.
  std::vector<std::pair<std::string, std::string>> files;
  /// An XYZ tile template ({z}, {x}, {y}, optional {s}) of http(s) tiles behind the plan, or empty:
  /// no basemap, and the page fetches nothing at all (its Content-Security-Policy forbids it).
  std::string basemap_url;
  /// The user's own imagery behind the plan (--basemap), inlined: the page still fetches nothing.
  std::optional<MapTiles> basemap_tiles;
};

/// The page. Throws base::InputError when basemap_url is no http(s) XYZ template.
std::string plan_page(const PlanPage& page);

/// The page with its placeholders (/*SWATH_TITLE*/, /*SWATH_CSP*/, /*SWATH_DATA*/): generated at
/// build time from web/page and Leaflet (web/embed_page.cmake).
const std::string& plan_page_template();

}  // namespace swath::web

#pragma once
// The fleet's live and replay page (swath-fleet run --live, swath-fleet view): one self-contained
// page (Leaflet and the page's script inlined) that draws a run's events.jsonl lines on a map in
// the run's local frame: drones with trails, state and battery, tasks coloured by state,
// forecasts and the scheduler's assignment.

#include <optional>
#include <string>

namespace swath::web {

/// Where a run's local frame (x east, y north, metres) lies: the world's origin, WGS84 degrees.
struct MapOrigin {
  double lat_deg = 0, lon_deg = 0;
};

/// Live: the page reads the run's events from the server that sent it (GET /events, server-sent
/// events); its Content-Security-Policy lets it connect to that origin and nowhere else. With the
/// world's `origin` the run is drawn on a map in lat/lon (Web Mercator), else in local metres.
std::string live_page(const std::string& title,
                      const std::optional<MapOrigin>& origin = std::nullopt);

/// Replay: `events_jsonl` (a whole events.jsonl) inlined, with a time slider and a play button;
/// the page fetches nothing. Drawn in lat/lon when run_start gives the world's origin.
std::string replay_page(const std::string& title, const std::string& events_jsonl);

/// The page with its placeholders (/*SWATH_TITLE*/, /*SWATH_CSP*/, /*SWATH_DATA*/): generated at
/// build time from web/page/live.* and Leaflet (web/embed_page.cmake).
const std::string& live_page_template();

}  // namespace swath::web

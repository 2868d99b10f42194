#pragma once
// The fleet's live and replay page (swath-fleet run --live, swath-fleet view): one self-contained
// page (Leaflet and the page's script inlined) that draws a run's events.jsonl lines on a map in
// the run's local frame: drones with trails, state and battery, tasks coloured by state,
// forecasts and the scheduler's assignment.

#include <string>

namespace swath::web {

/// Live: the page reads the run's events from the server that sent it (GET /events, server-sent
/// events); its Content-Security-Policy lets it connect to that origin and nowhere else.
std::string live_page(const std::string& title);

/// Replay: `events_jsonl` (a whole events.jsonl) inlined, with a time slider and a play button;
/// the page fetches nothing.
std::string replay_page(const std::string& title, const std::string& events_jsonl);

/// The page with its placeholders (/*SWATH_TITLE*/, /*SWATH_CSP*/, /*SWATH_DATA*/): generated at
/// build time from web/page/live.* and Leaflet (web/embed_page.cmake).
const std::string& live_page_template();

}  // namespace swath::web

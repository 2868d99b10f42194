#include "swath/web/plan_page.hpp"

#include <nlohmann/json.hpp>

#include <regex>

#include "html_text.hpp"
#include "swath/base/input_error.hpp"

namespace swath::web {
namespace {

// The tile server's origin for the Content-Security-Policy ({s} subdomains become a wildcard).
std::string tile_origin(const std::string& url) {
  static const std::regex xyz(R"(^(https?://[A-Za-z0-9.{}:-]+)/[^\s"';<>]*$)");
  std::smatch m;
  const bool has_xyz = url.find("{z}") != std::string::npos &&
                       url.find("{x}") != std::string::npos && url.find("{y}") != std::string::npos;
  if (!std::regex_match(url, m, xyz) || !has_xyz)
    throw base::InputError("--basemap-url " + url +
                           ": not an XYZ tile template (http(s)://host/.../{z}/{x}/{y}.png)");
  std::string origin = m[1];
  const std::size_t s = origin.find("{s}");
  if (s != std::string::npos) origin.replace(s, 3, "*");
  if (origin.find_first_of("{}") != std::string::npos)
    throw base::InputError("--basemap-url " + url + ": only {s} may stand in the host name");
  return origin;
}

}  // namespace

std::string plan_page(const PlanPage& page) {
  std::string csp = detail::kOfflineCsp;
  if (!page.basemap_url.empty()) csp += " " + tile_origin(page.basemap_url);
  nlohmann::ordered_json files = nlohmann::ordered_json::object();
  for (const auto& [name, text] : page.files) files[name] = text;
  nlohmann::ordered_json tiles;  // null: none
  if (page.basemap_tiles) {
    const MapTiles& m = *page.basemap_tiles;
    nlohmann::ordered_json by_place = nlohmann::ordered_json::object();
    for (const MapTile& t : m.tiles)
      by_place[std::to_string(t.z) + "/" + std::to_string(t.x) + "/" + std::to_string(t.y)] =
          "data:image/png;base64," + detail::base64(t.png);
    tiles = {{"min_zoom", m.min_zoom},
             {"max_zoom", m.max_zoom},
             {"bounds", {{m.south_deg, m.west_deg}, {m.north_deg, m.east_deg}}},
             {"finest_px_m", m.finest_px_m},
             {"raster_px_m", m.raster_px_m},
             {"capped", m.capped},
             {"tiles", by_place}};
  }
  const nlohmann::ordered_json data = {
      {"title", page.title},
      {"basemap_url", page.basemap_url.empty() ? nlohmann::ordered_json()
                                               : nlohmann::ordered_json(page.basemap_url)},
      {"basemap_tiles", tiles},
      {"files", files}};
  // From the last placeholder to the first: what is put in cannot be taken for a placeholder.
  std::string html = plan_page_template();
  detail::replace_once(html, "/*SWATH_DATA*/", detail::script_json(data));
  detail::replace_once(html, "/*SWATH_TITLE*/", detail::html_text(page.title));
  detail::replace_once(html, "/*SWATH_CSP*/", csp);
  return html;
}

}  // namespace swath::web

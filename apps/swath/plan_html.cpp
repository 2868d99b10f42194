#include "plan_html.hpp"

#include <nlohmann/json.hpp>

#include "basemap.hpp"
#include "swath/base/input_error.hpp"
#include "swath/web/plan_page.hpp"

namespace swath::apps {
namespace {

// The flights' file names as summary.json lists them: each drone's, and each sortie's.
std::vector<std::string> flight_stems(const std::string& summary) {
  std::vector<std::string> stems;
  const nlohmann::json j = nlohmann::json::parse(summary, nullptr, false);
  if (!j.is_object() || !j.contains("drones") || !j["drones"].is_array()) return stems;
  for (const auto& d : j["drones"]) {
    if (d.contains("file") && d["file"].is_string()) stems.push_back(d["file"]);
    if (d.contains("sorties") && d["sorties"].is_array())
      for (const auto& s : d["sorties"])
        if (s.contains("file") && s["file"].is_string()) stems.push_back(s["file"]);
  }
  return stems;
}

}  // namespace

std::string plan_html(const PlanFileLookup& file, const std::string& title,
                      const std::string& basemap_url, const std::string& basemap) {
  web::PlanPage page;
  page.title = title;
  page.basemap_url = basemap_url;
  for (const char* name : {"mission.geojson", "summary.json"}) {
    std::optional<std::string> text = file(name);
    if (!text)
      throw base::InputError(title + ": no " + name + " (is this a swath plan directory?)");
    page.files.emplace_back(name, std::move(*text));
  }
  for (const char* name : {"photos.csv", "waypoints.csv"})
    if (std::optional<std::string> text = file(name))
      page.files.emplace_back(name, std::move(*text));
  for (const std::string& stem : flight_stems(page.files[1].second))
    if (std::optional<std::string> text = file(stem + ".plan")) {
      // The page reads it as JSON: a broken one is named here, not left to fail in the browser.
      if (!nlohmann::json::accept(*text))
        throw base::InputError(title + "/" + stem + ".plan: not JSON (a QGroundControl plan)");
      page.files.emplace_back(stem + ".plan", std::move(*text));
    }
  if (!basemap.empty()) page.basemap_tiles = page_basemap(page.files[0].second, basemap);
  return web::plan_page(page);
}

}  // namespace swath::apps

#pragma once
// plan.html of a plan directory (docs/swath-plan.md, "The map page").

#include <functional>
#include <optional>
#include <string>

namespace swath::apps {

/// A plan file's text by name; nullopt when the plan has no such file.
using PlanFileLookup = std::function<std::optional<std::string>(const std::string& name)>;

/// The page from the plan's own files (mission.geojson, summary.json, photos.csv, waypoints.csv
/// and each flight's .plan, as summary.json names them): the same for `plan --html` (the files in
/// memory) and `render DIR --html` (the files read back).
/// `basemap`: a raster file drawn behind the plan (--basemap), or empty.
std::string plan_html(const PlanFileLookup& file, const std::string& title,
                      const std::string& basemap_url, const std::string& basemap = "");

}  // namespace swath::apps

#pragma once
// What swath verify and swath plan's own check take from area files: zones and the area.

#include <string>
#include <utility>
#include <vector>

#include "swath/preflight/verify.hpp"

namespace swath::apps {

/// Every polygon of every file (a FeatureCollection or MultiPolygon: each polygon its own zone),
/// read with the area reader; named "FILE" or "FILE feature K".
std::vector<preflight::Zone> zones_from_files(const std::vector<std::string>& paths);

/// The area's holes as zones ("hole K of FIELD") and its outer ring as the surveyed area.
void add_area(const std::string& path, preflight::CheckOptions& options);

/// swath plan's check of the files it is about to write; throws base::InputError naming the
/// first violation (file, item, check, amount) when one fails. SWATH_PLAN_VERIFY=0 turns it off.
void verify_before_writing(const std::vector<std::pair<std::string, std::string>>& files,
                           const preflight::CheckOptions& options);

}  // namespace swath::apps

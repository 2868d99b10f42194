#pragma once
// Reading a JSON document (GeoJSON areas, mission.geojson, QGC .plan) strictly, with errors that
// name the source and the place.

#include <nlohmann/json.hpp>

#include <string>

namespace swath::base {

/// Parses `text`. Throws InputError naming `source` for a syntax error (line and column), a
/// number JSON cannot hold as a double (1e999), or a key given twice in one object (JSON parsers
/// disagree on which one wins, so swath refuses to guess).
nlohmann::json parse_json_document(const std::string& text, const std::string& source);

}  // namespace swath::base

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

namespace swath::base {

/// `j` serialised with `indent`; bytes that are not UTF-8 (a drone name, a file name) become
/// U+FFFD instead of aborting the write (nlohmann's default throws type_error 316).
template <typename Json>
std::string json_text(const Json& j, int indent) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace swath::base

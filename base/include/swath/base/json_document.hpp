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

namespace detail {
/// parse_json_document() by nlohmann's parser alone: what it falls back on for a document its
/// own parser of plain documents gives up on, and the reference its tests compare it with.
nlohmann::json parse_json_document_nlohmann(const std::string& text, const std::string& source);
}  // namespace detail

}  // namespace swath::base

namespace swath::base {

// Checked access into a parsed document (swath's own files read back are input like any other:
// docs/reliability.md). Every failure is an InputError "<where>: ..." naming the place; never
// operator[] on a const document, never a library exception.

/// The member `key` of `object`; refused when `object` is not an object or has no such key.
const nlohmann::json& json_member(const nlohmann::json& object, const char* key,
                                  const std::string& where);
/// The member `key`, or nullptr when `object` is not an object or has none.
const nlohmann::json* json_find(const nlohmann::json& object, const char* key);
/// A finite number.
double json_number(const nlohmann::json& value, const std::string& where);
/// A whole number in [lo, hi].
long long json_integer(const nlohmann::json& value, long long lo, long long hi,
                       const std::string& where);
/// A string.
const std::string& json_string(const nlohmann::json& value, const std::string& where);
/// An array of at least `min_size` elements.
const nlohmann::json& json_array(const nlohmann::json& value, const std::string& where,
                                 std::size_t min_size = 0);

/// Appends `x` as nlohmann's serializer writes a number: its Grisu2 shortest text ("1.0" for one),
/// "null" for a non-finite one (for writers that write JSON text directly, not through a tree).
void append_json_number(std::string& out, double x);

/// `j` serialised with `indent`; bytes that are not UTF-8 (a drone name, a file name) become
/// U+FFFD instead of aborting the write (nlohmann's default throws type_error 316).
template <typename Json>
std::string json_text(const Json& j, int indent) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace swath::base

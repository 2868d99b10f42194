#pragma once
// Internal: what a field parser hands to the common validation (not installed).

#include <cctype>
#include <string>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/geometry/point.hpp"

namespace swath::geometry::detail {

using base::InputError;

using base::line_column;

/// One ring as the file gives it: (lon, lat) or (x, y), with where each position stands.
struct RawRing {
  std::string name;            ///< e.g. "feature 0, ring 1" or "outer boundary"
  std::vector<Point2> points;  ///< x = lon or east, y = lat or north
  std::vector<int> line;       ///< 1-based file line of each position, or empty if unknown
};

/// Ring 0 is the outer ring, the others holes.
struct RawField {
  std::vector<RawRing> rings;
};

/// "<name>, position <i>" plus ", line <L>" when known.
std::string position_place(const RawRing& ring, std::size_t i);

[[noreturn]] inline void fail(const std::string& source, const std::string& message) {
  throw InputError(source + ": " + message);
}

/// `s` in lower case (ASCII): column names, type names and extensions compared without case.
inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// A piece of the file for a message: at most 40 characters, each not printable as '?' (a NUL
/// cut the message short, a control character garbled the terminal).
inline std::string shown(const std::string& piece) {
  std::string out;
  for (const char c : piece.substr(0, 40))
    out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return piece.size() > 40 ? out + "..." : out;
}

RawField parse_geojson(const std::string& text, const std::string& source);
/// A GeoJSON FeatureCollection's feature count and whether any feature's geometry is a Polygon or
/// MultiPolygon ({0, false} for any other GeoJSON). Throws InputError as parse_geojson() does.
struct GeojsonCollection {
  std::size_t features = 0;
  bool polygonal = false;
};
GeojsonCollection geojson_collection(const std::string& text, const std::string& source);
RawField parse_kml(const std::string& text, const std::string& source);
RawField parse_csv(const std::string& text, const std::string& source, bool local_metres);

}  // namespace swath::geometry::detail

#pragma once
// Survey area files: swath's own GeoJSON, KML and CSV readers (placed messages), and every other
// format GDAL/OGR opens (Shapefile, GeoPackage, KMZ, GPX, FlatGeobuf, GML, WKT, ...), reprojected
// to WGS84 (docs/swath-plan.md).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

enum class FieldFormat { geojson, kml, csv, wkt, ogr };

struct FieldReadOptions {
  /// CSV only: the columns are x,y in local metres instead of lon,lat.
  bool local_metres = false;
  /// Format; when empty it is taken from the file extension (.geojson/.json, .kml, .csv/.txt;
  /// .shp, .zip, .gpkg, .kmz, .gpx, .fgb, .gml, .wkt, .sqlite, .tab through OGR).
  std::optional<FieldFormat> format;
  /// A file with several layers: the one to read (name, or 0-based index).
  std::optional<std::string> layer;
  /// A layer with several areas: the one to read (0-based index among its polygon features, or
  /// the value of `name_field`).
  std::optional<std::string> feature;
  /// The attribute that names features (default: the first of name, Name, NAME, id).
  std::optional<std::string> name_field;
  /// list_areas() of a file whose every feature must be an area (e.g. "a no-fly zone": a zone
  /// file's power line or mast would otherwise be skipped unseen): a feature of any layer that is
  /// no area (a line, a point, no geometry) is refused, naming it, its geometry type and the
  /// polygon this says it must be.
  std::optional<std::string> only_areas_as;
};

/// The most vertices an area file may hold (all rings): beyond it swath refuses the file instead
/// of spending minutes on it. Transits are routed on the outline's vertices, super-linearly: an
/// 800 m square traced by 10,000 points jittered 0.3 m off its edges (about half of them reflex)
/// plans in 24 s of CPU and 265 MB, by 15,000 points in 60 s; 250,000 collinear points on its
/// edges took 375 s and 8.4 GB.
inline constexpr std::size_t kMaxFieldVertices = 10'000;

/// A survey area ready for planning.
struct Field {
  std::string source;  ///< the file name, for messages
  /// The area in local metres, normalised (outer counter-clockwise, holes clockwise).
  Polygon polygon;
  /// Per ring (0 = outer, k = hole k-1): each kept vertex's position in the file's ring, so that
  /// reports can name vertices as the user numbered them (0-based).
  std::vector<std::vector<std::size_t>> source_index;
  /// The frame the polygon is in; empty for a local-metres CSV (no geographic reference).
  std::optional<LocalFrame> frame;
  /// Per ring, the file's own WGS84 position of each kept vertex (empty for a local-metres CSV),
  /// so outputs repeat the input exactly instead of converting back.
  std::vector<std::vector<GeoPoint>> geo_rings;
};

/// Reads and validates an area file. Throws InputError (file, place and problem in one sentence)
/// for a missing or empty file, a syntax error, a wrong geometry type, a non-finite coordinate, a
/// latitude beyond ±90° or longitude beyond ±180°, a ring with fewer than 3 distinct vertices, a
/// ring of zero area, a hole that lies outside the outer ring, or more than kMaxFieldVertices. A
/// self-intersecting area is read (classify() reports it). The local frame's origin is the mean of
/// the outer ring's vertices.
Field read_field(const std::filesystem::path& path, const FieldReadOptions& options = {});

/// One area of a file with several (swath batch).
struct AreaEntry {
  std::string name;   ///< the area's name (its name field), or its position as text
  std::size_t index;  ///< 0-based position among the layer's areas: --feature INDEX reads it
  /// A feature of the layer that is no area (no geometry, a point, an open line): the sentence
  /// that says so, naming the file and the feature's position; `index` then means nothing.
  std::string not_an_area;
};

/// The areas of `path` that read_field could choose with --feature (one entry for a file of one
/// area; the layer as `options` choose it), and in the file's order an entry for each feature
/// that is no area (not_an_area). Throws InputError when the file cannot be read or holds no
/// area.
std::vector<AreaEntry> list_areas(const std::filesystem::path& path,
                                  const FieldReadOptions& options = {});

/// How many times a layer of `path` was read through GDAL in this process by read_field(): a read
/// of an area of the file last read, unchanged since (same device, inode, size and modification
/// time), with the same layer and name field, takes its areas from that read (`swath batch` reads
/// area after area of one file). For tests; 0 for a file never read through GDAL.
std::size_t area_file_reads(const std::filesystem::path& path);

/// Places a local-metres field on the map: its (0, 0) at `origin`; fills frame and geo_rings.
void place_local_field(Field& field, const GeoPoint& origin);

/// The same from text already in memory; `source` names it in messages.
Field parse_field(const std::string& text, FieldFormat format, const std::string& source,
                  bool local_metres = false);

}  // namespace swath::geometry

#include "swath/geometry/field.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

#include "field_ogr.hpp"
#include "raw_field.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::geometry {

using base::InputError;
namespace detail {

std::string position_place(const RawRing& ring, std::size_t i) {
  std::string place = ring.name + ", position " + std::to_string(i);
  if (i < ring.line.size() && ring.line[i] > 0)
    place += " (line " + std::to_string(ring.line[i]) + ")";
  return place;
}

}  // namespace detail

namespace {

using detail::fail;
using detail::position_place;

FieldFormat format_from_extension(const std::filesystem::path& path) {
  const std::string ext = detail::lower(path.extension().string());
  if (ext == ".geojson" || ext == ".json") return FieldFormat::geojson;
  if (ext == ".kml") return FieldFormat::kml;
  if (ext == ".csv" || ext == ".txt") return FieldFormat::csv;
  if (ext == ".wkt") return FieldFormat::wkt;
  for (const char* e : {".shp", ".zip", ".gpkg", ".kmz", ".gpx", ".fgb", ".gml", ".sqlite", ".tab",
                        ".mif", ".dxf", ".fgdb", ".gdb"})
    if (ext == e) return FieldFormat::ogr;
  throw InputError(path.string() + ": unknown file type '" + ext +
                   "'; expected .geojson, .json, .kml, .csv, or a GIS file GDAL reads (.shp, "
                   ".zip, .gpkg, .kmz, .gpx, .fgb, .gml, .wkt)");
}

void check_coordinates(const detail::RawField& raw, const std::string& source, bool geographic) {
  for (const detail::RawRing& ring : raw.rings) {
    for (std::size_t i = 0; i < ring.points.size(); ++i) {
      const Point2 p = ring.points[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        fail(source, position_place(ring, i) + ": coordinate is not a finite number");
      if (!geographic) continue;
      if (std::abs(p.y) > 90.0)
        fail(source, position_place(ring, i) + ": latitude " + base::shortest_text(p.y) +
                         " is beyond ±90 degrees (positions are longitude, latitude)");
      if (std::abs(p.x) > 180.0)
        fail(source, position_place(ring, i) + ": longitude " + base::shortest_text(p.x) +
                         " is beyond ±180 degrees");
    }
  }
}

// Longitude in [-180, 180), keeping values already inside (180 stays 180).
double wrap_longitude(double lon) {
  if (lon >= -180.0 && lon <= 180.0) return lon;
  return std::fmod(std::fmod(lon + 180.0, 360.0) + 360.0, 360.0) - 180.0;
}

// Each longitude moved by whole turns to within 180° of `reference`.
void unwrap_longitudes(detail::RawField& raw, double reference) {
  for (detail::RawRing& ring : raw.rings)
    for (Point2& p : ring.points) {
      while (p.x - reference > 180.0) p.x -= 360.0;
      while (p.x - reference < -180.0) p.x += 360.0;
    }
}

// A hole inside another hole (an island in a pond) is no area swath can sweep in one piece:
// refused naming both (holes that cross each other are crossings, reported by classify()).
void check_holes_apart(const std::vector<Ring>& holes, const detail::RawField& raw,
                       const std::string& source) {
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> boxes;
  for (const Ring& hole : holes) {
    Box b{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const Point2& p : hole)
      b = {std::min(b.x0, p.x), std::min(b.y0, p.y), std::max(b.x1, p.x), std::max(b.y1, p.y)};
    boxes.push_back(b);
  }
  for (std::size_t a = 0; a < holes.size(); ++a)
    for (std::size_t b = 0; b < holes.size(); ++b) {
      if (a == b) continue;
      const Box& in = boxes[b];
      const Point2 p = holes[a].front();
      if (p.x < in.x0 || p.x > in.x1 || p.y < in.y0 || p.y > in.y1) continue;
      if (locate_point(p, holes[b]) == Containment::inside)
        fail(source, raw.rings[a + 1].name + " lies inside " + raw.rings[b + 1].name +
                         "; nested holes (an island in a pond) are not supported: plan the island "
                         "as an area of its own");
    }
}

}  // namespace

namespace {

// The checks and the conversion every reader shares: rings as the file gives them in, a
// normalised field in local metres out.
Field field_from_raw(detail::RawField raw, const std::string& source, bool geographic);

}  // namespace

Field parse_field(const std::string& text, FieldFormat format, const std::string& source,
                  bool local_metres) {
  const bool blank =
      std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); });
  if (blank) fail(source, "the file is empty");

  detail::RawField raw;
  switch (format) {
    case FieldFormat::geojson:
      raw = detail::parse_geojson(text, source);
      break;
    case FieldFormat::kml:
      raw = detail::parse_kml(text, source);
      break;
    case FieldFormat::csv:
      raw = detail::parse_csv(text, source, local_metres);
      break;
    case FieldFormat::wkt:
      raw = detail::parse_wkt(text, source);
      break;
    case FieldFormat::ogr:
      fail(source, "a GIS file is read from its path (read_field), not from text");
  }
  return field_from_raw(std::move(raw), source, !(format == FieldFormat::csv && local_metres));
}

namespace {

// How far an outer ring's edge may stray from the frame's chord before points are inserted along
// it. The area's edge promises no clearance (a line end half a metre off it is well within the
// photos' overlap), and a point on a gently bowing edge is a reflex vertex: at 1 cm a convex
// field's 800 m east-west side at 47° would make it concave and split it into cells.
constexpr double kOuterEdgeDepartureTolerance_m = 0.5;
// A hole's edges are followed as a zone's are (kZoneEdgeDepartureTolerance_m): a field's holes,
// tens to hundreds of metres across, bow less and are read as they are.

// RFC 7946: an edge is straight in longitude and latitude. Where such an edge strays from the
// frame's chord (a long one, far from the equator), points along it keep the ring the shape
// drawn for every later stage; each inserted point takes its edge's first vertex's number.
void densify_long_edges(const LocalFrame& frame, NormalisedRing& ring, std::vector<GeoPoint>& geo,
                        double tolerance_m) {
  std::vector<std::size_t> from;
  std::vector<GeoPoint> dense = densify_lonlat_edges(frame, geo, &from, tolerance_m);
  if (dense.size() == geo.size()) return;
  std::vector<std::size_t> index;
  ring.ring.clear();
  for (std::size_t k = 0; k < dense.size(); ++k) {
    ring.ring.push_back(frame.to_local(dense[k]));
    index.push_back(ring.source_index[from[k]]);
  }
  ring.source_index = std::move(index);
  geo = std::move(dense);
}

Field field_from_raw(detail::RawField raw, const std::string& source, bool geographic) {
  std::size_t vertices = 0;
  for (const detail::RawRing& ring : raw.rings) vertices += ring.points.size();
  if (vertices > kMaxFieldVertices)
    fail(source, "its polygons have " + std::to_string(vertices) +
                     " vertices, more than swath's limit of " + std::to_string(kMaxFieldVertices) +
                     "; simplify it first (a survey rarely needs "
                     "vertices closer than a metre)");
  check_coordinates(raw, source, geographic);

  Field field;
  field.source = source;
  if (raw.rings.empty() || raw.rings[0].points.empty())
    fail(source,
         (raw.rings.empty() ? std::string("the area") : raw.rings[0].name) + " has no positions");
  if (geographic) {
    // A field across the antimeridian: longitudes unwrapped to the first vertex's side (179.9 and
    // -179.9 are 0.2° apart, not 359.8°), so rings stay continuous and the frame's origin lies in
    // the field instead of half a world away. ±180 are the same meridian.
    unwrap_longitudes(raw, raw.rings[0].points.front().x);
    // Origin at the mean of the outer ring's positions keeps local coordinates small.
    GeoPoint origin{};
    for (const Point2& p : raw.rings[0].points) {
      origin.lon_deg += p.x;
      origin.lat_deg += p.y;
    }
    origin.lon_deg =
        wrap_longitude(origin.lon_deg / static_cast<double>(raw.rings[0].points.size()));
    origin.lat_deg /= static_cast<double>(raw.rings[0].points.size());
    field.frame.emplace(origin);
  }

  for (std::size_t r = 0; r < raw.rings.size(); ++r) {
    const detail::RawRing& ring = raw.rings[r];
    // Normalise in file coordinates (duplicates are the file's; lon/lat keep orientation except
    // about a pole, set again below in the local plane), then convert.
    NormalisedRing normalised = normalise_ring(ring.points, r == 0);
    if (geographic) {
      std::vector<GeoPoint> geo;
      geo.reserve(normalised.ring.size());
      for (Point2& p : normalised.ring) {
        geo.push_back({p.y, wrap_longitude(p.x), 0.0});
        p = field.frame->to_local(geo.back());
      }
      densify_long_edges(*field.frame, normalised, geo,
                         r == 0 ? kOuterEdgeDepartureTolerance_m : kZoneEdgeDepartureTolerance_m);
      // Except about a pole: a ring round the South Pole turns the other way on the ground than
      // in longitude and latitude (every vertex was reflex, and the cells failed). The local
      // plane decides, and the first vertex stays first as in normalise_ring().
      const double a = signed_area(normalised.ring);
      if ((r == 0 && a < 0) || (r > 0 && a > 0)) {
        std::reverse(normalised.ring.begin() + 1, normalised.ring.end());
        std::reverse(normalised.source_index.begin() + 1, normalised.source_index.end());
        std::reverse(geo.begin() + 1, geo.end());
      }
      field.geo_rings.push_back(std::move(geo));
    }
    if (normalised.ring.size() < 3)
      fail(source, ring.name + " has " + std::to_string(normalised.ring.size()) +
                       " distinct vertices; a ring needs at least 3");
    // Degenerate: the convex hull is a sliver (thinner than ~1e-5 of its length), so the ring
    // encloses no area. The hull, not the shoelace sum, since a crossing ring may sum to zero;
    // and not an exact collinearity test, since points on a parallel are not collinear in the
    // local plane.
    const double ring_perimeter = perimeter(normalised.ring);
    const bool clearly_wide =
        std::abs(signed_area(normalised.ring)) > 1e-6 * ring_perimeter * ring_perimeter;
    if (!clearly_wide) {
      const Ring hull = convex_hull(normalised.ring);
      const double hull_perimeter = perimeter(hull);
      if (hull.size() < 3 || signed_area(hull) <= 1e-6 * hull_perimeter * hull_perimeter)
        fail(source, ring.name + " encloses no area (its vertices lie on one line)");
    }
    if (r == 0) {
      field.polygon.outer = std::move(normalised.ring);
    } else {
      field.polygon.holes.push_back(std::move(normalised.ring));
    }
    field.source_index.push_back(std::move(normalised.source_index));
  }

  // A hole with no vertex inside the outer ring lies outside it (a hole that is partly outside
  // crosses the outer ring, which classify() reports as a crossing).
  for (std::size_t h = 0; h < field.polygon.holes.size(); ++h) {
    const Ring& hole = field.polygon.holes[h];
    const bool any_inside = std::any_of(hole.begin(), hole.end(), [&](Point2 p) {
      return locate_point(p, field.polygon.outer) == Containment::inside;
    });
    if (!any_inside)
      fail(source, raw.rings[h + 1].name + " is a hole that lies outside the outer ring");
  }
  check_holes_apart(field.polygon.holes, raw, source);
  return field;
}

}  // namespace

void place_local_field(Field& field, const GeoPoint& origin) {
  field.frame.emplace(origin);
  field.geo_rings.clear();
  for (std::size_t r = 0; r < ring_count(field.polygon); ++r) {
    std::vector<GeoPoint> geo;
    for (const Point2& p : ring_at(field.polygon, r)) geo.push_back(field.frame->to_geo(p));
    field.geo_rings.push_back(std::move(geo));
  }
}

std::vector<AreaEntry> list_areas(const std::filesystem::path& path,
                                  const FieldReadOptions& options) {
  const FieldFormat format = options.format ? *options.format : format_from_extension(path);
  if (format == FieldFormat::csv || format == FieldFormat::wkt) {
    read_field(path, options);  // refuses a bad file as a plan would
    return {{path.stem().string(), 0, {}}};
  }
  return detail::list_ogr_areas(path.string(), options);
}

std::size_t area_file_reads(const std::filesystem::path& path) {
  return detail::area_reads(path.string());
}

namespace {

// A GeoJSON collection of several features is counted as list_areas() counts it, so that swath
// plan, --feature and swath batch agree on its areas (a closed line is one, an empty polygon is
// none): several areas are refused naming the first two (--feature's indices); a lone area that
// is no polygon (a closed line beside a point) is read through OGR as --feature reads it. The
// options for that read, or none: swath's own reader reads the file (a collection of one
// feature, or one whose lone area is its polygon).
std::optional<FieldReadOptions> lone_listed_area(const std::filesystem::path& path,
                                                 const std::string& text,
                                                 const FieldReadOptions& options) {
  const detail::GeojsonCollection collection = detail::geojson_collection(text, path.string());
  if (collection.features < 2) return std::nullopt;
  std::vector<AreaEntry> areas;
  try {
    areas = list_areas(path, options);
  } catch (const InputError&) {
    return std::nullopt;  // no area: swath's reader says why in its own words
  }
  std::erase_if(areas, [](const AreaEntry& a) { return !a.not_an_area.empty(); });
  if (areas.size() > 1)
    detail::fail(path.string(), "features " + std::to_string(areas[0].index) + " and " +
                                    std::to_string(areas[1].index) +
                                    " are both areas; choose one with --feature NAME or INDEX");
  if (areas.size() != 1 || collection.polygonal) return std::nullopt;
  FieldReadOptions chosen = options;
  chosen.feature = std::to_string(areas[0].index);
  return chosen;
}

}  // namespace

Field read_field(const std::filesystem::path& path, const FieldReadOptions& options) {
  const std::string source = path.string();
  // A missing file or a directory is said so before its extension is looked at.
  if (!std::filesystem::is_regular_file(path) && path.extension() != ".gdb")
    (void)base::read_text_file(path, "area file");
  const FieldFormat format = options.format ? *options.format : format_from_extension(path);
  const bool choosing = options.layer || options.feature || options.name_field;
  if (format == FieldFormat::ogr ||
      (choosing && format != FieldFormat::csv && format != FieldFormat::wkt))
    return field_from_raw(detail::read_ogr(source, options), source, true);
  if (choosing)
    fail(source,
         "a CSV or WKT file holds one area: --layer, --feature and --name-field do not apply");
  std::string text = base::read_text_file(path, "area file");
  // A GeoJSON naming a coordinate reference system (the 2008 "crs" member, e.g. EPSG:2056) is
  // reprojected by OGR; swath's own reader takes RFC 7946's longitude/latitude.
  if (format == FieldFormat::geojson && text.find("\"crs\"") != std::string::npos &&
      text.find("CRS84") == std::string::npos && text.find("EPSG::4326") == std::string::npos)
    return field_from_raw(detail::read_ogr(source, options), source, true);
  if (format == FieldFormat::geojson && text.find("FeatureCollection") != std::string::npos)
    if (const auto chosen = lone_listed_area(path, text, options))
      return field_from_raw(detail::read_ogr(source, *chosen), source, true);
  return parse_field(text, format, source, options.local_metres);
}

}  // namespace swath::geometry

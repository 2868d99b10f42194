// Area files through GDAL/OGR (docs/swath-plan.md): any vector format GDAL opens, one polygon
// chosen by layer and feature, reprojected to WGS84 longitude/latitude by OGR itself. GDAL's
// headers stay in this file, which is the GIS module libswath_gis.so (gis_module.hpp says why).

#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include "field_ogr.hpp"
#include "gdal_confinement.hpp"
#include "gis_module.hpp"
#include "raster_gdal.hpp"
#include "swath/base/file_text.hpp"

namespace swath::geometry::detail {
namespace {

struct DatasetClose {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

void register_once() {
  confine_gdal();
}

std::string last_gdal_error() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("GDAL cannot read it");
}

bool polygonal(OGRwkbGeometryType t) {
  t = wkbFlatten(t);
  return t == wkbPolygon || t == wkbMultiPolygon || t == wkbLineString || t == wkbMultiLineString ||
         t == wkbUnknown || t == wkbGeometryCollection || t == wkbCurvePolygon ||
         t == wkbMultiSurface;
}

// The polygon a geometry stands for: a Polygon, a MultiPolygon of one part, or a closed line (a
// GPX track or route walked around the field). nullptr with `why` otherwise.
std::unique_ptr<OGRPolygon> as_polygon(const OGRGeometry* g, std::string& why) {
  if (!g) {
    why = "has no geometry";
    return nullptr;
  }
  std::unique_ptr<OGRGeometry> linear(g->getLinearGeometry());
  if (!linear || linear->IsEmpty()) {  // POLYGON EMPTY has no exterior ring at all
    why = "is empty";
    return nullptr;
  }
  const OGRwkbGeometryType t = wkbFlatten(linear->getGeometryType());
  if (t == wkbPolygon) return std::unique_ptr<OGRPolygon>(linear.release()->toPolygon());
  if (t == wkbMultiPolygon) {
    const OGRMultiPolygon* m = linear->toMultiPolygon();
    if (m->getNumGeometries() != 1) {
      why = "is a MultiPolygon of " + std::to_string(m->getNumGeometries()) +
            " parts (plan each part as its own area)";
      return nullptr;
    }
    return std::unique_ptr<OGRPolygon>(m->getGeometryRef(0)->clone());
  }
  // Lines: a closed track or route walked around the field; with several closed segments the
  // first is the boundary and the others holes (a GPX track with a segment around a pond).
  std::vector<const OGRLineString*> lines;
  if (t == wkbLineString) lines.push_back(linear->toLineString());
  if (t == wkbMultiLineString)
    for (const OGRLineString* l : *linear->toMultiLineString()) lines.push_back(l);
  if (!lines.empty()) {
    auto poly = std::make_unique<OGRPolygon>();
    for (const OGRLineString* line : lines) {
      const int n = line->getNumPoints();
      if (n < 4 || line->getX(0) != line->getX(n - 1) || line->getY(0) != line->getY(n - 1)) {
        why = "is a line that does not close (a track or route must end where it starts)";
        return nullptr;
      }
      auto ring = std::make_unique<OGRLinearRing>();
      for (int i = 0; i < n; ++i) ring->addPoint(line->getX(i), line->getY(i));
      poly->addRingDirectly(ring.release());
    }
    return poly;
  }
  why = std::string("is a ") + OGRGeometryTypeToName(linear->getGeometryType()) + ", not an area";
  return nullptr;
}

// The areas a layer's feature holds: each part of a MultiPolygon (swath batch plans them one by
// one, and --feature picks one), else as_polygon()'s one; none with `why`.
std::vector<std::unique_ptr<OGRPolygon>> feature_areas(const OGRGeometry* g, std::string& why) {
  std::vector<std::unique_ptr<OGRPolygon>> out;
  const std::unique_ptr<OGRGeometry> linear(g ? g->getLinearGeometry() : nullptr);
  if (linear && !linear->IsEmpty() && wkbFlatten(linear->getGeometryType()) == wkbMultiPolygon) {
    const OGRMultiPolygon* m = linear->toMultiPolygon();
    if (m->getNumGeometries() > 1) {
      for (const OGRPolygon* part : *m)
        if (part && !part->IsEmpty()) out.emplace_back(part->clone());
      if (!out.empty()) return out;
    }
  }
  if (auto poly = as_polygon(g, why)) out.push_back(std::move(poly));
  return out;
}

std::string names_list(const std::vector<std::string>& names) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(names.size(), 10);
  for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > shown) out += " and " + std::to_string(names.size() - shown) + " more";
  return out;
}

RawField to_raw(const OGRPolygon& poly, const std::string& where) {
  RawField raw;
  auto add = [&](const OGRLinearRing* r, const std::string& name) {
    RawRing ring;
    ring.name = where + ", " + name;
    for (int i = 0; i < r->getNumPoints(); ++i) ring.points.push_back({r->getX(i), r->getY(i)});
    raw.rings.push_back(std::move(ring));
  };
  if (!poly.getExteriorRing()) return raw;  // as_polygon refuses empty geometries first
  // Rings named as the GeoJSON reader names them: "outer ring (ring 0)", "hole 0 (ring 1)".
  add(poly.getExteriorRing(), "outer ring (ring 0)");
  for (int k = 0; k < poly.getNumInteriorRings(); ++k)
    add(poly.getInteriorRing(k),
        "hole " + std::to_string(k) + " (ring " + std::to_string(k + 1) + ")");
  return raw;
}

// Refuses an area (already in WGS84 longitude/latitude) that lies wholly more than a degree
// outside the area where its CRS is used: coordinates of another CRS than the file says
// (longitude/latitude under a Swiss LV95 .prj became a "convex area" of 0 m² in the Atlantic). A
// CRS without a recorded area of use, or one across the antimeridian, is checked in latitude only.
void check_area_of_use(const OGRGeometry& g, const OGRSpatialReference& crs,
                       const std::string& source) {
  double west = 0, south = 0, east = 0, north = 0;
  const char* name = nullptr;
  if (!crs.GetAreaOfUse(&west, &south, &east, &north, &name) || west == -1000) return;
  OGREnvelope e;
  g.getEnvelope(&e);
  constexpr double kMargin_deg = 1.0;
  const bool lat_outside = e.MaxY < south - kMargin_deg || e.MinY > north + kMargin_deg;
  const bool lon_outside =
      west <= east && (e.MaxX < west - kMargin_deg || e.MinX > east + kMargin_deg);
  if (!lat_outside && !lon_outside) return;
  const char* crs_name = crs.GetName();
  throw InputError(source + ": its coordinates lie outside the area where its CRS (" +
                   std::string(crs_name ? crs_name : "unnamed") + ") is used" +
                   (name ? std::string(": ") + name : std::string()) +
                   "; are they in another CRS than the file says?");
}

// A Shapefile whose .prj GDAL could not read has no CRS, and would be taken as
// longitude/latitude: refused instead (a misspelt or garbage .prj is not WGS84).
void refuse_unread_prj(bool layer_has_crs, const std::string& path) {
  if (layer_has_crs || !lower(path).ends_with(".shp")) return;
  std::error_code ec;
  for (const char* ext : {".prj", ".PRJ"})
    if (std::filesystem::exists(std::filesystem::path(path).replace_extension(ext), ec))
      throw InputError(path +
                       ": its .prj names no coordinate reference system GDAL knows; fix "
                       "it, or remove it for longitude/latitude");
}

// Into WGS84 longitude/latitude (traditional GIS order), when the source has another CRS.
void to_wgs84(OGRGeometry& g, const OGRSpatialReference* srs, const std::string& source) {
  if (!srs) return;  // no CRS: taken as longitude/latitude (GeoJSON's and KML's rule)
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference from(*srs);
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (from.IsSame(&wgs84)) return;
  std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&from, &wgs84));
  if (!ct || g.transform(ct.get()) != OGRERR_NONE)
    throw InputError(source + ": its coordinates cannot be transformed to WGS84 (" +
                     last_gdal_error() + ")");
  check_area_of_use(g, from, source);
}

}  // namespace

RawField parse_wkt(const std::string& text, const std::string& source) {
  register_once();
  OGRGeometry* g = nullptr;
  const char* rest = text.c_str();
  if (OGRGeometryFactory::createFromWkt(&rest, nullptr, &g) != OGRERR_NONE || !g)
    throw InputError(source + ": not a WKT geometry (POLYGON ((lon lat, ...)))");
  std::unique_ptr<OGRGeometry> owned(g);
  // OGR stops at the geometry's end: whatever follows (a second geometry, a stray word) would
  // be silently dropped, so the file is refused instead.
  const auto after = static_cast<std::size_t>(rest - text.c_str());
  const auto tail = text.find_first_not_of(" \t\r\n", after);
  if (tail != std::string::npos)
    throw InputError(source + ": text follows the WKT geometry at byte " +
                     std::to_string(tail + 1) + " (one geometry per file)");
  std::string why;
  auto poly = as_polygon(owned.get(), why);
  if (!poly) throw InputError(source + ": the geometry " + why);
  return to_raw(*poly, "the WKT polygon");
}

namespace {
RawField read_or_list(const std::string& path, const FieldReadOptions& options,
                      std::vector<AreaEntry>* list);
}  // namespace

RawField read_ogr(const std::string& path, const FieldReadOptions& options) {
  return read_or_list(path, options, nullptr);
}

std::vector<AreaEntry> list_ogr_areas(const std::string& path, const FieldReadOptions& options) {
  std::vector<AreaEntry> out;
  read_or_list(path, options, &out);
  return out;
}

namespace {

// Refuses a zip archive (.zip, .kmz) whose members inflate to more than swath reads of any data
// file (kMaxDataFileBytes): a 2 MB KMZ of repeated text inflated to 4.3 GB in memory, and zipped
// GeoJSON of several GiB was read for a minute before "no layer". Sizes from the zip's directory,
// before anything is inflated. An archive GDAL cannot list is left to the open to report.
void check_archive_size(const std::string& local, const std::string& path) {
  const std::string root = "/vsizip/" + local;
  char** names = VSIReadDirRecursive(root.c_str());
  std::uint64_t total = 0;
  for (char** n = names; n && *n; ++n) {
    VSIStatBufL st;
    if (VSIStatL((root + "/" + *n).c_str(), &st) == 0 && VSI_ISREG(st.st_mode))
      total += static_cast<std::uint64_t>(st.st_size);
  }
  CSLDestroy(names);
  if (total > base::kMaxDataFileBytes)
    throw InputError(path + ": the archive inflates to " + std::to_string(total >> 20) +
                     " MiB, more than swath's limit of " +
                     std::to_string(base::kMaxDataFileBytes >> 20) + " MiB for an area file");
}

// A GPX track or route of more points than swath's vertex limit, refused before OGR builds any
// geometry: OGR keeps every point of a track in memory and swath copies it several times (a
// 1,000,000-point track took 113 s and 2.7 GB). The points of each <trk> and <rte> are counted
// in one pass over the bytes (element names, any namespace prefix); the file size cap holds the
// pass to a quarter of a gigabyte.
void check_gpx_points(const std::string& local, const std::string& path) {
  std::ifstream in(local, std::ios::binary);
  std::string name;
  std::size_t points = 0, line = 1, group_line = 1;
  enum { text, open, naming } state = text;  // outside tags, after <, in a name
  auto done = [&] {                          // an element's name is complete
    const std::size_t colon = name.rfind(':');
    const std::string local_name = colon == std::string::npos ? name : name.substr(colon + 1);
    if (local_name == "trk" || local_name == "rte") {
      points = 0;
      group_line = line;
    } else if ((local_name == "trkpt" || local_name == "rtept") && ++points > kMaxFieldVertices) {
      throw InputError(path + ": the track or route from line " + std::to_string(group_line) +
                       " has more than " + std::to_string(kMaxFieldVertices) + " points (line " +
                       std::to_string(line) +
                       "), swath's limit for the vertices of an area; simplify it first (a "
                       "survey rarely needs vertices closer than a metre)");
    }
    name.clear();
  };
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize k = 0; k < in.gcount(); ++k) {
      const char c = buffer[k];
      if (c == '\n') ++line;
      if (state == text) {
        if (c == '<') state = open;
      } else if (state == open && (c == '/' || c == '?' || c == '!')) {
        state = text;  // a closing tag, a declaration, a comment: nothing to count
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '>' || c == '/') {
        if (state == naming) done();
        state = text;
      } else {
        state = naming;
        if (name.size() < 64) name += c;
      }
    }
  }
}

// The file through GDAL (a .zip, zipped Shapefile, and a .kmz through /vsizip/).
std::unique_ptr<GDALDataset, DatasetClose> open_vector(const std::string& path) {
  register_once();
  const std::string local = local_gdal_path(path, "area file");
  const std::string name = lower(path);
  // A zipped Shapefile through /vsizip/; a KMZ as itself (LIBKML reads it whole, doc.kml with
  // its layers/), through /vsizip/ only where that fails.
  std::string open_path = local;
  if (name.ends_with(".zip")) open_path = "/vsizip/" + local;
  if (name.ends_with(".zip") || name.ends_with(".kmz")) check_archive_size(local, path);
  if (name.ends_with(".gpx")) check_gpx_points(local, path);
  CPLErrorReset();
  std::unique_ptr<GDALDataset, DatasetClose> ds(static_cast<GDALDataset*>(
      GDALOpenEx(open_path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  const std::string second = open_path != local       ? local
                             : name.ends_with(".kmz") ? "/vsizip/" + local
                                                      : "";
  if (!ds && !second.empty())
    ds.reset(static_cast<GDALDataset*>(
        GDALOpenEx(second.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds)
    throw InputError(path + ": GDAL cannot open it as a vector file (" + last_gdal_error() + ")");
  return ds;
}

// The layer: the one asked for, or the only one that holds a feature with an area (GPX files list
// empty layers too).
OGRLayer* choose_layer(GDALDataset& ds, const FieldReadOptions& options,
                       const std::string& source) {
  std::vector<OGRLayer*> layers;
  std::vector<std::string> layer_names;
  for (int i = 0; i < ds.GetLayerCount(); ++i) {
    OGRLayer* l = ds.GetLayer(i);
    layer_names.push_back(l->GetName());
    if (polygonal(l->GetGeomType())) layers.push_back(l);
  }
  if (options.layer) {  // by name or position; a later name wins over an earlier position
    OGRLayer* named = nullptr;
    for (int i = 0; i < ds.GetLayerCount(); ++i)
      if (layer_names[static_cast<std::size_t>(i)] == *options.layer ||
          std::to_string(i) == *options.layer)
        named = ds.GetLayer(i);
    if (named) return named;
    throw InputError(source + ": no layer \"" + *options.layer + "\"; its layers are " +
                     names_list(layer_names));
  }
  std::vector<OGRLayer*> with_areas;
  for (OGRLayer* l : layers) {
    l->ResetReading();
    for (auto& f : *l) {
      std::string why;
      if (!feature_areas(f->GetGeometryRef(), why).empty()) {
        with_areas.push_back(l);
        break;
      }
    }
  }
  if (with_areas.empty())
    throw InputError(source + ": no layer holds an area (a polygon or a closed track)");
  if (with_areas.size() > 1) {
    std::vector<std::string> names;
    for (OGRLayer* l : with_areas) names.push_back(l->GetName());
    throw InputError(source + ": " + std::to_string(with_areas.size()) + " layers hold areas (" +
                     names_list(names) + "); choose one with --layer");
  }
  return with_areas.front();
}

// The field that names areas: the one asked for, else name, Name, NAME, id or ID; -1 for none.
int name_field_index(OGRLayer& layer, const FieldReadOptions& options, const std::string& source) {
  const OGRFeatureDefn* defn = layer.GetLayerDefn();
  int name_index = -1;
  if (options.name_field) {
    name_index = defn->GetFieldIndex(options.name_field->c_str());
    if (name_index < 0) {
      std::vector<std::string> fields;
      for (int i = 0; i < defn->GetFieldCount(); ++i)
        fields.push_back(defn->GetFieldDefn(i)->GetNameRef());
      throw InputError(source + ": layer \"" + layer.GetName() + "\" has no field \"" +
                       *options.name_field + "\"" +
                       (fields.empty() ? std::string(" (it has no fields)")
                                       : "; its fields are " + names_list(fields)));
    }
  } else {
    for (const char* n : {"name", "Name", "NAME", "id", "ID"})
      if ((name_index = defn->GetFieldIndex(n)) >= 0) break;
  }
  return name_index;
}

struct LayerArea {
  std::unique_ptr<OGRPolygon> polygon;
  std::string name;  ///< its name field, or its position among the layer's areas
  std::size_t index;
  bool named = false;  ///< `name` is its name field's
};

// Every area of the layer (at most 100,000), a MultiPolygon's parts one by one ("<name>, part
// K", K from 0); none: refused with the first feature's reason. `listing` (swath batch): each
// area's entry and, in the file's order, each feature that is no area with why (a batch reports
// it in a row of its own instead of leaving it out unseen).
std::vector<LayerArea> layer_areas(OGRLayer& layer, int name_index, const std::string& source,
                                   std::vector<AreaEntry>* listing = nullptr) {
  std::vector<LayerArea> areas;
  std::string first_refusal;
  std::size_t position = 0;  // the feature's among all of the layer's
  layer.ResetReading();
  for (auto& f : layer) {
    const std::size_t feature_position = position++;
    std::string why;
    auto parts = feature_areas(f->GetGeometryRef(), why);
    std::string name = std::to_string(areas.size());
    const bool named = name_index >= 0 && f->IsFieldSetAndNotNull(name_index);
    if (named) name = f->GetFieldAsString(name_index);
    if (parts.empty()) {
      if (first_refusal.empty()) first_refusal = "feature " + name + " " + why;
      const std::string place = "feature " + std::to_string(feature_position);
      if (listing)
        listing->push_back({named ? name : place, 0,
                            source + ": " + place + (named ? " (\"" + name + "\") " : " ") + why +
                                "; it is not planned (an area is a polygon or a closed "
                                "line)"});
      continue;
    }
    for (std::size_t k = 0; k < parts.size(); ++k) {
      if (listing)
        listing->push_back(
            {parts.size() == 1 ? name : name + ", part " + std::to_string(k), areas.size(), {}});
      areas.push_back({std::move(parts[k]),
                       parts.size() == 1 ? name : name + ", part " + std::to_string(k),
                       areas.size(), named});
      if (areas.size() > 100000)
        throw InputError(source + ": more than 100,000 areas in one layer");
    }
  }
  if (areas.empty())
    throw InputError(source + ": layer \"" + layer.GetName() + "\" holds no area" +
                     (first_refusal.empty() ? std::string() : " (" + first_refusal + ")"));
  return areas;
}

// The area asked for by name or position, or the layer's only one.
std::size_t choose_area(const std::vector<LayerArea>& areas, const FieldReadOptions& options,
                        const std::string& layer_name, const std::string& source) {
  std::vector<std::string> names;
  for (const LayerArea& c : areas) names.push_back(c.name);
  if (!options.feature) {
    if (areas.size() == 1) return 0;
    throw InputError(source + ": layer \"" + layer_name + "\" holds " +
                     std::to_string(areas.size()) + " areas (" + names_list(names) +
                     "); choose one with --feature NAME or INDEX");
  }
  const std::string& want = *options.feature;
  std::vector<std::size_t> named;
  for (const LayerArea& c : areas)
    if (c.name == want) named.push_back(c.index);
  // Google Earth names every new polygon "Untitled Polygon": a name that several areas share
  // does not say which one is meant, and planning the last of them plans the wrong field.
  if (named.size() > 1) {
    std::vector<std::string> positions;
    for (std::size_t i : named) positions.push_back(std::to_string(i));
    throw InputError(source + ": " + std::to_string(named.size()) + " areas of layer \"" +
                     layer_name + "\" are named \"" + want + "\" (positions " +
                     names_list(positions) +
                     "); give the position (0-based) instead, e.g. --feature " + positions[0]);
  }
  std::size_t chosen = named.empty() ? 0 : named[0];
  bool found = !named.empty();
  if (!found && !want.empty() && std::all_of(want.begin(), want.end(), ::isdigit) &&
      want.size() < 9 && std::stoul(want) < areas.size())
    chosen = std::stoul(want), found = true;
  if (!found)
    throw InputError(source + ": no area \"" + want + "\" in layer \"" + layer_name +
                     "\"; its areas are " + names_list(names) + " (or 0 to " +
                     std::to_string(areas.size() - 1) + " by position)");
  return chosen;
}

// A layer's areas as read, for the area asked of them (area_of()).
struct LayerRead {
  std::vector<LayerArea> areas;
  std::string layer_name;
  std::unique_ptr<OGRSpatialReference> crs;  ///< the layer's (a copy), or none
};

// The one area `options` choose of `read`, refused as read_ogr() says, in WGS84.
RawField area_of(const LayerRead& read, const FieldReadOptions& options, const std::string& path) {
  const std::size_t chosen = choose_area(read.areas, options, read.layer_name, path);
  refuse_unread_prj(read.crs != nullptr, path);
  CPLErrorReset();  // a transformation's failure names its own error, not an earlier one
  const std::unique_ptr<OGRPolygon> poly(read.areas[chosen].polygon->clone());
  to_wgs84(*poly, read.crs.get(), path);
  // Named as --feature and the messages naming a zone of several name it ("feature 2"), an
  // area file's and a zone file's alike: a zone is no area.
  const LayerArea& area = read.areas[chosen];
  return to_raw(*poly, "feature " + (area.named ? "\"" + area.name + "\"" : area.name));
}

// The layers last read, kept for the next read of the same file: `swath batch` plans area after
// area of one file in each worker, and each read parsed the whole file again (a GeoJSON of 400
// plots: 90 M instructions a read, most of each plan; its table of outlines, 400 reads more). A
// layer is kept while its file is the same (path, device, inode, size, modification time; a
// Shapefile's other files are taken to change with it), for the same layer and name field, and
// only in the process that read it (OGR's and PROJ's objects are not carried over a fork). The
// last kKept files' (a plan may also read its zones' files, --exclude, each time).
class LastLayers {
 public:
  struct Key;
  // What identifies a read of `path` with `options` (none where the file cannot be looked at).
  static std::optional<Key> key_of(const std::string& path, const FieldReadOptions& options);
  // The read kept under `key`, if any.
  std::shared_ptr<const LayerRead> find(const Key& key) {
    const std::lock_guard<std::mutex> guard(lock_);
    const auto it =
        std::find_if(kept_.begin(), kept_.end(), [&](const auto& k) { return k.first == key; });
    if (it == kept_.end()) return nullptr;
    std::rotate(kept_.begin(), it, it + 1);  // the most recent first
    return kept_.front().second;
  }
  // `read` of `path`, kept under `key` (taken before the file was opened: a file changed while it
  // was read is read again next time).
  void keep(const std::string& path, const std::optional<Key>& key,
            std::shared_ptr<const LayerRead> read) {
    const std::lock_guard<std::mutex> guard(lock_);
    ++reads_[path];
    if (!key) return;
    std::erase_if(kept_, [&](const auto& k) { return k.first.path == path; });
    kept_.insert(kept_.begin(), {*key, std::move(read)});
    if (kept_.size() > kKept) kept_.pop_back();
  }
  std::size_t reads(const std::string& path) {
    const std::lock_guard<std::mutex> guard(lock_);
    const auto it = reads_.find(path);
    return it == reads_.end() ? 0 : it->second;
  }

  struct Key {
    std::string path;
    std::optional<std::string> layer, name_field;
    dev_t device = 0;
    ino_t inode = 0;
    off_t size = 0;
    std::int64_t modified_ns = 0;
    pid_t process = 0;
    bool operator==(const Key&) const = default;
  };

 private:
  static constexpr std::size_t kKept = 4;
  std::mutex lock_;
  std::vector<std::pair<Key, std::shared_ptr<const LayerRead>>> kept_;  // the most recent first
  std::map<std::string, std::size_t> reads_;  // layers read by path, for area_file_reads()
};

std::optional<LastLayers::Key> LastLayers::key_of(const std::string& path,
                                                  const FieldReadOptions& options) {
  struct stat st {};
  if (::stat(local_gdal_path(path, "area file").c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    return std::nullopt;
  return Key{path,
             options.layer,
             options.name_field,
             st.st_dev,
             st.st_ino,
             st.st_size,
             std::int64_t{st.st_mtim.tv_sec} * 1'000'000'000 + st.st_mtim.tv_nsec,
             ::getpid()};
}

LastLayers& last_layers() {
  static LastLayers kept;
  return kept;
}

// A geometry's type as GeoJSON spells it (OGR's own names are "Line String", "Point").
std::string type_name(const OGRGeometry& g) {
  switch (wkbFlatten(g.getGeometryType())) {
    case wkbPoint:
      return "Point";
    case wkbLineString:
      return "LineString";
    case wkbMultiPoint:
      return "MultiPoint";
    case wkbMultiLineString:
      return "MultiLineString";
    case wkbGeometryCollection:
      return "GeometryCollection";
    default:
      return OGRGeometryTypeToName(g.getGeometryType());
  }
}

// The first position of `g` in WGS84 as "lat, lon (lat, lon)", or empty (an empty geometry).
std::string first_position_text(const OGRGeometry& g, const OGRSpatialReference* crs,
                                const std::string& source) {
  std::unique_ptr<OGRGeometry> linear(g.getLinearGeometry());
  if (!linear || linear->IsEmpty()) return {};
  to_wgs84(*linear, crs, source);
  const OGRGeometry* first = linear.get();
  while (OGR_GT_IsSubClassOf(wkbFlatten(first->getGeometryType()), wkbGeometryCollection) &&
         !first->toGeometryCollection()->IsEmpty())
    first = first->toGeometryCollection()->getGeometryRef(0);
  OGRPoint p;
  const OGRwkbGeometryType t = wkbFlatten(first->getGeometryType());
  if (t == wkbPoint)
    p = *first->toPoint();
  else if (t == wkbLineString && first->toLineString()->getNumPoints() > 0)
    first->toLineString()->getPoint(0, &p);
  else if (t == wkbPolygon && first->toPolygon()->getExteriorRing())
    first->toPolygon()->getExteriorRing()->getPoint(0, &p);
  else
    return {};
  std::ostringstream s;
  s.precision(8);
  s << p.getY() << ", " << p.getX() << " (lat, lon)";
  return s.str();
}

// A layer GDAL derives from others' features: a GPX file's track and route points repeat its
// tracks' and routes' vertices (a closed track is an area; its points are not features of
// their own).
bool derived_layer(GDALDataset& ds, OGRLayer& layer) {
  const std::string name = layer.GetName();
  return ds.GetDriver() && std::string(ds.GetDriver()->GetDescription()) == "GPX" &&
         (name == "track_points" || name == "route_points");
}

// FieldReadOptions::only_areas_as: the first feature of any layer that is no area, refused
// naming it (position in its layer, its name, the layer where there are several), its type and
// where it starts.
void refuse_non_areas(GDALDataset& ds, const FieldReadOptions& options, const std::string& source) {
  const int layers = ds.GetLayerCount();
  for (int i = 0; i < layers; ++i) {
    OGRLayer& layer = *ds.GetLayer(i);
    if (derived_layer(ds, layer)) continue;
    const int name_index = name_field_index(layer, options, source);
    std::size_t position = 0;
    layer.ResetReading();
    for (auto& f : layer) {
      const std::size_t here = position++;
      std::string why;
      const OGRGeometry* g = f->GetGeometryRef();
      if (!feature_areas(g, why).empty()) continue;
      std::string place = "feature " + std::to_string(here);
      if (name_index >= 0 && f->IsFieldSetAndNotNull(name_index))
        place += " (\"" + shown(f->GetFieldAsString(name_index)) + "\")";
      if (layers > 1) place += " of layer \"" + shown(layer.GetName()) + "\"";
      std::string what = "has no geometry";
      if (g) {
        const std::string at = first_position_text(*g, layer.GetSpatialRef(), source);
        what = "is a " + type_name(*g) +
               (at.empty() ? std::string(" with no positions")
                           : (g->getDimension() == 0 ? " at " : " starting at ") + at);
      }
      throw InputError(source + ": " + place + " " + what + "; " + *options.only_areas_as +
                       " must be a polygon (buffer lines and points into polygons first)");
    }
  }
}

RawField read_or_list(const std::string& path, const FieldReadOptions& options,
                      std::vector<AreaEntry>* list) {
  std::optional<LastLayers::Key> key;
  if (!list && (key = LastLayers::key_of(path, options)))
    if (const std::shared_ptr<const LayerRead> kept = last_layers().find(*key))
      return area_of(*kept, options, path);
  const auto ds = open_vector(path);
  if (list && options.only_areas_as) refuse_non_areas(*ds, options, path);
  OGRLayer* layer = choose_layer(*ds, options, path);
  auto read = std::make_shared<LayerRead>();
  read->areas = layer_areas(*layer, name_field_index(*layer, options, path), path, list);
  if (list) return {};  // swath batch: every area of the layer, nothing read
  read->layer_name = layer->GetName();
  if (const OGRSpatialReference* crs = layer->GetSpatialRef()) read->crs.reset(crs->Clone());
  last_layers().keep(path, key, read);
  return area_of(*read, options, path);
}

}  // namespace

std::size_t area_reads(const std::string& path) {
  return last_layers().reads(path);
}

}  // namespace swath::geometry::detail

namespace {

using namespace swath::geometry;

template <typename F>
bool guarded(std::string& error, F&& f) {
  try {
    f();
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

bool module_read(const std::string& path, const FieldReadOptions& o, detail::RawField& out,
                 std::string& error) {
  return guarded(error, [&] { out = detail::read_ogr(path, o); });
}
bool module_list(const std::string& path, const FieldReadOptions& o, std::vector<AreaEntry>& out,
                 std::string& error) {
  return guarded(error, [&] { out = detail::list_ogr_areas(path, o); });
}
bool module_wkt(const std::string& text, const std::string& source, detail::RawField& out,
                std::string& error) {
  return guarded(error, [&] { out = detail::parse_wkt(text, source); });
}

bool module_sample(const std::string& path, double asked_unit_m,
                   const std::vector<GeoPoint>& points, std::vector<double>& values,
                   double& resolution_m, std::string& error) {
  return guarded(error,
                 [&] { detail::sample_raster(path, asked_unit_m, points, values, resolution_m); });
}
bool module_bends(const std::string& path, double asked_unit_m, const GeoPoint& a,
                  const GeoPoint& b, std::vector<double>& fractions, std::string& error) {
  return guarded(error, [&] { detail::raster_bends(path, asked_unit_m, a, b, fractions); });
}
bool module_grid(const std::string& name, std::string& path, std::string& error) {
  return guarded(error, [&] { path = detail::proj_grid(name); });
}

bool module_geotiff(const LocalRaster& raster, std::string& bytes, std::string& error) {
  return guarded(error, [&] { bytes = detail::geotiff(raster); });
}

bool module_imagery(const std::string& path, const detail::ImageryGrid& grid, std::string& rgba,
                    double& pixel_m, std::string& error) {
  return guarded(error, [&] { rgba = detail::imagery_rgba(path, grid, pixel_m); });
}

bool module_png(int width, int height, const std::string& rgba, std::string& bytes,
                std::string& error) {
  return guarded(error, [&] { bytes = detail::rgba_png(width, height, rgba); });
}

const detail::GisModule kModule{detail::kGisModuleAbi,
                                module_read,
                                module_list,
                                module_wkt,
                                module_sample,
                                detail::raster_reads,
                                detail::forget_raster,
                                module_grid,
                                module_geotiff,
                                module_imagery,
                                module_png,
                                detail::imagery_opens,
                                detail::area_reads,
                                module_bends};

}  // namespace

extern "C" __attribute__((visibility("default"))) const swath::geometry::detail::GisModule*
swath_gis_module() {
  return &kModule;
}

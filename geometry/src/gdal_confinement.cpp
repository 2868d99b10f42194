// GDAL kept to what swath documents (gdal_confinement.hpp says why and how).
#include "gdal_confinement.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_minixml.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>

#include "swath/base/input_error.hpp"

namespace swath::geometry::detail {
namespace {

using base::InputError;
namespace fs = std::filesystem;

// A name from a file as a message may quote it: printable ASCII, at most 60 characters.
std::string quoted(const std::string& name) {
  std::string out;
  for (const char c : name) {
    if (out.size() >= 60) {
      out += "…";
      break;
    }
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  return "\"" + out + "\"";
}

// `text` names something other than a plain file: a GDAL virtual path, a URL, or a connection
// string such as PG:dbname=…, WFS:http://…, vrt://… (a word and a colon before any slash).
bool names_a_non_file(const std::string& text) {
  if (text.rfind("/vsi", 0) == 0 || text.find("://") != std::string::npos) return true;
  const auto colon = text.find(':');
  const auto slash = text.find('/');
  return colon != std::string::npos && colon > 0 && (slash == std::string::npos || colon < slash);
}

void set_network_off() {
  // /vsicurl/ and the cloud file systems built on it accept no name: nothing is fetched.
  CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_FILENAME", "/swath/network/is/off");
  CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_EXTENSIONS", ".swath-network-off");
  // Whatever else would speak HTTP (a driver's schema download) goes to a proxy at port 0 of the
  // loopback address: the connection fails at once and no packet leaves the machine.
  for (const char* proxy : {"GDAL_HTTP_PROXY", "GDAL_HTTPS_PROXY"})
    CPLSetConfigOption(proxy, "127.0.0.1:0");
  CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", "0");
  CPLSetConfigOption("GDAL_HTTP_TIMEOUT", "1");
  CPLSetConfigOption("GDAL_HTTP_CONNECTTIMEOUT", "1");
  CPLSetConfigOption("GDAL_VRT_ENABLE_PYTHON", "NO");
  CPLSetConfigOption("PROJ_NETWORK", "OFF");
  OSRSetPROJEnableNetwork(FALSE);
}

void keep_only_documented_drivers() {
  GDALDriverManager* manager = GetGDALDriverManager();
  const std::vector<std::string>& kept = kept_drivers();
  for (int i = manager->GetDriverCount() - 1; i >= 0; --i) {
    GDALDriver* d = manager->GetDriver(i);
    if (std::find(kept.begin(), kept.end(), d->GetDescription()) != kept.end()) continue;
    manager->DeregisterDriver(d);
    GDALDestroyDriver(d);
  }
}

bool is_vrt(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find("<VRTDataset") != std::string::npos;
}

struct XmlFree {
  void operator()(CPLXMLNode* n) const { CPLDestroyXMLNode(n); }
};

void check_vrt_at(const fs::path& vrt, int depth);

// One SourceFilename/SourceDataset of `vrt`: a regular file in the VRT's folder or below it.
void check_vrt_source(const fs::path& vrt, const CPLXMLNode& node, int depth) {
  const std::string text = CPLGetXMLValue(&node, nullptr, "");
  const std::string where = vrt.string() + ": its source " + quoted(text);
  if (names_a_non_file(text))
    throw InputError(where +
                     " is not a local file; a VRT DEM may read only files in its own "
                     "folder or below it");
  const bool relative = CPLTestBool(CPLGetXMLValue(&node, "relativeToVRT", "0"));
  const fs::path folder = fs::weakly_canonical(vrt).parent_path();
  const fs::path source = fs::weakly_canonical(relative ? folder / text : fs::path(text));
  const fs::path inside = source.lexically_relative(folder);
  if (inside.empty() || *inside.begin() == "..")
    throw InputError(where +
                     " lies outside the VRT's folder; a VRT DEM may read only files in "
                     "its own folder or below it");
  std::error_code ec;
  if (!fs::is_regular_file(source, ec)) throw InputError(where + " is not a file");
  if (is_vrt(source)) check_vrt_at(source, depth + 1);
}

void check_vrt_nodes(const fs::path& vrt, const CPLXMLNode* node, int depth) {
  for (; node; node = node->psNext) {
    if (node->eType != CXT_Element) continue;
    const std::string name = node->pszValue;
    if (name == "SourceFilename" || name == "SourceDataset") check_vrt_source(vrt, *node, depth);
    if (name == "VRTRasterBand" &&
        std::string(CPLGetXMLValue(node, "subClass", "")) == "VRTRawRasterBand")
      throw InputError(vrt.string() +
                       ": a VRT raw band is not read (it reads any file as "
                       "heights); convert the DEM to GeoTIFF");
    if (name == "PixelFunctionLanguage" && std::string(CPLGetXMLValue(node, nullptr, "")) != "")
      throw InputError(vrt.string() + ": a VRT pixel function in another language is not run");
    check_vrt_nodes(vrt, node->psChild, depth);
  }
}

void check_vrt_at(const fs::path& vrt, int depth) {
  if (depth > 8) throw InputError(vrt.string() + ": VRTs nested more than 8 deep");
  CPLErrorReset();
  std::unique_ptr<CPLXMLNode, XmlFree> root(CPLParseXMLFile(vrt.c_str()));
  if (!root) throw InputError(vrt.string() + ": not a readable VRT (" + CPLGetLastErrorMsg() + ")");
  check_vrt_nodes(vrt, root.get(), depth);
}

}  // namespace

const std::vector<std::string>& kept_drivers() {
  static const std::vector<std::string> kept = {
      // area files (README: Shapefile, zipped Shapefile, GeoPackage, KML/KMZ, GPX, FlatGeobuf,
      // GML, SQLite, MapInfo TAB, DXF, and GeoJSON with another CRS)
      "ESRI Shapefile", "GPKG", "KML", "LIBKML", "GPX", "FlatGeobuf", "GML", "SQLite",
      "MapInfo File", "DXF", "GeoJSON",
      // DEMs (GeoTIFF, ESRI ASCII grid, SRTM .hgt, VRT; Erdas .img, .bil, USGS .dem, XYZ) and
      // coverage.tif, written through GTiff in memory
      "GTiff", "AAIGrid", "SRTMHGT", "VRT", "HFA", "EHdr", "USGSDEM", "XYZ", "MEM",
      // basemaps (--basemap: orthophotos as GeoTIFF, or PNG and JPEG with a world file; PNG also
      // writes the map page's basemap image, in memory)
      "PNG", "JPEG",
      // PROJ's EGM96 geoid grid (--dem-heights ellipsoid)
      "GTX"};
  return kept;
}

void confine_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    set_network_off();
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);  // errors come back as our sentences
  });
  // Every time: whatever registered GDAL's drivers again since (a program or test of its own
  // calling GDALAllRegister) loses them before swath opens a file. A count and a few compares.
  static std::mutex guard;
  const std::lock_guard<std::mutex> lock(guard);
  if (GetGDALDriverManager()->GetDriverCount() > static_cast<int>(kept_drivers().size()))
    keep_only_documented_drivers();
}

std::string local_gdal_path(const std::string& path, const std::string& what) {
  if (path.rfind("/vsi", 0) == 0)
    throw InputError(path + ": a GDAL virtual path is not read; give the " + what +
                     " as a file on disk");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    if (names_a_non_file(path))
      throw InputError(path + ": not a file; swath reads the " + what +
                       " from a local file, never from a URL, database or service");
    throw InputError(path + ": cannot open the " + what + " (no such file)");
  }
  if (!fs::is_regular_file(status))
    throw InputError(path + ": the " + what + " is not a regular file");
  // Absolute, so that GDAL never reads a prefix of the name (`PG:x` in the current folder).
  return fs::absolute(path, ec).lexically_normal().string();
}

void check_vrt(const std::string& path) {
  if (is_vrt(path)) check_vrt_at(path, 0);
}

}  // namespace swath::geometry::detail

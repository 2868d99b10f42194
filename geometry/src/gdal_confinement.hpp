#pragma once
// Internal to the GIS module: GDAL kept to what swath documents. GDAL opens whatever its ~200
// drivers recognise, by content, not by name: a 140-byte OGR VRT named `.gpkg` makes it fetch a
// URL, `PG:` opens a database connection, a GDAL_WMS XML named `.tif` downloads tiles, a VRT raw
// band reads any file on the machine (/etc/passwd as terrain). swath reads area files and DEMs
// the user named, from the local disk, and nothing else:
// - only the drivers of the formats swath documents stay registered (kept_drivers());
// - every network path is off before any file is opened: /vsicurl/ and its kin accept no file
//   name, HTTP goes through a proxy at 127.0.0.1:0 (which fails at once, no packet leaves the
//   machine) with no retries, PROJ's network grids are off;
// - a path reaches GDAL only as the absolute path of an existing regular file, so no connection
//   string (`PG:…`, `WFS:…`) or virtual path (`/vsicurl/…`) typed as a file name is ever opened;
// - a VRT DEM may read only regular files in its own folder or below it, no raw bands and no
//   Python pixel functions (checked by reading its XML before GDAL does).

#include <string>
#include <vector>

namespace swath::geometry::detail {

/// Registers GDAL's drivers and confines GDAL as above, once per process (thread-safe). Every
/// entry of the GIS module calls it before touching GDAL.
void confine_gdal();

/// The drivers confine_gdal() keeps: the vector formats of area files, the raster formats of
/// DEMs, and GTiff for coverage.tif.
const std::vector<std::string>& kept_drivers();

/// The path to give GDAL for `path`, a file the user named as `what` ("area file", "DEM"): its
/// absolute, normalised form. Throws base::InputError for a GDAL virtual path (/vsi…), a URL or
/// connection string, or anything that is not an existing regular file (symlinks followed).
std::string local_gdal_path(const std::string& path, const std::string& what);

/// Throws base::InputError when `path` is a VRT that reads anything but regular files in its own
/// folder or below it (a URL, a /vsi… path, a connection string, a file elsewhere), has a raw
/// band or a Python pixel function. VRTs within VRTs are checked the same way, 8 deep at most.
/// Other files pass.
void check_vrt(const std::string& path);

}  // namespace swath::geometry::detail

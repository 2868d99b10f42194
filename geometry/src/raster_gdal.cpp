// Raster sampling through GDAL for the GIS module (raster_gdal.hpp).
#include "raster_gdal.hpp"

#include "gdal_confinement.hpp"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "swath/base/input_error.hpp"

namespace swath::geometry::detail {
namespace {

using base::InputError;

struct Raster {
  GDALDataset* dataset = nullptr;  // open for the process
  GDALRasterBand* band = nullptr;
  std::unique_ptr<OGRCoordinateTransformation> from_wgs84;  // null: the raster is in WGS84
  double inverse[6]{};                                      // georeferenced -> pixel/line
  int width = 0, height = 0;
  bool has_nodata = false;
  double nodata = 0.0;
  bool float32 = false;  // the band's type: its NoData value is compared as a float
  double resolution_m = 0.0;
  double metres_per_unit = 1.0;  // the band's unit (GDAL unit type: m, ft, US survey foot)
};

// Metres per unit of a band's GDAL unit type; 0 for a unit swath does not know.
double vertical_unit_m(std::string unit) {
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" ||
      unit == "meters")
    return 1.0;
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot")
    return 0.3048;
  if (unit == "us survey foot" || unit == "ftus" || unit == "us-ft" || unit == "us_survey_foot")
    return 1200.0 / 3937.0;
  return 0.0;
}

std::string gdal_error() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("GDAL cannot read it");
}

Raster open_raster(const std::string& path) {
  confine_gdal();
  const std::string local = local_gdal_path(path, "DEM");
  check_vrt(local);
  Raster r;
  r.dataset = GDALDataset::Open(local.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  if (!r.dataset) throw InputError(path + ": not a raster GDAL reads (" + gdal_error() + ")");
  if (r.dataset->GetRasterCount() < 1) throw InputError(path + ": the raster has no band");
  r.band = r.dataset->GetRasterBand(1);
  r.width = r.dataset->GetRasterXSize();
  r.height = r.dataset->GetRasterYSize();
  r.metres_per_unit = vertical_unit_m(r.band->GetUnitType());
  if (r.metres_per_unit == 0.0)
    throw InputError(path + ": heights in \"" + std::string(r.band->GetUnitType()) +
                     "\", a unit swath does not know (metres, feet, US survey feet)");
  int ok = 0;
  r.nodata = r.band->GetNoDataValue(&ok);
  r.float32 = r.band->GetRasterDataType() == GDT_Float32;
  r.has_nodata = ok != 0;
  double gt[6];
  if (r.dataset->GetGeoTransform(gt) != CE_None)
    throw InputError(path + ": the raster is not georeferenced (no geotransform)");
  if (!GDALInvGeoTransform(gt, r.inverse))
    throw InputError(path + ": the raster's geotransform cannot be inverted");
  const double px = std::hypot(gt[1], gt[4]), py = std::hypot(gt[2], gt[5]);
  double unit_m = 1.0;
  const OGRSpatialReference* srs = r.dataset->GetSpatialRef();
  if (srs && !srs->IsEmpty()) {
    OGRSpatialReference wgs84, to(*srs);
    wgs84.importFromEPSG(4326);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (srs->IsGeographic()) {
      unit_m = 111'320.0 * srs->GetAngularUnits() / (M_PI / 180.0);
    } else {
      unit_m = srs->GetLinearUnits();
    }
    if (!to.IsSame(&wgs84)) {
      r.from_wgs84.reset(OGRCreateCoordinateTransformation(&wgs84, &to));
      if (!r.from_wgs84)
        throw InputError(path + ": its CRS cannot be reached from WGS84 (" + gdal_error() + ")");
    }
  } else {
    unit_m = 111'320.0;  // no CRS: longitude/latitude degrees, as for area files
  }
  r.resolution_m = std::max(0.05, 0.5 * std::min(px, py) * unit_m);
  return r;
}

Raster& raster(const std::string& path) {
  static std::map<std::string, Raster> open;
  auto it = open.find(path);
  if (it == open.end()) it = open.emplace(path, open_raster(path)).first;
  return it->second;
}

double pixel(Raster& r, int i, int j) {
  i = std::clamp(i, 0, r.width - 1);
  j = std::clamp(j, 0, r.height - 1);
  double v = 0;
  if (r.band->RasterIO(GF_Read, i, j, 1, 1, &v, 1, 1, GDT_Float64, 0, 0) != CE_None)
    return std::numeric_limits<double>::quiet_NaN();
  // A Float32 band holds its NoData value rounded to float (1e30 is 1.0000000150e30 there).
  const bool nodata =
      r.has_nodata &&
      (v == r.nodata || (r.float32 && static_cast<float>(v) == static_cast<float>(r.nodata)));
  if (nodata || !std::isfinite(v)) return std::numeric_limits<double>::quiet_NaN();
  return v;
}

// A height no ground on Earth has (the Dead Sea shore is -430 m, Everest 8,849 m): an undeclared
// void (SRTM's -32768 in a GeoTIFF without a NoData tag, a 1e30 fill) or heights in another unit.
// Read as ground it put waypoints at -33,128 m or 1e30 m: refused with its place instead.
void check_on_earth(double height_m, const GeoPoint& at, const std::string& path) {
  constexpr double kLowest_m = -430.0, kHighest_m = 8'850.0;
  if (std::isnan(height_m) || (height_m >= kLowest_m && height_m <= kHighest_m)) return;
  char place[96];
  std::snprintf(place, sizeof place, "%.7f, %.7f", at.lat_deg, at.lon_deg);
  char value[32];
  std::snprintf(value, sizeof value, "%.6g", height_m);
  throw InputError(path + ": the ground near " + place + " (lat, lon) is " + value +
                   " m, beyond any on Earth (-430 to 8,850 m): a void without a NoData value, or "
                   "heights in another unit? Give the DEM a NoData value or its unit");
}

}  // namespace

void sample_raster(const std::string& path, const std::vector<GeoPoint>& points,
                   std::vector<double>& values, double& resolution_m) {
  static std::mutex guard;
  const std::lock_guard<std::mutex> lock(guard);
  Raster& r = raster(path);
  resolution_m = r.resolution_m;
  values.assign(points.size(), std::numeric_limits<double>::quiet_NaN());
  if (points.empty()) return;
  std::vector<double> x(points.size()), y(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    x[k] = points[k].lon_deg;
    y[k] = points[k].lat_deg;
  }
  std::vector<int> ok(points.size(), 1);
  if (r.from_wgs84 && !r.from_wgs84->Transform(static_cast<int>(points.size()), x.data(), y.data(),
                                               nullptr, ok.data()))
    std::fill(ok.begin(), ok.end(), 0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!ok[k]) continue;
    const double* t = r.inverse;
    const double pi = t[0] + t[1] * x[k] + t[2] * y[k];  // pixel, line (0 at the raster's edge)
    const double pj = t[3] + t[4] * x[k] + t[5] * y[k];
    if (!(pi >= 0 && pi <= r.width && pj >= 0 && pj <= r.height)) continue;
    const double u = pi - 0.5, v = pj - 0.5;  // between pixel centres
    const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(v));
    const double fu = u - i0, fv = v - j0;
    const double a = pixel(r, i0, j0), b = pixel(r, i0 + 1, j0);
    const double c = pixel(r, i0, j0 + 1), d = pixel(r, i0 + 1, j0 + 1);
    for (const double h : {a, b, c, d}) check_on_earth(r.metres_per_unit * h, points[k], path);
    values[k] =
        r.metres_per_unit * ((1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d));
  }
}

std::string proj_grid(const std::string& name) {
  std::vector<std::string> dirs;
  if (char** paths = OSRGetPROJSearchPaths()) {
    for (char** p = paths; *p; ++p) dirs.emplace_back(*p);
    CSLDestroy(paths);
  }
  dirs.emplace_back("/usr/share/proj");
  for (const std::string& d : dirs) {
    std::error_code ec;
    const auto f = std::filesystem::path(d) / name;
    if (std::filesystem::exists(f, ec)) return f.string();
  }
  throw InputError("PROJ's geoid grid " + name +
                   " is not installed (Debian: apt-get install proj-data); it converts "
                   "ellipsoidal DEM heights to heights above sea level");
}

std::string geotiff(const LocalRaster& raster) {
  confine_gdal();
  static std::mutex guard;
  const std::lock_guard<std::mutex> lock(guard);
  const std::string path = "/vsimem/swath-coverage.tif";
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!gtiff) throw std::runtime_error("GDAL has no GTiff driver");
  char** options = nullptr;
  options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
  options = CSLSetNameValue(options, "PREDICTOR", "2");
  const int bands = static_cast<int>(raster.bands.size());
  GDALDataset* d =
      gtiff->Create(path.c_str(), raster.width, raster.height, bands, GDT_UInt16, options);
  CSLDestroy(options);
  if (!d) throw std::runtime_error("GDAL cannot create a GeoTIFF (" + gdal_error() + ")");
  double gt[6] = {raster.west_m, raster.cell_m, 0, raster.north_m, 0, -raster.cell_m};
  d->SetGeoTransform(gt);
  OGRSpatialReference srs;
  char proj[256];
  std::snprintf(proj, sizeof proj,
                "+proj=ortho +lat_0=%.12f +lon_0=%.12f +x_0=0 +y_0=0 +ellps=WGS84 +units=m "
                "+no_defs",
                raster.origin.lat_deg, raster.origin.lon_deg);
  srs.importFromProj4(proj);
  d->SetSpatialRef(&srs);
  bool ok = true;
  for (int b = 0; b < bands; ++b) {
    GDALRasterBand* band = d->GetRasterBand(b + 1);
    band->SetDescription(raster.bands[static_cast<std::size_t>(b)].first.c_str());
    auto& values =
        const_cast<std::vector<std::uint16_t>&>(raster.bands[static_cast<std::size_t>(b)].second);
    ok = ok && band->RasterIO(GF_Write, 0, 0, raster.width, raster.height, values.data(),
                              raster.width, raster.height, GDT_UInt16, 0, 0) == CE_None;
  }
  GDALClose(d);
  vsi_l_offset size = 0;
  GByte* data = VSIGetMemFileBuffer(path.c_str(), &size, FALSE);
  std::string bytes = ok && data ? std::string(reinterpret_cast<const char*>(data), size) : "";
  VSIUnlink(path.c_str());
  if (bytes.empty())
    throw std::runtime_error("GDAL cannot write the GeoTIFF (" + gdal_error() + ")");
  return bytes;
}

}  // namespace swath::geometry::detail

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
#include <unordered_map>

#include "swath/base/input_error.hpp"

namespace swath::geometry::detail {
namespace {

using base::InputError;

// Pixels are read a tile at a time into memory (kTile x kTile, with a one-pixel rim for the
// neighbour check): one-pixel RasterIO calls cost ~10 us each, and a plan over a fine DEM samples
// millions of pixels (a 2.5 cm DEM over a 2 km field took 130 s); GDAL's drivers also re-scan a
// truncated ASCII grid from its start on every failed one-pixel read (a hang past 300 s).
constexpr int kTile = 64;
// At most this many tiles in memory (32 KB each, 32 MB in all); then they are dropped and read
// again as needed: the samples of a leg lie along a line, so few are read twice.
constexpr std::size_t kMaxTiles = 1024;

struct Raster {
  GDALDataset* dataset = nullptr;  // open for the process
  GDALRasterBand* band = nullptr;
  std::string local;  // the path GDAL was given (absolute): in GDAL's messages, shown as given
  std::unique_ptr<OGRCoordinateTransformation> from_wgs84;  // null: the raster is in WGS84
  double inverse[6]{};                                      // georeferenced -> pixel/line
  int width = 0, height = 0;
  bool has_nodata = false;
  double nodata = 0.0;
  bool float32 = false;  // the band's type: its NoData value is compared as a float
  double resolution_m = 0.0;
  double pixel_m = 0.0;          // the pixel's shorter side, metres
  double asked_unit_m = 0.0;     // --dem-units (0: not given)
  double metres_per_unit = 1.0;  // the band's unit (GDAL unit type: m, ft, US survey foot)
  std::unordered_map<std::uint64_t, std::vector<double>> tiles;  // by tile_key(); NaN: no data
  DemReads reads;
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

// The unit as a sentence's words ("feet"), for messages.
std::string unit_words(double metres_per_unit) {
  if (metres_per_unit == 1.0) return "metres";
  if (metres_per_unit == 0.3048) return "feet";
  return "US survey feet";
}

// The band's heights unit: the one it declares, else --dem-units (asked_unit_m, 0 when not given),
// else metres. A declared unit that --dem-units contradicts is refused: one of them is wrong.
double heights_unit_m(GDALRasterBand& band, double asked_unit_m, const std::string& path) {
  const std::string declared = band.GetUnitType() ? band.GetUnitType() : "";
  const double unit_m = vertical_unit_m(declared);
  if (unit_m == 0.0)
    throw InputError(path + ": heights in \"" + declared +
                     "\", a unit swath does not know (metres, feet, US survey feet)");
  if (declared.empty()) return asked_unit_m > 0 ? asked_unit_m : 1.0;
  if (asked_unit_m > 0 && asked_unit_m != unit_m)
    throw InputError(path + ": the DEM declares its heights in \"" + declared + "\" (" +
                     unit_words(unit_m) + "), but --dem-units says " + unit_words(asked_unit_m) +
                     "; leave --dem-units out or fix the DEM's unit");
  return unit_m;
}

// A DEM without a CRS is read as longitudes and latitudes; one whose corners cannot be (a
// projected grid whose .prj was left behind) is refused as such, not as "no height" at a home.
void check_degrees(const double gt[6], int width, int height, const std::string& path) {
  for (const int col : {0, width})
    for (const int row : {0, height}) {
      const double x = gt[0] + gt[1] * col + gt[2] * row, y = gt[3] + gt[4] * col + gt[5] * row;
      if (std::abs(x) <= 180 && std::abs(y) <= 90) continue;
      char corner[64];  // the module links no swath_base (number_text)
      std::snprintf(corner, sizeof corner, "(%.1f, %.1f)", x, y);
      throw InputError(path + ": the DEM has no coordinate reference system and its corner " +
                       corner +
                       " is no longitude and latitude; give its CRS in a .prj file beside it "
                       "(same name, .prj: e.g. gdalsrsinfo -o wkt_esri EPSG:32632)");
    }
}

Raster open_raster(const std::string& path, double asked_unit_m) {
  confine_gdal();
  const std::string local = local_gdal_path(path, "DEM");
  check_vrt(local);
  Raster r;
  r.local = local;
  CPLErrorReset();
  r.dataset = GDALDataset::Open(local.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  if (!r.dataset) throw InputError(path + ": not a raster GDAL reads (" + gdal_error() + ")");
  if (r.dataset->GetRasterCount() < 1) throw InputError(path + ": the raster has no band");
  r.band = r.dataset->GetRasterBand(1);
  r.width = r.dataset->GetRasterXSize();
  r.height = r.dataset->GetRasterYSize();
  r.asked_unit_m = asked_unit_m;
  r.metres_per_unit = heights_unit_m(*r.band, asked_unit_m, path);
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
    check_degrees(gt, r.width, r.height, path);
    unit_m = 111'320.0;  // no CRS: longitude/latitude degrees, as for area files
  }
  r.pixel_m = std::min(px, py) * unit_m;
  r.resolution_m = std::max(0.05, 0.5 * r.pixel_m);
  return r;
}

std::map<std::string, Raster>& open_rasters() {
  static std::map<std::string, Raster> open;
  return open;
}

void close_raster(const std::string& path) {
  auto& open = open_rasters();
  auto it = open.find(path);
  if (it == open.end()) return;
  GDALClose(it->second.dataset);
  open.erase(it);
}

void index_text_rows(Raster& r, const std::string& path);

// The raster at `path`, opened on first use; again when --dem-units differs.
Raster& raster(const std::string& path, double asked_unit_m) {
  auto& open = open_rasters();
  auto it = open.find(path);
  if (it != open.end() && it->second.asked_unit_m != asked_unit_m) {
    close_raster(path);
    it = open.end();
  }
  if (it == open.end()) {
    Raster fresh = open_raster(path, asked_unit_m);
    index_text_rows(fresh, path);  // may refuse the file: then nothing is kept open
    it = open.emplace(path, std::move(fresh)).first;
  }
  return it->second;
}

bool is_nodata(const Raster& r, double v) {
  // A Float32 band holds its NoData value rounded to float (1e30 is 1.0000000150e30 there).
  const bool nodata =
      r.has_nodata &&
      (v == r.nodata || (r.float32 && static_cast<float>(v) == static_cast<float>(r.nodata)));
  return nodata || !std::isfinite(v);
}

std::uint64_t tile_key(int ti, int tj) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(tj)) << 32) |
         static_cast<std::uint32_t>(ti);
}

// GDAL's first error message while in scope (its root cause: a truncated GeoTIFF reports "Read
// error at scanline 15; got 433 bytes, expected 1020" first and "IReadBlock failed" last), kept
// from GDAL's stderr so that the refusal stays one sentence.
class FirstGdalError {
 public:
  FirstGdalError() {
    CPLErrorReset();
    CPLPushErrorHandlerEx(handler, this);
  }
  ~FirstGdalError() { CPLPopErrorHandler(); }
  FirstGdalError(const FirstGdalError&) = delete;
  FirstGdalError& operator=(const FirstGdalError&) = delete;
  std::string reason() const { return first_.empty() ? gdal_error() : first_; }

 private:
  static void CPL_STDCALL handler(CPLErr level, CPLErrorNum, const char* message) {
    auto* self = static_cast<FirstGdalError*>(CPLGetErrorHandlerUserData());
    if (level >= CE_Failure && self->first_.empty() && message) self->first_ = message;
  }
  std::string first_;
};

// A DEM row GDAL cannot read, as one sentence naming the file as the user gave it (GDAL names it
// by the absolute path it was given) and GDAL's reason.
InputError row_error(const Raster& r, const std::string& path, int row, std::string reason) {
  for (std::size_t at = 0; !r.local.empty() && (at = reason.find(r.local, at)) != std::string::npos;
       at += path.size())
    reason.replace(at, r.local.size(), path);
  return InputError(path + ": cannot read the DEM's row " + std::to_string(row + 1) + " of " +
                    std::to_string(r.height) + " (" + reason + ")");
}

// Reads rows [y0, y0 + h) of columns [x0, x0 + w) into `out` (w x h, row by row). A failed read
// names the first row GDAL cannot read and GDAL's reason (a truncated file, a bad block).
void read_window(Raster& r, int x0, int y0, int w, int h, std::vector<double>& out,
                 const std::string& path) {
  out.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0);
  ++r.reads.tiles;
  r.reads.pixels += out.size();
  std::string reason;
  {
    const FirstGdalError errors;
    if (r.band->RasterIO(GF_Read, x0, y0, w, h, out.data(), w, h, GDT_Float64, 0, 0) == CE_None)
      return;
    reason = errors.reason();
  }
  int bad = y0;
  for (int y = y0; y < y0 + h; ++y) {  // which row: read them one by one
    const FirstGdalError errors;
    if (r.band->RasterIO(GF_Read, x0, y, w, 1, out.data(), w, 1, GDT_Float64, 0, 0) != CE_None) {
      bad = y;
      break;
    }
  }
  throw row_error(r, path, bad, reason);
}

// An ESRI ASCII grid is read by GDAL a line at a time, and a row's place in the file is found by
// reading every row before it; where one of those fails to parse, GDAL starts over from the top
// for each row after it, recursively: a malformed grid of a few hundred rows then takes forever
// (libFuzzer: a 503-byte file ran for over ten minutes). Reading the rows once in order, at
// open, leaves GDAL every row's place, and a row that does not parse refuses the file at once.
// Costs one pass over the file; other formats are read by block and need none.
void index_text_rows(Raster& r, const std::string& path) {
  const GDALDriver* driver = r.dataset->GetDriver();
  if (!driver || std::string(driver->GetDescription()) != "AAIGrid") return;
  std::vector<double> row(static_cast<std::size_t>(r.width));
  for (int y = 0; y < r.height; ++y) {
    const FirstGdalError errors;
    if (r.band->RasterIO(GF_Read, 0, y, r.width, 1, row.data(), r.width, 1, GDT_Float64, 0, 0) !=
        CE_None)
      throw row_error(r, path, y, errors.reason());
  }
}

// A pixel that stands above or below every neighbour by more than a needle of ten times its width
// (and 250 m) could be no ground: an undeclared void filled with 0 in the mountains, a stray
// 9000 in a valley. Heights beyond the Earth's are left to check_on_earth(), which names the
// point. Checked once per tile, from the tile and its rim.
void check_spikes(const Raster& r, int x0, int y0, int w, int h, const std::vector<double>& rim,
                  int rx0, int ry0, int rw, const std::string& path) {
  const double limit_m = std::max(250.0, 10.0 * r.pixel_m);
  auto at = [&](int i, int j) { return rim[static_cast<std::size_t>((j - ry0) * rw + (i - rx0))]; };
  auto ground = [&](double v) {
    const double m = r.metres_per_unit * v;
    return !is_nodata(r, v) && m >= -430.0 && m <= 8'850.0;
  };
  const int rh = static_cast<int>(rim.size()) / rw;
  for (int j = y0; j < y0 + h; ++j)
    for (int i = x0; i < x0 + w; ++i) {
      const double v = at(i, j);
      if (!ground(v)) continue;
      double above = std::numeric_limits<double>::infinity(), below = above;  // least margins
      int neighbours = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj;
          if ((di == 0 && dj == 0) || ni < rx0 || nj < ry0 || ni >= rx0 + rw || nj >= ry0 + rh)
            continue;
          const double n = at(ni, nj);
          if (!ground(n)) continue;
          ++neighbours;
          above = std::min(above, r.metres_per_unit * (v - n));
          below = std::min(below, r.metres_per_unit * (n - v));
        }
      if (neighbours < 3 || (above <= limit_m && below <= limit_m)) continue;
      char value[32];
      std::snprintf(value, sizeof value, "%.6g", r.metres_per_unit * v);
      throw InputError(path + ": the ground at row " + std::to_string(j + 1) + ", column " +
                       std::to_string(i + 1) + " is " + value + " m, " +
                       std::to_string(static_cast<long long>(std::max(
                           above > limit_m ? above : 0.0, below > limit_m ? below : 0.0))) +
                       " m " + (above > limit_m ? "above" : "below") +
                       " every pixel around it: a void without a NoData value? Give the DEM a "
                       "NoData value or fill the void");
    }
}

const std::vector<double>& tile(Raster& r, int ti, int tj, const std::string& path) {
  const std::uint64_t key = tile_key(ti, tj);
  if (auto it = r.tiles.find(key); it != r.tiles.end()) return it->second;
  if (r.tiles.size() >= kMaxTiles) r.tiles.clear();
  const int x0 = ti * kTile, y0 = tj * kTile;
  const int w = std::min(kTile, r.width - x0), h = std::min(kTile, r.height - y0);
  const int rx0 = std::max(0, x0 - 1), ry0 = std::max(0, y0 - 1);
  const int rw = std::min(r.width, x0 + w + 1) - rx0, rh = std::min(r.height, y0 + h + 1) - ry0;
  std::vector<double> rim;
  read_window(r, rx0, ry0, rw, rh, rim, path);
  check_spikes(r, x0, y0, w, h, rim, rx0, ry0, rw, path);
  std::vector<double> t(static_cast<std::size_t>(kTile) * kTile,
                        std::numeric_limits<double>::quiet_NaN());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double v = rim[static_cast<std::size_t>((y0 + j - ry0) * rw + (x0 + i - rx0))];
      t[static_cast<std::size_t>(j * kTile + i)] =
          is_nodata(r, v) ? std::numeric_limits<double>::quiet_NaN() : v;
    }
  return r.tiles.emplace(key, std::move(t)).first->second;
}

double pixel(Raster& r, int i, int j, const std::string& path) {
  i = std::clamp(i, 0, r.width - 1);
  j = std::clamp(j, 0, r.height - 1);
  const std::vector<double>& t = tile(r, i / kTile, j / kTile, path);
  return t[static_cast<std::size_t>((j % kTile) * kTile + i % kTile)];
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

std::mutex& rasters_guard() {
  static std::mutex guard;
  return guard;
}

}  // namespace

void sample_raster(const std::string& path, double asked_unit_m,
                   const std::vector<GeoPoint>& points, std::vector<double>& values,
                   double& resolution_m) {
  const std::lock_guard<std::mutex> lock(rasters_guard());
  Raster& r = raster(path, asked_unit_m);
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
    const double a = pixel(r, i0, j0, path), b = pixel(r, i0 + 1, j0, path);
    const double c = pixel(r, i0, j0 + 1, path), d = pixel(r, i0 + 1, j0 + 1, path);
    for (const double h : {a, b, c, d}) check_on_earth(r.metres_per_unit * h, points[k], path);
    values[k] =
        r.metres_per_unit * ((1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d));
  }
}

void raster_bends(const std::string& path, double asked_unit_m, const GeoPoint& a,
                  const GeoPoint& b, std::vector<double>& fractions) {
  const std::lock_guard<std::mutex> lock(rasters_guard());
  Raster& r = raster(path, asked_unit_m);
  fractions.clear();
  double x[2] = {a.lon_deg, b.lon_deg}, y[2] = {a.lat_deg, b.lat_deg};
  int ok[2] = {1, 1};
  if (r.from_wgs84 && (!r.from_wgs84->Transform(2, x, y, nullptr, ok) || !ok[0] || !ok[1])) return;
  const double* t = r.inverse;
  // Between pixel centres: the bilinear cells' edges are at whole numbers of u and v.
  const double u[2] = {t[0] + t[1] * x[0] + t[2] * y[0] - 0.5,
                       t[0] + t[1] * x[1] + t[2] * y[1] - 0.5};
  const double v[2] = {t[3] + t[4] * x[0] + t[5] * y[0] - 0.5,
                       t[3] + t[4] * x[1] + t[5] * y[1] - 0.5};
  for (const double* w : {u, v}) {
    if (!(std::abs(w[1] - w[0]) > 0)) continue;
    const double lo = std::min(w[0], w[1]), hi = std::max(w[0], w[1]);
    for (double k = std::floor(lo) + 1; k < hi; ++k) {
      const double f = (k - w[0]) / (w[1] - w[0]);
      if (f > 0 && f < 1) fractions.push_back(f);
    }
  }
  std::sort(fractions.begin(), fractions.end());
}

DemReads raster_reads(const std::string& path) {
  const std::lock_guard<std::mutex> lock(rasters_guard());
  auto& open = open_rasters();
  auto it = open.find(path);
  return it == open.end() ? DemReads{} : it->second.reads;
}

void forget_raster(const std::string& path) {
  const std::lock_guard<std::mutex> lock(rasters_guard());
  close_raster(path);
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

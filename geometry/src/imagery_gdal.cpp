// The basemap's raster through GDAL, for the GIS module (imagery_gdal.hpp).
#include "imagery_gdal.hpp"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "gdal_confinement.hpp"
#include "swath/base/input_error.hpp"

namespace swath::geometry::detail {
namespace {

using base::InputError;

// A picture's window of the raster is read into at most this many pixels a side (GDAL averages
// down to it): a band of floats is 64 MB at most, and the finest basemap tiles the page's budget
// allows (apps/swath/basemap.hpp) are at most about this wide.
constexpr int kMaxReadSide = 4096;

std::string gdal_reason() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("GDAL cannot read it");
}

struct Opened {
  GDALDatasetUniquePtr dataset;
  double inverse[6]{};  // georeferenced -> pixel/line
  std::unique_ptr<OGRCoordinateTransformation> from_wgs84;
  double pixel_m = 0;
};

Opened open_imagery(const std::string& path) {
  confine_gdal();
  const std::string local = local_gdal_path(path, "basemap");
  check_vrt(local);
  Opened o;
  CPLErrorReset();
  o.dataset.reset(GDALDataset::Open(local.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!o.dataset) throw InputError(path + ": not a raster GDAL reads (" + gdal_reason() + ")");
  if (o.dataset->GetRasterCount() < 1) throw InputError(path + ": the raster has no band");
  double gt[6];
  if (o.dataset->GetGeoTransform(gt) != CE_None || !GDALInvGeoTransform(gt, o.inverse))
    throw InputError(path +
                     ": the raster has no georeference (no geotransform): swath cannot tell "
                     "where on the Earth it lies");
  const OGRSpatialReference* srs = o.dataset->GetSpatialRef();
  if (!srs || srs->IsEmpty())
    throw InputError(path +
                     ": the raster has no georeference (no CRS): swath cannot tell where on the "
                     "Earth it lies");
  OGRSpatialReference wgs84, to(*srs);
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x longitude, y latitude
  to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  o.from_wgs84.reset(OGRCreateCoordinateTransformation(&wgs84, &to));
  if (!o.from_wgs84)
    throw InputError(path + ": its CRS cannot be reached from WGS84 (" + gdal_reason() + ")");
  const double unit_m = srs->IsGeographic() ? 111'320.0 * srs->GetAngularUnits() / (M_PI / 180.0)
                                            : srs->GetLinearUnits();
  o.pixel_m = std::min(std::hypot(gt[1], gt[4]), std::hypot(gt[2], gt[5])) * unit_m;
  return o;
}

// Each raster opened once for the process and kept open (with GDAL's block cache, what one
// picture read the next reads from memory): coverage.png and every zoom level of plan.html's
// tiles come from one open. Reopened when the file changes (size or time). Never destroyed: GDAL
// may be gone before static destructors run.
struct Cached {
  Opened opened;
  std::uintmax_t size = 0;
  std::filesystem::file_time_type time{};
};
struct Cache {
  std::mutex guard;
  std::map<std::string, Cached> open;
  std::map<std::string, std::size_t> opens;  // GDAL opens by path, for imagery_opens()
};
Cache& cache() {
  static Cache* const c = new Cache;
  return *c;
}

// The file's size and time, or zeros when it is no plain file (a /vsi path, a URL).
std::pair<std::uintmax_t, std::filesystem::file_time_type> stamp(const std::string& path) {
  std::error_code e;
  const auto size = std::filesystem::file_size(path, e);
  if (e) return {0, {}};
  return {size, std::filesystem::last_write_time(path, e)};
}

// With cache().guard held.
Opened& open_cached(const std::string& path) {
  Cache& c = cache();
  const auto [size, time] = stamp(path);
  auto it = c.open.find(path);
  if (it != c.open.end() && it->second.size == size && it->second.time == time)
    return it->second.opened;
  if (it != c.open.end()) c.open.erase(it);
  Opened o = open_imagery(path);  // throws: nothing kept
  ++c.opens[path];
  return c.open.emplace(path, Cached{std::move(o), size, time}).first->second.opened;
}

// The raster's pixel (column, line) of each node; NaN where PROJ cannot place it.
std::vector<std::array<double, 2>> node_pixels(const Opened& o, const ImageryGrid& g) {
  const std::size_t n = g.nodes.size();
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = g.nodes[k].lon_deg, y[k] = g.nodes[k].lat_deg;
  std::vector<int> ok(n, 1);
  if (!o.from_wgs84->Transform(static_cast<int>(n), x.data(), y.data(), nullptr, ok.data()))
    std::fill(ok.begin(), ok.end(), 0);
  std::vector<std::array<double, 2>> out(n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double* t = o.inverse;
  for (std::size_t k = 0; k < n; ++k)
    out[k] = ok[k] ? std::array<double, 2>{t[0] + t[1] * x[k] + t[2] * y[k],
                                           t[3] + t[4] * x[k] + t[5] * y[k]}
                   : std::array<double, 2>{nan, nan};
  return out;
}

// A window of the raster read into memory as RGBA, `w` x `h` samples over raster pixels
// [x0, x0 + span_x) x [y0, y0 + span_y).
struct Window {
  int x0 = 0, y0 = 0, span_x = 0, span_y = 0, w = 0, h = 0;
  std::vector<std::uint8_t> rgba;
};

// Band values to 8 bits: Byte bands as they are, others stretched over their values in view.
std::vector<std::uint8_t> to_bytes(GDALRasterBand& band, const std::vector<float>& v,
                                   std::vector<bool>& nodata) {
  int has = 0;
  const double nd = band.GetNoDataValue(&has);
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]) || (has && static_cast<float>(nd) == v[k])) nodata[k] = true;
  double lo = 0, hi = 255;
  if (band.GetRasterDataType() != GDT_Byte) {
    lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!nodata[k]) lo = std::min<double>(lo, v[k]), hi = std::max<double>(hi, v[k]);
    if (!(hi > lo)) hi = lo + 1;
  }
  std::vector<std::uint8_t> out(v.size());
  for (std::size_t k = 0; k < v.size(); ++k)
    out[k] =
        static_cast<std::uint8_t>(std::clamp(std::lround((v[k] - lo) / (hi - lo) * 255), 0L, 255L));
  return out;
}

Window read_window(Opened& o, int x0, int y0, int x1, int y1, const std::string& path) {
  Window win;
  win.x0 = x0, win.y0 = y0, win.span_x = x1 - x0, win.span_y = y1 - y0;
  win.w = std::min(win.span_x, kMaxReadSide), win.h = std::min(win.span_y, kMaxReadSide);
  const std::size_t n = static_cast<std::size_t>(win.w) * static_cast<std::size_t>(win.h);
  const int count = std::min(o.dataset->GetRasterCount(), 4);
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.eResampleAlg = GRIORA_Average;
  std::vector<std::vector<std::uint8_t>> bands;
  std::vector<bool> nodata(n, false);
  for (int b = 1; b <= count; ++b) {
    GDALRasterBand& band = *o.dataset->GetRasterBand(b);
    std::vector<float> v(n);
    CPLErrorReset();
    if (band.RasterIO(GF_Read, x0, y0, win.span_x, win.span_y, v.data(), win.w, win.h, GDT_Float32,
                      0, 0, &extra) != CE_None)
      throw InputError(path + ": cannot read band " + std::to_string(b) + " (" + gdal_reason() +
                       ")");
    bands.push_back(to_bytes(band, v, nodata));
  }
  win.rgba.assign(4 * n, 0);
  const GDALColorTable* palette =
      count == 1 ? o.dataset->GetRasterBand(1)->GetColorTable() : nullptr;
  for (std::size_t k = 0; k < n; ++k) {
    std::array<std::uint8_t, 4> p{};
    if (palette) {
      const GDALColorEntry* e = palette->GetColorEntry(bands[0][k]);
      if (e)
        p = {static_cast<std::uint8_t>(e->c1), static_cast<std::uint8_t>(e->c2),
             static_cast<std::uint8_t>(e->c3), static_cast<std::uint8_t>(e->c4)};
    } else if (count <= 2) {
      p = {bands[0][k], bands[0][k], bands[0][k], count == 2 ? bands[1][k] : std::uint8_t{255}};
    } else {
      p = {bands[0][k], bands[1][k], bands[2][k], count == 4 ? bands[3][k] : std::uint8_t{255}};
    }
    if (nodata[k]) p[3] = 0;
    std::copy(p.begin(), p.end(), win.rgba.begin() + static_cast<std::ptrdiff_t>(4 * k));
  }
  return win;
}

}  // namespace

std::size_t imagery_opens(const std::string& path) {
  const std::lock_guard<std::mutex> lock(cache().guard);
  const auto it = cache().opens.find(path);
  return it == cache().opens.end() ? 0 : it->second;
}

std::string imagery_rgba(const std::string& path, const ImageryGrid& g, double& pixel_m) {
  const std::lock_guard<std::mutex> lock(cache().guard);
  Opened& o = open_cached(path);
  pixel_m = o.pixel_m;
  if (g.nodes.empty()) return "";
  const auto px = node_pixels(o, g);
  // The raster's part in view (a pixel's rim more), clamped to the raster.
  const int width = o.dataset->GetRasterXSize(), height = o.dataset->GetRasterYSize();
  double lo_x = width, hi_x = 0, lo_y = height, hi_y = 0;
  for (const auto& p : px) {
    if (std::isnan(p[0])) continue;
    lo_x = std::min(lo_x, p[0]), hi_x = std::max(hi_x, p[0]);
    lo_y = std::min(lo_y, p[1]), hi_y = std::max(hi_y, p[1]);
  }
  std::string rgba(4 * static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height),
                   '\0');
  const int x0 = std::max(0, static_cast<int>(std::floor(lo_x)) - 1);
  const int x1 = std::min(width, static_cast<int>(std::ceil(hi_x)) + 1);
  const int y0 = std::max(0, static_cast<int>(std::floor(lo_y)) - 1);
  const int y1 = std::min(height, static_cast<int>(std::ceil(hi_y)) + 1);
  if (x1 <= x0 || y1 <= y0) return rgba;  // no overlap: all transparent
  const Window win = read_window(o, x0, y0, x1, y1, path);
  const double sx = static_cast<double>(win.w) / win.span_x,
               sy = static_cast<double>(win.h) / win.span_y;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      // The raster pixel under this pixel's centre: bilinear between the four nodes around it.
      const int i = x / g.step, j = y / g.step;
      const double fx = (x - i * g.step) / static_cast<double>(g.step);
      const double fy = (y - j * g.step) / static_cast<double>(g.step);
      const auto& a = px[static_cast<std::size_t>(j * g.nodes_x + i)];
      const auto& b = px[static_cast<std::size_t>(j * g.nodes_x + i + 1)];
      const auto& c = px[static_cast<std::size_t>((j + 1) * g.nodes_x + i)];
      const auto& d = px[static_cast<std::size_t>((j + 1) * g.nodes_x + i + 1)];
      const double col =
          (1 - fy) * ((1 - fx) * a[0] + fx * b[0]) + fy * ((1 - fx) * c[0] + fx * d[0]);
      const double row =
          (1 - fy) * ((1 - fx) * a[1] + fx * b[1]) + fy * ((1 - fx) * c[1] + fx * d[1]);
      if (!(col >= x0 && col < x1 && row >= y0 && row < y1)) continue;  // NaN included
      const int wx = std::min(win.w - 1, static_cast<int>((col - x0) * sx));
      const int wy = std::min(win.h - 1, static_cast<int>((row - y0) * sy));
      const std::size_t from = 4 * (static_cast<std::size_t>(wy) * win.w + wx);
      const std::size_t to = 4 * (static_cast<std::size_t>(y) * g.width + x);
      for (int ch = 0; ch < 4; ++ch) rgba[to + ch] = static_cast<char>(win.rgba[from + ch]);
    }
  return rgba;
}

std::string rgba_png(int width, int height, const std::string& rgba) {
  confine_gdal();
  static std::mutex guard;
  const std::lock_guard<std::mutex> lock(guard);
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
  if (!mem || !png) throw std::runtime_error("GDAL has no MEM or PNG driver");
  GDALDatasetUniquePtr d(mem->Create("", width, height, 4, GDT_Byte, nullptr));
  if (!d) throw std::runtime_error("GDAL cannot make an image in memory (" + gdal_reason() + ")");
  auto* data = reinterpret_cast<GByte*>(const_cast<char*>(rgba.data()));
  if (d->RasterIO(GF_Write, 0, 0, width, height, data, width, height, GDT_Byte, 4, nullptr, 4,
                  4 * width, 1, nullptr) != CE_None)
    throw std::runtime_error("GDAL cannot fill the image (" + gdal_reason() + ")");
  d->GetRasterBand(4)->SetColorInterpretation(GCI_AlphaBand);
  const std::string path = "/vsimem/swath-basemap.png";
  GDALDataset* out = png->CreateCopy(path.c_str(), d.get(), FALSE, nullptr, nullptr, nullptr);
  if (!out) throw std::runtime_error("GDAL cannot write a PNG (" + gdal_reason() + ")");
  GDALClose(out);
  vsi_l_offset size = 0;
  GByte* bytes = VSIGetMemFileBuffer(path.c_str(), &size, FALSE);
  std::string result = bytes ? std::string(reinterpret_cast<const char*>(bytes), size) : "";
  VSIUnlink(path.c_str());
  // The PNG driver also writes an .aux.xml beside it for what PNG cannot hold.
  VSIUnlink((path + ".aux.xml").c_str());
  if (result.empty()) throw std::runtime_error("GDAL wrote no PNG (" + gdal_reason() + ")");
  return result;
}

}  // namespace swath::geometry::detail

#pragma once
// A georeferenced raster (an orthophoto: any raster GDAL reads, in any CRS) resampled to a picture
// whose pixels the caller places on the Earth: the basemap behind swath's coverage pictures and
// map page (docs/swath-plan.md, "Imagery behind the plan"). Read through the GIS module.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// 8-bit RGBA, rows top to bottom; alpha 0 where the raster has no data (outside it, NoData).
struct Imagery {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::size_t covered_px = 0;  ///< pixels with alpha > 0
};

/// Where a point of the picture lies: x_px right, y_px down from its top-left corner (a pixel's
/// centre is at +0.5). Must be smooth: it is evaluated every 16 px and interpolated between.
using PixelPlace = std::function<GeoPoint(double x_px, double y_px)>;

/// The raster at `path` drawn into a width_px x height_px picture, nearest pixel (an average
/// where the picture is coarser than the raster). One band is grey (or its palette), two grey and
/// alpha, three RGB, four RGBA; bands of more than 8 bits are stretched from their least to their
/// greatest value in view. Throws InputError naming the file when GDAL cannot read it or it has
/// no georeference (no geotransform or no CRS); std::runtime_error without the GIS module.
Imagery imagery(const std::string& path, int width_px, int height_px, const PixelPlace& where);

/// The raster's pixel size: its shorter side on the ground, metres. Throws as imagery().
double imagery_pixel_m(const std::string& path);

/// How many times `path` was opened (with GDAL) in this process: a raster is opened once and kept
/// open, so that every picture of it (coverage.png, each zoom level of plan.html's tiles) is
/// drawn from one open. For tests.
std::size_t imagery_opens(const std::string& path);

/// PNG bytes (RGBA) of the picture, written by GDAL; same picture, same bytes.
std::string imagery_png(const Imagery& picture);

}  // namespace swath::geometry

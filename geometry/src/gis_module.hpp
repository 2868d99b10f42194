#pragma once
// Internal: the GIS module (libswath_gis.so: field_ogr.cpp and GDAL) is opened on the first GIS
// file, like the drawing module: a program reading GeoJSON, KML or CSV, or none at all, never
// loads GDAL and the hundred libraries it brings (65 ms of every start, measured with
// swath --version). The module hands back these functions; errors come back as text.

#include <string>
#include <vector>

#include "imagery_gdal.hpp"
#include "raw_field.hpp"
#include "swath/geometry/field.hpp"
#include "swath/geometry/geotiff.hpp"
#include "swath/geometry/ground.hpp"

namespace swath::geometry::detail {

/// Bumped whenever GisModule or the types it passes change.
inline constexpr int kGisModuleAbi = 9;

struct GisModule {
  int abi;
  bool (*read)(const std::string& path, const FieldReadOptions& options, RawField& out,
               std::string& error);
  bool (*list)(const std::string& path, const FieldReadOptions& options,
               std::vector<AreaEntry>& out, std::string& error);
  bool (*wkt)(const std::string& text, const std::string& source, RawField& out,
              std::string& error);
  /// raster_gdal.hpp's sample_raster, raster_reads, forget_raster and proj_grid.
  bool (*sample)(const std::string& path, double asked_unit_m, const std::vector<GeoPoint>& points,
                 std::vector<double>& values, double& resolution_m, std::string& error);
  DemReads (*reads)(const std::string& path);
  void (*forget)(const std::string& path);
  bool (*grid)(const std::string& name, std::string& path, std::string& error);
  /// raster_gdal.hpp's geotiff.
  bool (*geotiff)(const LocalRaster& raster, std::string& bytes, std::string& error);
  /// imagery_gdal.hpp's imagery_rgba and rgba_png (since ABI 5).
  bool (*imagery)(const std::string& path, const ImageryGrid& grid, std::string& rgba,
                  double& pixel_m, std::string& error);
  bool (*png)(int width, int height, const std::string& rgba, std::string& bytes,
              std::string& error);
  /// imagery_gdal.hpp's imagery_opens (since ABI 6).
  std::size_t (*imagery_opens)(const std::string& path);
  /// field_ogr.hpp's area_reads (since ABI 7).
  std::size_t (*area_reads)(const std::string& path);
  /// raster_gdal.hpp's raster_bends (since ABI 9).
  bool (*bends)(const std::string& path, double asked_unit_m, const GeoPoint& a, const GeoPoint& b,
                std::vector<double>& fractions, std::string& error);
};

/// The module, opened on the first call (gis_loader.cpp). Throws std::runtime_error when it is
/// missing or of another build: an installation fault, not bad input.
const GisModule& gis_module();

}  // namespace swath::geometry::detail

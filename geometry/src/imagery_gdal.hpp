#pragma once
// Internal: the basemap's raster reading for the GIS module (GDAL's headers stay in
// imagery_gdal.cpp); imagery.hpp is the public side.

#include <cstddef>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry::detail {

/// The picture's places on a coarse grid: node (i, j) is the WGS84 position of the picture's
/// point (i step + 0.5, j step + 0.5), i < nodes_x, j < nodes_y (the last row and column may lie
/// past the picture's edge, so that every pixel has four nodes around it).
struct ImageryGrid {
  int width = 0, height = 0, step = 16;
  int nodes_x = 0, nodes_y = 0;
  std::vector<GeoPoint> nodes;  ///< row by row
};

/// The picture as RGBA bytes (imagery.hpp), or only the raster's pixel size when the grid has no
/// node. Throws base::InputError naming the file.
std::string imagery_rgba(const std::string& path, const ImageryGrid& grid, double& pixel_m);

/// How many times `path` was opened with GDAL by imagery_rgba in this process (it stays open).
std::size_t imagery_opens(const std::string& path);

/// PNG bytes of width x height RGBA pixels (GDAL's PNG driver, in memory).
std::string rgba_png(int width, int height, const std::string& rgba);

}  // namespace swath::geometry::detail

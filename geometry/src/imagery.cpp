// imagery.hpp: the places of the picture's pixels on a coarse grid, the rest in the GIS module.
#include "swath/geometry/imagery.hpp"

#include <stdexcept>

#include "gis_module.hpp"
#include "swath/base/input_error.hpp"

namespace swath::geometry {
namespace {

// A node every 16 px: over a picture of a few km the places of a local frame or Web Mercator
// bend by far less than a pixel between nodes.
constexpr int kStep_px = 16;

detail::ImageryGrid grid(int width_px, int height_px, const PixelPlace& where) {
  detail::ImageryGrid g;
  g.width = width_px, g.height = height_px, g.step = kStep_px;
  g.nodes_x = (width_px - 1) / kStep_px + 2;
  g.nodes_y = (height_px - 1) / kStep_px + 2;
  g.nodes.reserve(static_cast<std::size_t>(g.nodes_x) * static_cast<std::size_t>(g.nodes_y));
  for (int j = 0; j < g.nodes_y; ++j)
    for (int i = 0; i < g.nodes_x; ++i)
      g.nodes.push_back(where(i * kStep_px + 0.5, j * kStep_px + 0.5));
  return g;
}

}  // namespace

Imagery imagery(const std::string& path, int width_px, int height_px, const PixelPlace& where) {
  if (width_px <= 0 || height_px <= 0) return {};
  std::string rgba, error;
  double pixel_m = 0;
  if (!detail::gis_module().imagery(path, grid(width_px, height_px, where), rgba, pixel_m, error))
    throw base::InputError(error);
  Imagery out;
  out.width = width_px, out.height = height_px;
  out.rgba.assign(rgba.begin(), rgba.end());
  for (std::size_t k = 3; k < out.rgba.size(); k += 4) out.covered_px += out.rgba[k] > 0;
  return out;
}

double imagery_pixel_m(const std::string& path) {
  std::string rgba, error;
  double pixel_m = 0;
  if (!detail::gis_module().imagery(path, detail::ImageryGrid{}, rgba, pixel_m, error))
    throw base::InputError(error);
  return pixel_m;
}

std::size_t imagery_opens(const std::string& path) {
  return detail::gis_module().imagery_opens(path);
}

std::string imagery_png(const Imagery& picture) {
  std::string bytes, error;
  const std::string rgba(picture.rgba.begin(), picture.rgba.end());
  if (!detail::gis_module().png(picture.width, picture.height, rgba, bytes, error))
    throw std::runtime_error(error);
  return bytes;
}

}  // namespace swath::geometry

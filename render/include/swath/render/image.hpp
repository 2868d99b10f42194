#pragma once
// Rendering a scene offscreen (OSMesa, software OpenGL: no display, no GPU) to RGB pixels and PNG.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "swath/render/scene.hpp"
#include "swath/render/view.hpp"

namespace swath::render {

/// 8-bit RGB, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::uint8_t at(int x, int y, int channel) const {
    return rgb[3 * (static_cast<std::size_t>(y) * width + x) + channel];
  }
};

/// The offscreen context could not be created or used; what() says why.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Draws the scene: geometry with OpenGL at `supersample` times the size, then an area-average
/// down to view.width_px x view.height_px (anti-aliasing), then the labels with OpenCV's
/// anti-aliased text. Deterministic: same scene and view, same pixels. Throws RenderError.
Image draw(const Scene& scene, const View& view, int supersample = 3);

/// PNG bytes of the image (deterministic encoder settings).
std::string encode_png(const Image& image);

/// The image in PNG bytes; throws RenderError if they are not a PNG.
Image decode_png(const std::string& png);

}  // namespace swath::render

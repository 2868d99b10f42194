#pragma once
// Rendering a scene offscreen (OSMesa, software OpenGL: no display, no GPU) to RGB pixels and PNG.
// The drawing stack is a module loaded on the first call (programs that draw nothing never load
// OpenGL or OpenCV); it is found next to the program, at $SWATH_RENDER_MODULE, or in the build
// tree. A missing module is a RenderError saying where it was looked for.

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

/// The box a label's text takes, in pixels: `width_px` from the anchor to the right end,
/// `height_px` above the baseline and `baseline_px` below it (descenders).
struct TextExtent {
  int width_px = 0, height_px = 0, baseline_px = 0;
};

/// The extent of `text` drawn as a Label of `height_px` (same font and thickness as draw()),
/// so legends can be sized to fit inside the image. Throws RenderError.
TextExtent text_extent(const std::string& text, double height_px);

/// PNG bytes of the image (deterministic encoder settings).
std::string encode_png(const Image& image);

/// The image in PNG bytes; throws RenderError if they are not a PNG.
Image decode_png(const std::string& png);

}  // namespace swath::render

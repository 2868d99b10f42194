#pragma once
// Rendering a scene in software (no display, no GPU) to RGB pixels and PNG. The drawing stack is a
// module loaded on the first call (programs that draw nothing never load OpenCV or libpng); it is
// found next to the program, at $SWATH_RENDER_MODULE, or in the build tree. A missing module is a
// RenderError saying where it was looked for.

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

/// Draws the scene at view.width_px x view.height_px: each shape in the scene's draw order,
/// anti-aliased by the exact area of each pixel it covers and blended over what is there with its
/// straight alpha (a = alpha x coverage: a x colour + (1 - a) x below); then the labels with
/// OpenCV's anti-aliased text. Deterministic: same scene and view, same pixels. Throws RenderError.
Image draw(const Scene& scene, const View& view);

/// The box a label's text takes, in pixels: `width_px` from the anchor to the right end,
/// `height_px` above the baseline and `baseline_px` below it (descenders).
struct TextExtent {
  int width_px = 0, height_px = 0, baseline_px = 0;
};

/// The extent of `text` drawn as a Label of `height_px` (same font and thickness as draw()),
/// so legends can be sized to fit inside the image. Throws RenderError.
TextExtent text_extent(const std::string& text, double height_px);

/// PNG bytes of the image (8-bit RGB; fixed encoder settings and no timestamp: same image, same
/// bytes).
std::string encode_png(const Image& image);

/// The image in PNG bytes; throws RenderError if they are not a PNG.
Image decode_png(const std::string& png);

}  // namespace swath::render

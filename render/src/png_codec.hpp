#pragma once
// Internal: PNG bytes with libpng. Encoding is deterministic (fixed zlib level 6, libpng's
// adaptive choice among all five row filters, no time or text chunks): same pixels, same bytes.

#include <string>

#include "swath/render/image.hpp"

namespace swath::render::detail {

/// 8-bit RGB PNG of the image. Throws RenderError.
std::string png_encode(const Image& image);

/// The PNG's pixels as 8-bit RGB (palette and grey expanded, alpha dropped, 16-bit cut to 8).
/// Throws RenderError if the bytes are not a PNG.
Image png_decode(const std::string& png);

}  // namespace swath::render::detail

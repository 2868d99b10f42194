#pragma once
// Internal: the drawing module's entry points. The drawing stack (the coverage rasteriser, OpenCV's
// core and imgproc for the labels, libpng) lives in a module of its own, libswath_draw.so,
// that swath::render opens on the first picture (module_loader.cpp): a program that draws nothing
// loads none of those libraries at start-up. Errors cross the boundary as text, not as exceptions.

#include <string>

#include "swath/render/image.hpp"

namespace swath::render::detail {

/// Bumped whenever this struct or the types it passes change: a stale module is refused.
inline constexpr int kDrawModuleAbi = 3;

struct DrawModule {
  int abi = kDrawModuleAbi;
  /// Each returns false and sets `error` on failure.
  bool (*draw)(const Scene& scene, const View& view, Image& out,
               std::string& error) noexcept = nullptr;
  bool (*encode_png)(const Image& image, std::string& out, std::string& error) noexcept = nullptr;
  bool (*decode_png)(const std::string& png, Image& out, std::string& error) noexcept = nullptr;
  bool (*text_extent)(const std::string& text, double height_px, TextExtent& out,
                      std::string& error) noexcept = nullptr;
};

}  // namespace swath::render::detail

/// The module's one exported symbol.
extern "C" const swath::render::detail::DrawModule* swath_draw_module();

#pragma once
// Internal: the drawing module's entry points. OpenGL (OSMesa, which loads LLVM) and OpenCV
// (whose image codecs load GDAL) bring ~140 shared libraries; linked into the programs they cost
// ~150 ms at every start, drawing or not (issue 17). So they live in a module of their own,
// libswath_render_gl.so, that swath::render opens on the first picture (module_loader.cpp).
// Errors cross the boundary as text, not as exceptions.

#include <string>

#include "swath/render/image.hpp"

namespace swath::render::detail {

/// Bumped whenever this struct or the types it passes change: a stale module is refused.
inline constexpr int kGlModuleAbi = 2;

struct GlModule {
  int abi = kGlModuleAbi;
  /// Each returns false and sets `error` on failure.
  bool (*draw)(const Scene& scene, const View& view, int supersample, Image& out,
               std::string& error) noexcept = nullptr;
  bool (*encode_png)(const Image& image, std::string& out, std::string& error) noexcept = nullptr;
  bool (*decode_png)(const std::string& png, Image& out, std::string& error) noexcept = nullptr;
  bool (*text_extent)(const std::string& text, double height_px, TextExtent& out,
                      std::string& error) noexcept = nullptr;
};

}  // namespace swath::render::detail

/// The module's one exported symbol.
extern "C" const swath::render::detail::GlModule* swath_render_gl_module();

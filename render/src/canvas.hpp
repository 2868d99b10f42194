#pragma once
// Internal: the picture being drawn, one float per channel (so that many translucent layers do not
// round at every step), and straight alpha blending of coverage rows onto it.

#include <cstdint>
#include <span>
#include <vector>

#include "swath/render/scene.hpp"

namespace swath::render::detail {

/// The largest picture side drawn or decoded, pixels: a 16384 x 16384 canvas is ~3.2 GB of floats.
inline constexpr int kMaxSide_px = 16384;

class Canvas {
 public:
  /// width_px x height_px, filled with `background` (its alpha is ignored: the picture is opaque).
  Canvas(int width_px, int height_px, const Color& background);

  /// Copies the backdrop's pixels when it is exactly the canvas's size; otherwise does nothing.
  void paste(const Backdrop& backdrop);

  /// Blends `color` over row y from x_begin on: with a = color.a * coverage[i], each channel
  /// becomes a * color + (1 - a) * what was there. Pixels outside the canvas are skipped.
  void blend(int y, int x_begin, std::span<const float> coverage, const Color& color);

  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  /// A channel's value in [0, 1] (channel 0 red, 1 green, 2 blue).
  float at(int x, int y, int channel) const {
    return pixels_[3 * (static_cast<std::size_t>(y) * width_px_ + x) + channel];
  }

  /// 8-bit RGB, rows top to bottom, each channel rounded to the nearest level.
  std::vector<std::uint8_t> to_rgb8() const;

 private:
  int width_px_, height_px_;
  std::vector<float> pixels_;
};

}  // namespace swath::render::detail

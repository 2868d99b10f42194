#include "canvas.hpp"

#include <algorithm>
#include <cmath>

namespace swath::render::detail {

Canvas::Canvas(int width_px, int height_px, const Color& background)
    : width_px_(width_px), height_px_(height_px) {
  pixels_.resize(3 * static_cast<std::size_t>(width_px) * height_px);
  for (std::size_t i = 0; i < pixels_.size(); i += 3) {
    pixels_[i] = background.r;
    pixels_[i + 1] = background.g;
    pixels_[i + 2] = background.b;
  }
}

void Canvas::paste(const Backdrop& backdrop) {
  if (backdrop.width_px != width_px_ || backdrop.height_px != height_px_ ||
      backdrop.rgb.size() != pixels_.size())
    return;
  for (std::size_t i = 0; i < pixels_.size(); ++i) pixels_[i] = backdrop.rgb[i] / 255.0f;
}

void Canvas::blend(int y, int x_begin, std::span<const float> coverage, const Color& color) {
  if (y < 0 || y >= height_px_) return;
  const int first = std::max(0, x_begin);
  const int end = std::min<int>(width_px_, x_begin + static_cast<int>(coverage.size()));
  float* row = pixels_.data() + 3 * static_cast<std::size_t>(y) * width_px_;
  for (int x = first; x < end; ++x) {
    const float a = color.a * coverage[x - x_begin];
    if (a <= 0) continue;
    float* p = row + 3 * x;
    p[0] += a * (color.r - p[0]);
    p[1] += a * (color.g - p[1]);
    p[2] += a * (color.b - p[2]);
  }
}

std::vector<std::uint8_t> Canvas::to_rgb8() const {
  std::vector<std::uint8_t> out(pixels_.size());
  for (std::size_t i = 0; i < pixels_.size(); ++i)
    out[i] = static_cast<std::uint8_t>(std::lround(std::clamp(pixels_[i], 0.0f, 1.0f) * 255.0f));
  return out;
}

}  // namespace swath::render::detail

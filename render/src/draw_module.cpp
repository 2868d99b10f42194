// The drawing module (libswath_draw.so): the only translation unit that sees OpenCV and libpng.
// Loaded on first use by module_loader.cpp (see draw_module.hpp). The geometry is filled by
// the coverage rasteriser (exact-area anti-aliasing, no supersampled buffer), the labels by
// OpenCV's anti-aliased text, PNG by libpng.
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "canvas.hpp"
#include "coverage_rasterizer.hpp"
#include "draw_module.hpp"
#include "png_codec.hpp"
#include "shapes.hpp"
#include "swath/render/image.hpp"

namespace swath::render {
namespace {

using detail::Canvas;
using detail::CoverageRasterizer;
using detail::FillRule;
using detail::Ring;
using geometry::Point2;

// The colour with every channel in [0, 1] (one that is not a number counts as 0): out-of-range
// values would extrapolate the blend, and NaN would poison the pixel.
Color usable(const Color& c) {
  const auto unit = [](float v) { return v > 0 ? std::min(v, 1.0f) : 0.0f; };
  return {unit(c.r), unit(c.g), unit(c.b), unit(c.a)};
}

// Fills shapes onto the canvas in the order given. Opaque shapes of one colour that follow each
// other are filled as one union (nonzero rule): the same picture, without the faint seams that
// blending each one's edge coverage separately leaves where they abut (a row of 1 px ticks).
class Painter {
 public:
  explicit Painter(Canvas& canvas)
      : canvas_(canvas), rasterizer_(canvas.width_px(), canvas.height_px()) {}

  // Adds a shape (rings under the nonzero rule).
  void add(std::vector<Ring> rings, const Color& color) {
    if (!pending_.empty() && !(color.a >= 1 && same(color, pending_color_))) flush();
    for (Ring& ring : rings) pending_.push_back(std::move(ring));
    pending_color_ = color;
    if (color.a < 1) flush();
  }

  // A filled polygon (even-odd) and its outline.
  void polygon(const std::vector<Ring>& rings, const FilledPolygon& p) {
    flush();
    fill(rings, FillRule::even_odd, p.fill);
    if (p.outline.a <= 0) return;
    std::vector<Ring> outline;
    for (Ring ring : rings) {
      if (ring.empty()) continue;
      ring.push_back(ring.front());
      for (Ring& piece : detail::stroke(ring, p.outline_px)) outline.push_back(std::move(piece));
    }
    add(std::move(outline), p.outline);
  }

  // A line and its arrowheads: one shape, so that a translucent line is not darker where its
  // pieces overlap.
  void polyline(const std::vector<Point2>& points, const Polyline& l) {
    std::vector<Ring> rings = detail::stroke(points, l.width_px);
    if (l.arrow_every_px > 0)
      for (Ring& head : detail::arrowheads(
               points, l.arrow_every_px, l.width_px * 4,
               {static_cast<double>(canvas_.width_px()), static_cast<double>(canvas_.height_px())}))
        rings.push_back(std::move(head));
    add(std::move(rings), l.color);
  }

  void flush() {
    if (!pending_.empty()) fill(pending_, FillRule::nonzero, pending_color_);
    pending_.clear();
  }

 private:
  static bool same(const Color& a, const Color& b) {
    return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a;
  }

  void fill(const std::vector<Ring>& rings, FillRule rule, const Color& given) {
    const Color color = usable(given);
    if (color.a <= 0) return;
    rasterizer_.clear();
    for (const Ring& ring : rings) rasterizer_.add_ring(ring);
    rasterizer_.rasterize(rule, [&](int y, int x_begin, std::span<const float> coverage) {
      canvas_.blend(y, x_begin, coverage, color);
    });
  }

  Canvas& canvas_;
  CoverageRasterizer rasterizer_;
  std::vector<Ring> pending_;
  Color pending_color_;
};

cv::Scalar scalar(const Color& given) {  // RGB channel order: the Mat holds RGB
  const Color c = usable(given);
  return {std::round(c.r * 255.0), std::round(c.g * 255.0), std::round(c.b * 255.0)};
}

using detail::kMaxSide_px;

// A label's height in whole pixels, 1 to kMaxSide_px; a height that is not a number is refused.
int text_height(double height_px) {
  if (!std::isfinite(height_px))
    throw RenderError("a label's height (" + std::to_string(height_px) +
                      " px) is not a finite number");
  return static_cast<int>(std::clamp(height_px, 1.0, static_cast<double>(kMaxSide_px)));
}

int text_thickness(int height_px) {
  return std::max(1, height_px / 12);
}

Image draw_scene(const Scene& scene, const View& view) {
  if (view.width_px <= 0 || view.height_px <= 0 || view.width_px > kMaxSide_px ||
      view.height_px > kMaxSide_px)
    throw RenderError("image size " + std::to_string(view.width_px) + " x " +
                      std::to_string(view.height_px) + " is out of range (1 to " +
                      std::to_string(kMaxSide_px) + " pixels a side)");
  Canvas canvas(view.width_px, view.height_px, usable(scene.background));
  canvas.paste(scene.backdrop);
  Painter painter(canvas);

  const auto world = [&](const std::vector<Point2>& points) {
    Ring out;
    out.reserve(points.size());
    for (const Point2& p : points) out.push_back(view.to_pixel(p));
    return out;
  };
  for (const FilledPolygon& p : scene.polygons) {
    std::vector<Ring> rings;
    for (const auto& ring : p.rings) rings.push_back(world(ring));
    painter.polygon(rings, p);
  }
  for (const Strip& s : scene.strips)
    painter.add({detail::band(view.to_pixel(s.a), view.to_pixel(s.b), s.width_m * view.px_per_m)},
                s.color);
  for (const Polyline& l : scene.polylines) painter.polyline(world(l.points), l);
  for (const Marker& m : scene.markers)
    painter.add({detail::marker(view.to_pixel(m.at), m.size_px, m.shape)}, m.color);
  for (const FilledPolygon& p : scene.screen_polygons) painter.polygon(p.rings, p);
  for (const Polyline& l : scene.screen_polylines) painter.polyline(l.points, l);
  painter.flush();

  Image image;
  image.width = view.width_px;
  image.height = view.height_px;
  image.rgb = canvas.to_rgb8();
  cv::Mat rgb(image.height, image.width, CV_8UC3, image.rgb.data());  // shares image.rgb
  for (const Label& label : scene.labels) {
    const int height = text_height(label.height_px);
    const double scale = cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, height, 1);
    cv::putText(rgb, label.text, {label.x_px, label.y_px}, cv::FONT_HERSHEY_SIMPLEX, scale,
                scalar(label.color), text_thickness(height), cv::LINE_AA);
  }
  return image;
}

TextExtent measure_text(const std::string& text, double height_px) {
  const int height = text_height(height_px);
  const double scale = cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, height, 1);
  int baseline = 0;
  const cv::Size size =
      cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, text_thickness(height), &baseline);
  return {size.width, size.height, baseline};
}

// Runs `f`, turning any exception into `error` (exceptions do not cross the module boundary).
template <typename F>
bool guarded(std::string& error, F&& f) noexcept {
  try {
    f();
    return true;
  } catch (const std::exception& e) {
    error = e.what();
  } catch (...) {
    error = "unknown error in the drawing module";
  }
  return false;
}

}  // namespace
}  // namespace swath::render

extern "C" __attribute__((visibility("default"))) const swath::render::detail::DrawModule*
swath_draw_module() {
  using namespace swath::render;
  static const detail::DrawModule module{
      detail::kDrawModuleAbi,
      [](const Scene& scene, const View& view, Image& out, std::string& error) noexcept {
        return guarded(error, [&] { out = draw_scene(scene, view); });
      },
      [](const Image& image, std::string& out, std::string& error) noexcept {
        return guarded(error, [&] { out = detail::png_encode(image); });
      },
      [](const std::string& png, Image& out, std::string& error) noexcept {
        return guarded(error, [&] { out = detail::png_decode(png); });
      },
      [](const std::string& text, double height_px, TextExtent& out, std::string& error) noexcept {
        return guarded(error, [&] { out = measure_text(text, height_px); });
      },
  };
  return &module;
}

// The drawing module (libswath_render_gl.so): the only translation unit that sees OpenGL
// (OSMesa) and OpenCV. Loaded on first use by module_loader.cpp (see gl_module.hpp).
#include <GL/gl.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gl_module.hpp"
#include "swath/render/image.hpp"

namespace swath::render {
namespace {

using geometry::Point2;

// RAII: an OSMesa context drawing into our own RGBA buffer, top row first.
class OffscreenContext {
 public:
  OffscreenContext(int width, int height) : buffer_(4 * std::size_t(width) * height) {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 0, 8, 0, nullptr);
    if (context_ == nullptr)
      throw RenderError("cannot create an offscreen OpenGL context (OSMesa)");
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) {
      OSMesaDestroyContext(context_);
      throw RenderError("cannot draw offscreen at " + std::to_string(width) + " x " +
                        std::to_string(height) + " pixels (OSMesa refused the buffer)");
    }
    OSMesaPixelStore(OSMESA_Y_UP, 0);
  }
  ~OffscreenContext() { OSMesaDestroyContext(context_); }
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;
  const std::vector<unsigned char>& pixels() {
    glFinish();
    return buffer_;
  }

 private:
  std::vector<unsigned char> buffer_;
  OSMesaContext context_ = nullptr;
};

void set(const Color& c) {
  glColor4f(c.r, c.g, c.b, c.a);
}

void quad(Point2 a, Point2 b, Point2 c, Point2 d) {
  glBegin(GL_QUADS);
  for (Point2 p : {a, b, c, d}) glVertex2d(p.x, p.y);
  glEnd();
}

void disc(Point2 at, double radius) {
  glBegin(GL_TRIANGLE_FAN);
  glVertex2d(at.x, at.y);
  for (int k = 0; k <= 32; ++k) {
    const double t = 2 * std::numbers::pi * k / 32;
    glVertex2d(at.x + radius * std::cos(t), at.y + radius * std::sin(t));
  }
  glEnd();
}

// Even-odd fill through the stencil buffer: each ring toggles the pixels its fan covers.
void fill_even_odd(const std::vector<std::vector<Point2>>& rings, const Color& color) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  glEnable(GL_STENCIL_TEST);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glStencilFunc(GL_ALWAYS, 0, 1);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INVERT);
  for (const auto& ring : rings) {
    if (ring.size() < 3) continue;
    glBegin(GL_TRIANGLE_FAN);
    for (const Point2& p : ring) {
      glVertex2d(p.x, p.y);
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
    }
    glEnd();
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glStencilFunc(GL_EQUAL, 1, 1);
  glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);  // and clear for the next polygon
  set(color);
  quad({x0, y0}, {x1, y0}, {x1, y1}, {x0, y1});
  glDisable(GL_STENCIL_TEST);
}

// A polyline of width w as quads with round joins.
void thick_polyline(const std::vector<Point2>& points, double w, const Color& color) {
  set(color);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Point2 a = points[i], b = points[i + 1], d = b - a;
    const double len = std::sqrt(geometry::dot(d, d));
    if (len == 0) continue;
    const Point2 n{-d.y / len * w / 2, d.x / len * w / 2};
    quad(a + n, b + n, b - n, a - n);
  }
  // Round joins at interior vertices (and where a ring closes); flat ends, so that a bar is as
  // long as it claims. Only opaque: overdraw would darken a translucent line.
  if (color.a < 1 || points.size() < 2) return;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) disc(points[i], w / 2);
  if (points.front() == points.back()) disc(points.front(), w / 2);
}

void arrows(const std::vector<Point2>& points, double every, double size, const Color& color) {
  set(color);
  double walked = 0, next = every / 2;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Point2 a = points[i], b = points[i + 1], d = b - a;
    const double len = std::sqrt(geometry::dot(d, d));
    if (len == 0) continue;
    const Point2 u = d * (1 / len), n{-u.y, u.x};
    while (next <= walked + len) {
      const Point2 tip = a + u * (next - walked + size / 2);
      const Point2 back = tip - u * size;
      glBegin(GL_TRIANGLES);
      glVertex2d(tip.x, tip.y);
      glVertex2d(back.x + n.x * size / 2, back.y + n.y * size / 2);
      glVertex2d(back.x - n.x * size / 2, back.y - n.y * size / 2);
      glEnd();
      next += every;
    }
    walked += len;
  }
}

void marker(Point2 at, double size, MarkerShape shape, const Color& color) {
  set(color);
  switch (shape) {
    case MarkerShape::disc:
      disc(at, size / 2);
      break;
    case MarkerShape::square:
      quad(at + Point2{-size / 2, -size / 2}, at + Point2{size / 2, -size / 2},
           at + Point2{size / 2, size / 2}, at + Point2{-size / 2, size / 2});
      break;
    case MarkerShape::triangle:
      glBegin(GL_TRIANGLES);
      glVertex2d(at.x, at.y - size / 2);
      glVertex2d(at.x + size / 2, at.y + size / 2);
      glVertex2d(at.x - size / 2, at.y + size / 2);
      glEnd();
      break;
  }
}

cv::Scalar scalar(const Color& c) {  // RGB channel order: the Mat holds RGB
  return {std::round(c.r * 255.0), std::round(c.g * 255.0), std::round(c.b * 255.0)};
}

// The backdrop's pixels, each ss x ss, from the top-left corner down (the raster position is
// the projection's top-left, y up in window coordinates: a negative zoom draws rows downwards).
void draw_backdrop(const Backdrop& b, const View& view, int ss) {
  if (b.width_px != view.width_px || b.height_px != view.height_px ||
      b.rgb.size() != 3 * static_cast<std::size_t>(b.width_px) * b.height_px)
    return;
  glDisable(GL_BLEND);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelZoom(static_cast<float>(ss), -static_cast<float>(ss));
  glRasterPos2d(0, 0);
  glDrawPixels(b.width_px, b.height_px, GL_RGB, GL_UNSIGNED_BYTE, b.rgb.data());
  glPixelZoom(1, 1);
  glEnable(GL_BLEND);
}

Image draw_scene(const Scene& scene, const View& view, int supersample) {
  const int ss = std::max(1, supersample);
  const int w = view.width_px * ss, h = view.height_px * ss;
  if (view.width_px <= 0 || view.height_px <= 0 || w > 16384 || h > 16384)
    throw RenderError("image size " + std::to_string(view.width_px) + " x " +
                      std::to_string(view.height_px) + " is out of range (1 to " +
                      std::to_string(16384 / ss) + " pixels a side)");
  OffscreenContext context(w, h);
  glViewport(0, 0, w, h);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, w, h, 0, -1, 1);  // pixel coordinates, y down, in the supersampled image
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glClearColor(scene.background.r, scene.background.g, scene.background.b, 1);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  draw_backdrop(scene.backdrop, view, ss);

  auto px = [&](Point2 world) { return view.to_pixel(world) * ss; };
  auto px_all = [&](const std::vector<Point2>& pts) {
    std::vector<Point2> out;
    for (const Point2& p : pts) out.push_back(px(p));
    return out;
  };
  for (const FilledPolygon& p : scene.polygons) {
    std::vector<std::vector<Point2>> rings;
    for (const auto& ring : p.rings) rings.push_back(px_all(ring));
    fill_even_odd(rings, p.fill);
    if (p.outline.a > 0)
      for (auto ring : rings) {
        ring.push_back(ring.front());
        thick_polyline(ring, p.outline_px * ss, p.outline);
      }
  }
  for (const Strip& s : scene.strips) {
    const Point2 a = px(s.a), b = px(s.b), d = b - a;
    const double len = std::sqrt(geometry::dot(d, d));
    if (len == 0) continue;
    const double half = s.width_m * view.px_per_m * ss / 2;
    const Point2 n{-d.y / len * half, d.x / len * half};
    set(s.color);
    quad(a + n, b + n, b - n, a - n);
  }
  for (const Polyline& l : scene.polylines) {
    const std::vector<Point2> pts = px_all(l.points);
    thick_polyline(pts, l.width_px * ss, l.color);
    if (l.arrow_every_px > 0) arrows(pts, l.arrow_every_px * ss, l.width_px * ss * 4, l.color);
  }
  for (const Marker& m : scene.markers) marker(px(m.at), m.size_px * ss, m.shape, m.color);
  for (const FilledPolygon& p : scene.screen_polygons) {
    std::vector<std::vector<Point2>> rings;
    for (const auto& ring : p.rings) {
      rings.emplace_back();
      for (const Point2& q : ring) rings.back().push_back(q * ss);
    }
    fill_even_odd(rings, p.fill);
    if (p.outline.a > 0)
      for (auto ring : rings) {
        ring.push_back(ring.front());
        thick_polyline(ring, p.outline_px * ss, p.outline);
      }
  }
  for (const Polyline& l : scene.screen_polylines) {
    std::vector<Point2> pts;
    for (const Point2& q : l.points) pts.push_back(q * ss);
    thick_polyline(pts, l.width_px * ss, l.color);
  }
  if (glGetError() != GL_NO_ERROR) throw RenderError("OpenGL reported an error while drawing");

  // Area-average down: anti-aliasing, deterministic.
  const std::vector<unsigned char>& rgba = context.pixels();
  cv::Mat big(h, w, CV_8UC4, const_cast<unsigned char*>(rgba.data()));
  cv::Mat big_rgb, small;
  cv::cvtColor(big, big_rgb, cv::COLOR_RGBA2RGB);
  cv::resize(big_rgb, small, cv::Size(view.width_px, view.height_px), 0, 0, cv::INTER_AREA);
  for (const Label& label : scene.labels) {
    const double scale =
        cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, static_cast<int>(label.height_px), 1);
    cv::putText(small, label.text, {label.x_px, label.y_px}, cv::FONT_HERSHEY_SIMPLEX, scale,
                scalar(label.color), std::max(1, static_cast<int>(label.height_px / 12)),
                cv::LINE_AA);
  }
  Image image;
  image.width = view.width_px;
  image.height = view.height_px;
  image.rgb.assign(small.data, small.data + small.total() * 3);
  return image;
}

std::string png_of(const Image& image) {
  cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<unsigned char> bytes;
  cv::imencode(".png", bgr, bytes, {cv::IMWRITE_PNG_COMPRESSION, 6});
  return std::string(bytes.begin(), bytes.end());
}

Image image_of_png(const std::string& png) {
  const std::vector<unsigned char> bytes(png.begin(), png.end());
  cv::Mat bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  if (bgr.empty()) throw RenderError("not a PNG image");
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  Image image;
  image.width = rgb.cols;
  image.height = rgb.rows;
  image.rgb.assign(rgb.data, rgb.data + rgb.total() * 3);
  return image;
}

TextExtent measure_text(const std::string& text, double height_px) {
  const int height = static_cast<int>(height_px);
  const double scale = cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, height, 1);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale,
                                        std::max(1, static_cast<int>(height_px / 12)), &baseline);
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

extern "C" __attribute__((visibility("default"))) const swath::render::detail::GlModule*
swath_render_gl_module() {
  using namespace swath::render;
  static const detail::GlModule module{
      detail::kGlModuleAbi,
      [](const Scene& scene, const View& view, int ss, Image& out, std::string& error) noexcept {
        return guarded(error, [&] { out = draw_scene(scene, view, ss); });
      },
      [](const Image& image, std::string& out, std::string& error) noexcept {
        return guarded(error, [&] { out = png_of(image); });
      },
      [](const std::string& png, Image& out, std::string& error) noexcept {
        return guarded(error, [&] { out = image_of_png(png); });
      },
      [](const std::string& text, double height_px, TextExtent& out, std::string& error) noexcept {
        return guarded(error, [&] { out = measure_text(text, height_px); });
      },
  };
  return &module;
}

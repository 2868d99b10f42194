// Pixels at known places of a known scene: a 100 x 100 m square, footprint strips, a path.
#include "swath/render/image.hpp"

#include <gtest/gtest.h>

namespace swath::render {
namespace {

using geometry::Point2;

const Color kArea{0.6f, 0.8f, 0.6f, 1};
const Color kStrip{0.1f, 0.2f, 0.9f, 0.3f};
const Color kPath{0.9f, 0.1f, 0.1f, 1};

Scene square_scene() {
  Scene s;
  s.polygons.push_back(
      {{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {{40, 40}, {40, 60}, {60, 60}, {60, 40}}},
       kArea});
  s.strips.push_back({{0, 20}, {100, 20}, 20, kStrip});  // y 10..30
  s.strips.push_back({{0, 28}, {100, 28}, 20, kStrip});  // y 18..38: overlaps 18..30
  s.polylines.push_back({{{10, 80}, {90, 80}}, 3, kPath});
  s.markers.push_back({{95, 95}, 8, kPath, MarkerShape::square});
  return s;
}

// The pixel of a world point.
std::array<int, 3> at(const Image& im, const View& v, Point2 world) {
  const Point2 p = v.to_pixel(world);
  const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
  return {im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)};
}

int channel(float c) {
  return static_cast<int>(std::lround(c * 255));
}

TEST(Fit, KeepsTheAspectRatioAndCentres) {
  const View v = fit({0, 0}, {100, 100}, 400, 200, 20);
  EXPECT_DOUBLE_EQ(v.px_per_m, 1.6);  // height limits: (200 - 40) / 100
  EXPECT_NEAR(v.to_pixel({50, 50}).x, 200, 1e-9);
  EXPECT_NEAR(v.to_pixel({50, 50}).y, 100, 1e-9);
  EXPECT_NEAR(v.to_pixel({0, 100}).y, 20, 1e-9);  // north is up
  EXPECT_NEAR(v.to_pixel({100, 0}).x - v.to_pixel({0, 0}).x, 160, 1e-9);
}

TEST(Draw, ColoursAtKnownPlaces) {
  const View v = fit({0, 0}, {100, 100}, 240, 240, 20);
  const Image im = draw(square_scene(), v);
  ASSERT_EQ(im.width, 240);
  ASSERT_EQ(im.height, 240);
  // Outside the area: background.
  EXPECT_EQ(at(im, v, {-5, 50}), (std::array<int, 3>{255, 255, 255}));
  // Inside, away from everything: the area's colour.
  EXPECT_EQ(at(im, v, {20, 60}), (std::array<int, 3>{channel(0.6f), channel(0.8f), channel(0.6f)}));
  // The hole shows the background.
  EXPECT_EQ(at(im, v, {50, 50}), (std::array<int, 3>{255, 255, 255}));
  // On the path: its colour.
  const auto path = at(im, v, {50, 80});
  EXPECT_NEAR(path[0], channel(0.9f), 2);
  EXPECT_NEAR(path[1], channel(0.1f), 2);
  // One strip darkens the area; two overlapping strips darken it more.
  const auto one = at(im, v, {20, 12}), two = at(im, v, {20, 24}), none = at(im, v, {20, 60});
  EXPECT_LT(one[0], none[0]);
  EXPECT_LT(two[0], one[0]);
  EXPECT_LT(two[1], one[1]);
  // Blending: one strip over the area is 0.3 strip + 0.7 area.
  EXPECT_NEAR(one[0], std::round(255 * (0.3 * 0.1 + 0.7 * 0.6)), 2);
}

TEST(Draw, SameSceneSameBytes) {
  const View v = fit({0, 0}, {100, 100}, 300, 200, 10);
  EXPECT_EQ(encode_png(draw(square_scene(), v)), encode_png(draw(square_scene(), v)));
  const std::string png = encode_png(draw(square_scene(), v));
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(Draw, ScreenLayerIsInPixels) {
  Scene s;
  s.screen_polylines.push_back({{{10, 50}, {110, 50}}, 4, {0, 0, 0, 1}});  // a 100 px bar
  const View v = fit({0, 0}, {10, 10}, 200, 100, 5);
  const Image im = draw(s, v);
  int dark = 0;
  for (int x = 0; x < im.width; ++x) dark += im.at(x, 50, 0) < 128;
  EXPECT_NEAR(dark, 100, 2);
}

// Straight alpha blending in draw order, by closed form: over a background b, a fill of colour c1
// and alpha a1 then one of c2, a2 give a2 c2 + (1 - a2) (a1 c1 + (1 - a1) b) where both cover a
// pixel; at a pixel a shape covers only a fraction f of, its alpha is f a.
TEST(Draw, TranslucentFillsBlendByClosedForm) {
  const Color bg{0.9f, 0.8f, 0.7f, 1}, c1{0.2f, 0.6f, 1.0f, 0.5f}, c2{1.0f, 0.1f, 0.3f, 0.35f};
  Scene s;
  s.background = bg;
  // Screen pixels: the first square's right edge at x = 60.25 cuts pixel column 60.
  s.screen_polygons.push_back({{{{10, 10}, {60.25, 10}, {60.25, 60}, {10, 60}}}, c1});
  s.screen_polygons.push_back({{{{40, 30}, {90, 30}, {90, 80}, {40, 80}}}, c2});
  const Image im = draw(s, View{1, 0, 0, 100, 100});
  const auto over = [](double c, double a, double below) { return a * c + (1 - a) * below; };
  const auto expect = [&](int x, int y, double r, double g, double b, const char* where) {
    EXPECT_NEAR(im.at(x, y, 0), 255 * r, 0.5 + 1e-3) << where;
    EXPECT_NEAR(im.at(x, y, 1), 255 * g, 0.5 + 1e-3) << where;
    EXPECT_NEAR(im.at(x, y, 2), 255 * b, 0.5 + 1e-3) << where;
  };
  expect(5, 5, bg.r, bg.g, bg.b, "background");
  expect(20, 20, over(c1.r, c1.a, bg.r), over(c1.g, c1.a, bg.g), over(c1.b, c1.a, bg.b), "first");
  expect(80, 70, over(c2.r, c2.a, bg.r), over(c2.g, c2.a, bg.g), over(c2.b, c2.a, bg.b), "second");
  expect(50, 40, over(c2.r, c2.a, over(c1.r, c1.a, bg.r)), over(c2.g, c2.a, over(c1.g, c1.a, bg.g)),
         over(c2.b, c2.a, over(c1.b, c1.a, bg.b)), "both");
  // Column 60 is a quarter covered by the first square; below the second square (y < 30) alone.
  const double a = 0.25 * c1.a;
  expect(60, 20, over(c1.r, a, bg.r), over(c1.g, a, bg.g), over(c1.b, a, bg.b), "a quarter");
  expect(60, 40, over(c2.r, c2.a, over(c1.r, a, bg.r)), over(c2.g, c2.a, over(c1.g, a, bg.g)),
         over(c2.b, c2.a, over(c1.b, a, bg.b)), "a quarter, then the second");
}

// Opaque shapes of one colour side by side cover a pixel they share together: two 1 px lines
// centred at x 10.25 and 11.25 cover three quarters and a quarter of pixel column 10, which is then
// wholly theirs (blending each one's coverage in turn would leave 1 - 0.25 x 0.75 of it).
TEST(Draw, AbuttingOpaqueShapesLeaveNoSeam) {
  Scene s;
  const Color ink{0.1f, 0.2f, 0.3f, 1};
  s.screen_polylines.push_back({{{10.25, 5}, {10.25, 25}}, 1.0, ink});
  s.screen_polylines.push_back({{{11.25, 5}, {11.25, 25}}, 1.0, ink});
  const Image im = draw(s, View{1, 0, 0, 30, 30});
  for (int c = 0; c < 3; ++c) EXPECT_EQ(im.at(10, 15, c), channel((&ink.r)[c])) << c;
  EXPECT_EQ(im.at(9, 15, 0), std::lround(255 * (0.25 * 0.1 + 0.75 * 1.0)));  // a quarter covered
}

// PNG: what is encoded decodes to the same pixels, and what is not a PNG is a clear error.
TEST(Png, RoundTripAndBadBytes) {
  Image im;
  im.width = 37;
  im.height = 11;
  for (int i = 0; i < 3 * 37 * 11; ++i) im.rgb.push_back(static_cast<std::uint8_t>(i * 7 % 256));
  const Image back = decode_png(encode_png(im));
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.rgb, im.rgb);
  EXPECT_THROW(decode_png("not a png at all"), RenderError);
  std::string cut = encode_png(im);
  cut.resize(cut.size() / 2);
  EXPECT_THROW(decode_png(cut), RenderError);
}

TEST(Draw, ImpossibleSizeIsAClearError) {
  const View v = fit({0, 0}, {10, 10}, 20000, 100, 5);
  try {
    draw(Scene{}, v);
    FAIL();
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos);
  }
}

}  // namespace
}  // namespace swath::render

namespace swath::render {
namespace {

// The measured box must contain the drawn text: every dark pixel of a label lies inside
// [x, x + width] x [baseline - height, baseline + descent] (a second, pixel-level measure).
TEST(TextExtent, BoundsTheDrawnTextAndGrowsWithLengthAndHeight) {
  const TextExtent short_text = text_extent("N", 14), long_text = text_extent("Nordwest 123", 14);
  const TextExtent tall = text_extent("Nordwest 123", 28);
  EXPECT_GT(short_text.width_px, 0);
  EXPECT_GT(long_text.width_px, 5 * short_text.width_px);
  EXPECT_GT(tall.width_px, long_text.width_px * 3 / 2);
  EXPECT_GT(tall.height_px, long_text.height_px * 3 / 2);

  Scene s;
  s.labels.push_back({20, 50, "Nordwest 123 gyp", 20, {0, 0, 0, 1}});
  const View v = fit({0, 0}, {1, 1}, 300, 100, 0);
  const Image im = draw(s, v);
  const TextExtent e = text_extent("Nordwest 123 gyp", 20);
  int dark = 0, outside = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      if (im.at(x, y, 0) < 128) {
        ++dark;
        // One pixel of anti-aliasing slack on each side.
        outside += x < 20 - 1 || x > 20 + e.width_px + 1 || y < 50 - e.height_px - 1 ||
                   y > 50 + e.baseline_px + 1;
      }
  EXPECT_GT(dark, 100);
  EXPECT_EQ(outside, 0);
}

}  // namespace
}  // namespace swath::render

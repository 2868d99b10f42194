// Scenes no program should make but the library must survive: coordinates that are not numbers or
// lie far beyond the image, sizes and spacings of 0, NaN or 1e9 px, colours out of range. Each
// draws something sensible (checked against what the shape means inside the image) or throws
// RenderError, promptly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "swath/render/image.hpp"

namespace swath::render {
namespace {

using geometry::Point2;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const Color kInk{0, 0, 0, 1};

// A 200 x 100 px view where world metres are pixels (y up): pixel (x, y) shows (x, 100 - y).
View pixels_view() {
  View v;
  v.width_px = 200;
  v.height_px = 100;
  v.origin_y_m = 100;
  return v;
}

bool blank(const Image& im) {
  for (std::uint8_t c : im.rgb)
    if (c != 255) return false;
  return true;
}

int red(const Image& im, int x, int y) {
  return im.at(x, y, 0);
}

FilledPolygon filled(std::vector<Point2> ring) {
  return {{std::move(ring)}, kInk};
}

TEST(HostileScene, ShapeFarBelowTheImageDrawsNothingAtOnce) {
  // Its rows start past INT_MAX: the first row must not be cast from that double.
  Scene s;
  s.polygons.push_back(filled({{0, -1e12}, {50, -1e12}, {50, -2e12}}));
  s.polygons.push_back(filled({{0, -1e300}, {50, -1e300}, {50, -2e300}}));
  EXPECT_TRUE(blank(draw(s, pixels_view())));
}

TEST(HostileScene, HugeTriangleCoversItsHalfPlane) {
  // Vertices at +-1.5e308 px: their differences overflow a double. Inside the image the triangle
  // is the half-plane below world y = 50 (pixel rows 50 and down).
  Scene s;
  s.screen_polygons.push_back(filled({{-1.5e308, 50}, {1.5e308, 50}, {0, 1.5e308}}));
  const Image im = draw(s, pixels_view());
  for (int x : {0, 1, 100, 199}) {
    EXPECT_EQ(red(im, x, 49), 255) << x;
    EXPECT_EQ(red(im, x, 50), 0) << x;
    EXPECT_EQ(red(im, x, 99), 0) << x;
  }
}

TEST(HostileScene, PointThatIsNotANumberIsLeftOutOfItsRing) {
  // The square 10..90 with a NaN corner between two others: the square still (its ring closes
  // through the other corners), nothing right of it.
  Scene s;
  s.screen_polygons.push_back(filled({{10, 10}, {90, 10}, {kNan, kNan}, {90, 90}, {10, 90}}));
  const Image im = draw(s, pixels_view());
  EXPECT_EQ(red(im, 50, 50), 0);
  EXPECT_EQ(red(im, 150, 50), 255);
  EXPECT_EQ(red(im, 5, 50), 255);
}

TEST(HostileScene, ArrowheadsAreBoundedByTheLineInsideTheImage) {
  // A line 2e12 px long with arrowheads asked every 1e-9 px, and one reaching 1e300 px (its length
  // squared overflows a double): the heads outside the image are never made, and they are no
  // closer than 1 px.
  Scene s;
  s.screen_polylines.push_back({{{-1e12, 50}, {1e12, 50}}, 2, kInk, 1e-9});
  s.screen_polylines.push_back({{{-1e300, 20}, {1e300, 20}}, 2, kInk, 40});
  const Image im = draw(s, pixels_view());
  EXPECT_EQ(red(im, 100, 50), 0);
  EXPECT_EQ(red(im, 100, 20), 0);
  EXPECT_EQ(red(im, 100, 80), 255);
}

TEST(HostileScene, SizesThatAreNotNumbersDrawNothing) {
  Scene s;
  s.markers.push_back({{50, 50}, kNan, kInk, MarkerShape::disc});
  s.markers.push_back({{50, 50}, kInf, kInk, MarkerShape::disc});
  s.screen_polylines.push_back({{{10, 10}, {100, 50}, {190, 10}}, kNan, kInk});
  s.screen_polylines.push_back({{{10, 10}, {100, 50}, {190, 10}}, kInf, kInk});
  s.polylines.push_back({{{10, 10}}, 5, kInk, 10});  // one point: no segment
  EXPECT_TRUE(blank(draw(s, pixels_view())));
}

TEST(HostileScene, VeryWideLineIsItsRectangle) {
  // 1e20 px wide along x 10..190 (flat ends): every pixel between those columns, none outside.
  Scene s;
  s.screen_polylines.push_back({{{10, 50}, {190, 50}}, 1e20, kInk});
  const Image im = draw(s, pixels_view());
  for (int y : {0, 50, 99}) {
    EXPECT_EQ(red(im, 10, y), 0) << y;
    EXPECT_EQ(red(im, 189, y), 0) << y;
    EXPECT_EQ(red(im, 9, y), 255) << y;
    EXPECT_EQ(red(im, 190, y), 255) << y;
  }
}

TEST(HostileScene, ColoursAreTakenWithinZeroToOne) {
  // Alpha 2 is alpha 1 (not an overshoot past the colour), NaN is 0, 5 is 1.
  Scene s;
  s.screen_polygons.push_back(filled({{0, 0}, {100, 0}, {100, 100}, {0, 100}}));
  s.screen_polygons.back().fill = {0.5f, static_cast<float>(kNan), 5, 2};
  const Image im = draw(s, pixels_view());
  EXPECT_EQ(im.at(50, 50, 0), 128);
  EXPECT_EQ(im.at(50, 50, 1), 0);
  EXPECT_EQ(im.at(50, 50, 2), 255);
}

TEST(HostileScene, LabelHeightThatIsNotANumberIsRefused) {
  Scene s;
  s.labels.push_back({5, 20, "x", kNan});
  try {
    draw(s, pixels_view());
    FAIL() << "no RenderError";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("label's height"), std::string::npos) << e.what();
  }
  EXPECT_THROW(text_extent("x", kInf), RenderError);
}

TEST(HostileScene, LabelsOfAnyTextAndHeightDraw) {
  Scene s;
  s.labels.push_back({5, 20, "", 14});
  s.labels.push_back({5, 40, std::string(100000, 'x'), 14});
  s.labels.push_back({5, 60, "h\xc3\xa9llo \xe2\x82\xac \xff", 14});
  s.labels.push_back({5, 80, "x", 0});
  s.labels.push_back({5, 80, "x", 1e9});
  s.labels.push_back({2147483000, -2147483000, "far", 14});
  const Image im = draw(s, pixels_view());
  EXPECT_EQ(im.width, 200);
  EXPECT_GE(text_extent("x", 1e9).width_px, 1);
}

TEST(HostileScene, OnePixelViewAndOutOfRangeSizes) {
  View v = pixels_view();
  v.width_px = v.height_px = 1;
  Scene s;
  s.screen_polygons.push_back(filled({{0, 0}, {1, 0}, {0, 1}}));
  EXPECT_EQ(red(draw(s, v), 0, 0), 128);  // half the pixel
  for (int bad : {0, -1, 16385}) {
    v.width_px = bad;
    EXPECT_THROW(draw(s, v), RenderError) << bad;
  }
}

// The triangle (-B, -B), (B, B), (B, -B) in pixels is, inside the image, the part above the
// diagonal y = x (screen rows down): 15,000 px² of the 200 x 100 image (closed form), whatever B
// within the rasteriser's stated precision (crossings to ~1e-16 of the coordinates: B up to
// ~1e10 px and beyond). Far beyond (1e300, 1.5e308, where the clipping overflows) it only has to
// draw something, the same each time.
TEST(HostileScene, FarTriangleCoversTheClosedFormAreaInsideTheImage) {
  const auto covered_px2 = [](double b) {
    Scene s;
    s.screen_polygons.push_back(filled({{-b, -b}, {b, b}, {b, -b}}));
    const Image im = draw(s, pixels_view());
    double sum = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) sum += (255 - red(im, x, y)) / 255.0;
    return sum;
  };
  for (double b : {1e3, 1e9, 1e12}) EXPECT_NEAR(covered_px2(b), 15000, 100) << b;
  for (double b : {1e300, 1.5e308}) EXPECT_EQ(covered_px2(b), covered_px2(b)) << b;
}

TEST(HostileScene, ABackgroundThatIsNotANumberIsBlack) {
  Scene s;
  s.background = {static_cast<float>(kNan), 0.5f, 2.0f, 1};
  const Image im = draw(s, pixels_view());
  EXPECT_EQ(im.at(10, 10, 0), 0);    // NaN counts as 0
  EXPECT_EQ(im.at(10, 10, 1), 128);  // 0.5
  EXPECT_EQ(im.at(10, 10, 2), 255);  // clamped to 1
}

}  // namespace
}  // namespace swath::render

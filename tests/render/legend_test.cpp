// Legends measured with the font they are drawn in: inside their box at every size, text inside
// the backing box, drawn where they say they are.
#include "swath/render/legend.hpp"

#include <gtest/gtest.h>

#include "swath/render/chart.hpp"
#include "swath/render/image.hpp"

namespace swath::render {
namespace {

using geometry::Point2;

std::vector<LegendEntry> entries(int n, const std::string& longest) {
  std::vector<LegendEntry> out;
  for (int i = 0; i < n; ++i)
    out.push_back({i == n / 2 ? longest : "entry " + std::to_string(i),
                   static_cast<SwatchKind>(i % 3), Color{0.2f, 0.3f, 0.8f, 1}});
  return out;
}

// Every label's measured extent lies inside the box (a 1 px rounding allowance).
void expect_text_inside(const Scene& scene, const PixelBox& box) {
  int inside = 0;
  for (const Label& l : scene.labels) {
    const TextExtent e = text_extent(l.text, l.height_px);
    EXPECT_GE(l.x_px, box.left_px) << l.text;
    EXPECT_LE(l.x_px + e.width_px, box.right_px + 1) << l.text;
    EXPECT_GE(l.y_px - e.height_px, box.top_px - 1) << l.text;
    EXPECT_LE(l.y_px + e.baseline_px, box.bottom_px + 1) << l.text;
    ++inside;
  }
  EXPECT_GT(inside, 0);
}

TEST(Legend, FitsItsBoxAtEverySizeShrinkingTheTextAndAddingColumns) {
  const std::string longest = "encryption (key bits) of the onboard computation";
  for (auto [w, h] : {std::pair{640, 480}, {1600, 1200}, {320, 200}, {200, 120}}) {
    for (int n : {1, 4, 12, 30}) {
      Scene scene;
      const PixelBox within{w * 0.4, 30, w - 8.0, h - 8.0};
      const PixelBox box = add_legend(scene, entries(n, longest), within, Corner::bottom_right, 14);
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(n));
      EXPECT_GE(box.left_px, within.left_px);
      EXPECT_GE(box.top_px, within.top_px);
      EXPECT_LE(box.right_px, within.right_px);
      EXPECT_LE(box.bottom_px, within.bottom_px);
      EXPECT_DOUBLE_EQ(box.right_px, within.right_px);  // in its corner
      EXPECT_DOUBLE_EQ(box.bottom_px, within.bottom_px);
      // All entries, or the first few and "+N more" (N the rest) when 7 px text does not fit.
      ASSERT_GE(scene.labels.size(), 1u);
      ASSERT_LE(scene.labels.size(), static_cast<std::size_t>(n));
      if (scene.labels.size() < static_cast<std::size_t>(n)) {
        const std::size_t left_out = static_cast<std::size_t>(n) - scene.labels.size() + 1;
        EXPECT_EQ(scene.labels.back().text, std::string("+") + std::to_string(left_out) + " more");
      }
      expect_text_inside(scene, box);
      const LegendSize size = measure_legend(entries(n, longest), within.right_px - within.left_px,
                                             within.bottom_px - within.top_px, 14);
      EXPECT_DOUBLE_EQ(size.width_px, box.right_px - box.left_px);
      EXPECT_DOUBLE_EQ(size.height_px, box.bottom_px - box.top_px);
    }
  }
}

TEST(Legend, DrawnWhereItSaysWithAnOpaqueBoxAndNothingOutside) {
  Scene scene;
  scene.background = {1, 1, 1, 1};
  // A dark map behind: the backing box must lighten it.
  scene.screen_polygons.push_back({{{{0, 0}, {640, 0}, {640, 480}, {0, 480}}}, {0, 0, 0, 1}});
  const PixelBox box = add_legend(scene, entries(6, "a long legend entry"), {300, 100, 600, 440},
                                  Corner::top_right, 12);
  const Image image = draw(scene, View{1, 0, 0, 640, 480});
  // Inside the box, away from text and swatches (its last 3 px column inside the outline): light.
  const int x = static_cast<int>(box.right_px) - 4;
  for (int y = static_cast<int>(box.top_px) + 4; y < box.bottom_px - 4; ++y)
    EXPECT_GT(image.at(x, y, 0), 180) << y;
  // Just outside: the dark map, untouched.
  EXPECT_LT(image.at(static_cast<int>(box.right_px) + 3, static_cast<int>(box.top_px) + 10, 0), 20);
  EXPECT_LT(image.at(static_cast<int>(box.left_px) - 3, static_cast<int>(box.top_px) + 10, 0), 20);
  // Text drawn: dark pixels inside the box's text column.
  int dark = 0;
  for (int y = static_cast<int>(box.top_px); y < box.bottom_px; ++y)
    for (int xx = static_cast<int>(box.left_px) + 30; xx < box.right_px - 5; ++xx)
      dark += image.at(xx, y, 0) < 90;
  EXPECT_GT(dark, 50);
}

TEST(Legend, TheTextShrinksToTheWidthGiven) {
  const std::string text = "drone 3 charlie: 2.59 km, 6 min 57 s";
  const double h = fitted_text_height(text, 240, 16);
  EXPECT_LT(h, 16);
  EXPECT_LE(text_extent(text, h).width_px, 240);
  EXPECT_GT(text_extent(text, h + 1).width_px, 240);  // the largest whole pixel height that fits
  EXPECT_EQ(fitted_text_height("N", 240, 16), 16);
}

TEST(FitInto, TheExtentCentredInTheBoxAtTheLargestScale) {
  const PixelBox box{20, 100, 420, 300};
  const View v = fit_into({0, 0}, {100, 50}, box, 640, 480);
  EXPECT_DOUBLE_EQ(v.px_per_m, 4);  // both fit exactly: 400 / 100 and 200 / 50
  const Point2 lo = v.to_pixel({0, 0}), hi = v.to_pixel({100, 50});
  EXPECT_NEAR(lo.x, 20, 1e-9);
  EXPECT_NEAR(lo.y, 300, 1e-9);
  EXPECT_NEAR(hi.x, 420, 1e-9);
  EXPECT_NEAR(hi.y, 100, 1e-9);
}

TEST(ChartLegend, LongSeriesNamesStayInsideThePlot) {
  ChartSpec spec{"Parameters (0 lowest, 1 highest)", "time (s)", "level", {}};
  for (const char* name : {"c1", "detection (fps)", "encryption (key bits)"})
    spec.series.push_back({name, {0, 10}, {0, 1}, {0.2f, 0.2f, 0.8f, 1}});
  for (auto [w, h] : {std::pair{640, 160}, {800, 300}, {1600, 400}}) {
    ChartLayout layout{};
    const Scene scene = chart_scene(spec, w, h, &layout);
    EXPECT_GE(layout.legend.left_px, layout.left_px);
    EXPECT_LE(layout.legend.right_px, layout.right_px);
    EXPECT_GE(layout.legend.top_px, layout.top_px);
    EXPECT_LE(layout.legend.bottom_px, layout.bottom_px);
    for (const Label& l : scene.labels) {
      const TextExtent e = text_extent(l.text, l.height_px);
      EXPECT_GE(l.x_px, 0) << l.text;
      EXPECT_LE(l.x_px + e.width_px, w) << l.text;
      if (l.text == "encryption (key bits)") {
        EXPECT_LE(l.x_px + e.width_px, layout.legend.right_px);
      }
    }
  }
}

}  // namespace
}  // namespace swath::render

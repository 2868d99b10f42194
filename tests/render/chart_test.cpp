#include "swath/render/chart.hpp"

#include <gtest/gtest.h>

#include "swath/render/image.hpp"

namespace swath::render {
namespace {

TEST(NiceTicks, RoundStepsCoveringTheRange) {
  EXPECT_EQ(nice_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(nice_ticks(3.2, 97, 4), (std::vector<double>{0, 50, 100}));
  const auto t = nice_ticks(0.013, 0.061, 5);
  EXPECT_NEAR(t.front(), 0.01, 1e-12);
  EXPECT_NEAR(t[1] - t[0], 0.01, 1e-12);
}

TEST(Chart, SeriesPassThroughTheirPixels) {
  ChartSpec spec{
      "power", "t (s)", "W", {{"measured", {0, 50, 100}, {0, 50, 100}, {0.8f, 0.1f, 0.1f, 1}, 3}}};
  ChartLayout layout{};
  const Scene scene = chart_scene(spec, 600, 400, &layout);
  EXPECT_DOUBLE_EQ(layout.x_min, 0);
  EXPECT_DOUBLE_EQ(layout.x_max, 100);
  const Image image = draw(scene, View{1, 0, 0, 600, 400});
  // The series' middle point (50, 50) is red; a point of the plot away from it is not.
  const int x = static_cast<int>(layout.to_x_px(50)), y = static_cast<int>(layout.to_y_px(50));
  EXPECT_GT(image.at(x, y, 0), 150);
  EXPECT_LT(image.at(x, y, 1), 100);
  const int far_y = static_cast<int>(layout.to_y_px(90));
  EXPECT_GT(image.at(x, far_y, 1), 150);  // grey grid or white, not the series
  // The axis is dark at the bottom-left corner of the plot.
  EXPECT_LT(image.at(static_cast<int>(layout.left_px), static_cast<int>(layout.bottom_px) - 10, 0),
            160);
  EXPECT_THROW(chart_scene({"", "", "", {{"bad", {1, 2}, {1}, {}, 1}}}, 600, 400),
               std::invalid_argument);
}

}  // namespace
}  // namespace swath::render

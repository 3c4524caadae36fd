// The scatter plot of `bsg dataset info --plot` (render/scatter_plot.h): round
// ticks by hand, a point drawn where the axes put it, and coinciding episodes
// drawn as one disc of their count's area.
#include "render/scatter_plot.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bsg::render {
namespace {

TEST(ScatterPlot, RoundTicks) {
  // 25 / 5 = 5: steps of 5.
  EXPECT_EQ(round_ticks(0, 25), (std::vector<double>{0, 5, 10, 15, 20, 25}));
  // (28.8 + 2.4) / 5 = 6.24: steps of 10, from -10 to 30.
  EXPECT_EQ(round_ticks(-2.4, 28.8), (std::vector<double>{-10, 0, 10, 20, 30}));
  // 0.9 / 5 = 0.18: steps of 0.2.
  const std::vector<double> small = round_ticks(0.1, 1.0);
  ASSERT_EQ(small.size(), 6u);
  EXPECT_NEAR(small.front(), 0.0, 1e-12);
  EXPECT_NEAR(small.back(), 1.0, 1e-12);
  EXPECT_THROW(round_ticks(2, 1), std::invalid_argument);
}

bool is_point_blue(const Image& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  return p[0] == 31 && p[1] == 119 && p[2] == 180;
}

TEST(ScatterPlot, PointsLandWhereTheAxesSay) {
  ScatterPlotOptions options;
  options.width = 720;
  options.height = 540;
  // x ticks 0..25 and y ticks -10..30 as above; the plot area is x in [110, 690], y in [44, 460],
  // inset by 12 pixels: x = 0 -> 122, x = 25 -> 678; y = 30 -> 56, y = -10 -> 448.
  const Image image = scatter_plot({0.0, 25.0, 12.5}, {30.0, -10.0, 10.0}, options);
  EXPECT_TRUE(is_point_blue(image, 122, 56));
  EXPECT_TRUE(is_point_blue(image, 678, 448));
  EXPECT_TRUE(is_point_blue(image, 400, 252));
  EXPECT_FALSE(is_point_blue(image, 300, 150));
  EXPECT_THROW(scatter_plot({0.0}, {}, options), std::invalid_argument);
  EXPECT_THROW(scatter_plot({0.0}, {std::nan("")}, options), std::invalid_argument);
}

TEST(ScatterPlot, EpisodesOnOnePixelMakeADiscWhoseAreaCountsThem) {
  ScatterPlotOptions options;
  // The axes of the test above: (0, 30) at pixel (122, 56), (25, -10) at (678, 448).
  // Four episodes at (0, 30): radius 3 sqrt(4) = 6; one at (25, -10): radius 3.
  const Image image = scatter_plot({0.0, 0.0, 0.0, 0.0, 25.0}, {30.0, 30.0, 30.0, 30.0, -10.0}, options);
  EXPECT_TRUE(is_point_blue(image, 122 + 4, 56));   // inside the rim of the four
  EXPECT_FALSE(is_point_blue(image, 122 + 7, 56));  // beyond radius 6
  const std::uint8_t* rim = image.pixel(122 + 6, 56);  // its dark rim
  EXPECT_LT(rim[2], 180);
  EXPECT_TRUE(is_point_blue(image, 678 + 3, 448));  // a single episode: radius 3, no rim
  EXPECT_FALSE(is_point_blue(image, 678 + 4, 448));
}

}  // namespace
}  // namespace bsg::render

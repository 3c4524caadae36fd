// A scatter plot as an RGB image (for `bsg dataset info --plot`: DSRL's
// picture of a dataset, each episode's cost return against its reward
// return). Axes with about five round ticks each, labelled in the caption
// font (render/caption.h), points as small dots (points falling on one pixel
// as one disc, its area proportional to their count up to a radius of 15
// pixels, the count written beside it), and an optional dashed vertical line
// (the cost limit).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/image.h"

namespace bsg::render {

struct ScatterPlotOptions {
  int width = 720;
  int height = 540;
  std::string x_label;  // in the caption font's characters (digits, ". - : /", "episode step return cost")
  std::string y_label;
  std::optional<double> vertical_line;  // an x drawn as a dashed red line
};

// Round tick values covering [low, high]: steps of 1, 2 or 5 times a power of
// ten, about `count` of them. Throws std::invalid_argument if low > high or
// either is not finite.
std::vector<double> round_ticks(double low, double high, int count = 5);

// Throws std::invalid_argument if xs and ys differ in length or hold a value
// that is not finite.
Image scatter_plot(const std::vector<double>& xs, const std::vector<double>& ys, const ScatterPlotOptions& options);

}  // namespace bsg::render

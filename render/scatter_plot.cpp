#include "render/scatter_plot.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <utility>
#include <sstream>
#include <stdexcept>

#include "render/caption.h"

namespace bsg::render {
namespace {

// A disc of many episodes stops growing here, so that it hides few of its neighbours.
constexpr double kLargestRadius = 15.0;

void put(Image& image, int x, int y, int r, int g, int b) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  std::uint8_t* p = image.pixel(x, y);
  p[0] = static_cast<std::uint8_t>(r);
  p[1] = static_cast<std::uint8_t>(g);
  p[2] = static_cast<std::uint8_t>(b);
}

// A tick's text: as few decimals as its step needs.
std::string tick_text(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << (std::abs(value) < step * 1e-9 ? 0.0 : value);
  return out.str();
}

}  // namespace

std::vector<double> round_ticks(double low, double high, int count) {
  if (!std::isfinite(low) || !std::isfinite(high) || low > high || count < 1) {
    throw std::invalid_argument("round_ticks: needs finite low <= high and count >= 1");
  }
  if (low == high) {
    low -= 1.0;
    high += 1.0;
  }
  const double raw = (high - low) / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * power;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::floor(low / step) * step; t <= high + step * 1e-9; t += step) ticks.push_back(t);
  if (ticks.back() < high) ticks.push_back(ticks.back() + step);
  return ticks;
}

Image scatter_plot(const std::vector<double>& xs, const std::vector<double>& ys, const ScatterPlotOptions& options) {
  if (xs.size() != ys.size()) throw std::invalid_argument("scatter_plot: as many x as y values are needed");
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
      throw std::invalid_argument("scatter_plot: point " + std::to_string(i) + " is not finite");
    }
  }
  Image image{options.width, options.height,
              std::vector<std::uint8_t>(static_cast<std::size_t>(options.width * options.height * 3), 255)};
  const int scale = 2;
  const int left = 110, right = 30, top = 44, bottom = 80;
  const int inset = 12;  // points on the extreme ticks stay off the frame
  const int plot_w = options.width - left - right, plot_h = options.height - top - bottom;
  double x_low = 0.0, x_high = 1.0, y_low = 0.0, y_high = 1.0;
  if (!xs.empty()) {
    const auto [x_min, x_max] = std::minmax_element(xs.begin(), xs.end());
    const auto [y_min, y_max] = std::minmax_element(ys.begin(), ys.end());
    x_low = *x_min, x_high = *x_max, y_low = *y_min, y_high = *y_max;
  }
  if (options.vertical_line) {
    x_low = std::min(x_low, *options.vertical_line);
    x_high = std::max(x_high, *options.vertical_line);
  }
  const std::vector<double> x_ticks = round_ticks(x_low, x_high);
  const std::vector<double> y_ticks = round_ticks(y_low, y_high);
  x_low = x_ticks.front(), x_high = x_ticks.back(), y_low = y_ticks.front(), y_high = y_ticks.back();
  const auto px = [&](double x) {
    return left + inset + static_cast<int>(std::lround((x - x_low) / (x_high - x_low) * (plot_w - 2 * inset)));
  };
  const auto py = [&](double y) {
    return top + plot_h - inset - static_cast<int>(std::lround((y - y_low) / (y_high - y_low) * (plot_h - 2 * inset)));
  };
  // Grid lines and tick labels.
  for (double t : x_ticks) {
    for (int y = top; y <= top + plot_h; ++y) put(image, px(t), y, 225, 225, 225);
    const std::string text = tick_text(t, x_ticks[1] - x_ticks[0]);
    draw_text(image, px(t) - text_width(text, scale) / 2, top + plot_h + 10, text, scale, 0, 0, 0);
  }
  for (double t : y_ticks) {
    for (int x = left; x <= left + plot_w; ++x) put(image, x, py(t), 225, 225, 225);
    const std::string text = tick_text(t, y_ticks[1] - y_ticks[0]);
    draw_text(image, left - 10 - text_width(text, scale), py(t) - 7, text, scale, 0, 0, 0);
  }
  // The frame.
  for (int x = left; x <= left + plot_w; ++x) put(image, x, top, 0, 0, 0), put(image, x, top + plot_h, 0, 0, 0);
  for (int y = top; y <= top + plot_h; ++y) put(image, left, y, 0, 0, 0), put(image, left + plot_w, y, 0, 0, 0);
  if (options.vertical_line) {
    for (int y = top; y <= top + plot_h; ++y) {
      if ((y / 6) % 2 == 0) put(image, px(*options.vertical_line), y, 220, 30, 30);
    }
  }
  // The points: filled discs of radius 3. Episodes landing on one pixel (a task whose returns
  // and costs are whole numbers, such as Gather's) make one disc whose area grows with their
  // count, so that a heavy point does not look like a single episode; its rim is drawn dark.
  std::map<std::pair<int, int>, int> counts;
  for (std::size_t i = 0; i < xs.size(); ++i) ++counts[{px(xs[i]), py(ys[i])}];
  for (const auto& [centre, count] : counts) {
    const double radius = std::min(kLargestRadius, 3.0 * std::sqrt(static_cast<double>(count)));
    const int reach = static_cast<int>(std::ceil(radius));
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const double distance = std::sqrt(static_cast<double>(dx * dx + dy * dy));
        if (distance > radius) continue;
        const bool rim = count > 1 && distance > radius - 1.0;
        put(image, centre.first + dx, centre.second + dy, rim ? 8 : 31, rim ? 48 : 119, rim ? 107 : 180);
      }
    }
  }
  // Their counts, beside the discs (after all discs, so that no disc covers a count).
  for (const auto& [centre, count] : counts) {
    if (count < 2) continue;
    const int reach = static_cast<int>(std::ceil(std::min(kLargestRadius, 3.0 * std::sqrt(static_cast<double>(count)))));
    draw_text(image, centre.first + reach + 3, centre.second - reach - 4, std::to_string(count), 1, 8, 48, 107);
  }
  draw_text(image, left + plot_w / 2 - text_width(options.x_label, scale) / 2, options.height - 35, options.x_label,
            scale, 0, 0, 0);
  draw_text(image, 8, 8, options.y_label, scale, 0, 0, 0);
  return image;
}

}  // namespace bsg::render

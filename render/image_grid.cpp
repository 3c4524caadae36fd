#include "render/image_grid.h"

#include <algorithm>
#include <stdexcept>

namespace bsg::render {

Image image_grid(std::span<const Image> images, int columns, int gap_px) {
  if (images.empty() || columns < 1) throw std::invalid_argument("image_grid: no images");
  const int w = images[0].width, h = images[0].height;
  for (const Image& image : images) {
    if (image.width != w || image.height != h) {
      throw std::invalid_argument("image_grid: the images differ in size");
    }
  }
  const int count = static_cast<int>(images.size());
  const int rows = (count + columns - 1) / columns;
  const int used_columns = std::min(columns, count);
  Image grid;
  grid.width = used_columns * (w + gap_px) + gap_px;
  grid.height = rows * (h + gap_px) + gap_px;
  grid.rgb.assign(static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height) * 3, 255);
  for (int i = 0; i < count; ++i) {
    const int x0 = gap_px + (i % columns) * (w + gap_px);
    const int y0 = gap_px + (i / columns) * (h + gap_px);
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* source = images[static_cast<size_t>(i)].pixel(0, y);
      std::copy_n(source, static_cast<size_t>(w) * 3,
                  grid.rgb.begin() + (static_cast<std::ptrdiff_t>(y0 + y) * grid.width + x0) * 3);
    }
  }
  return grid;
}

}  // namespace bsg::render

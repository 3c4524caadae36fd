// An H×W×3 uint8 RGB image, row 0 at the top (NumPy's and PNG's order).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bsg::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // height·width·3 bytes

  const std::uint8_t* pixel(int x, int y) const { return &rgb[offset(x, y)]; }
  std::uint8_t* pixel(int x, int y) { return &rgb[offset(x, y)]; }
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  }
};

}  // namespace bsg::render

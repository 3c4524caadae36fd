// Images of one size laid out in a grid, row by row (the 4×4 picture of the
// environments, the trajectory plot's one panel per episode).
#pragma once

#include <span>

#include "render/image.h"

namespace bsg::render {

// `columns` images per row, a `gap_px` white border between and around them.
// Throws std::invalid_argument if the images differ in size or none is given.
Image image_grid(std::span<const Image> images, int columns, int gap_px);

}  // namespace bsg::render

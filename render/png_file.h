// Writes an RGB image as a PNG file (libpng).
#pragma once

#include <string>

#include "render/image.h"

namespace bsg::render {

// Throws std::runtime_error naming the path if it cannot be written.
void write_png(const std::string& path, const Image& image);

}  // namespace bsg::render

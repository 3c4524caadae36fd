// A one-line caption drawn into the top-left corner of a frame (a video's
// episode, step, return and cost), white on a dark box, with a built-in 5×7
// pixel font of the digits, ". - : /" and the letters of
// "episode step return cost"; any other character is drawn as a space.
#pragma once

#include <string_view>

#include "render/image.h"

namespace bsg::render {

// Glyphs are scaled by max(1, height / 180) so that they stay legible at 480×360.
void draw_caption(Image& image, std::string_view text);

}  // namespace bsg::render

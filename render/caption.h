// A caption drawn into the top-left corner of a frame (a video's episode,
// step, return and cost), white on a dark box, with a built-in 5×7 pixel font
// of the digits, ". - : /" and the letters of "episode step return cost"; any
// other character is drawn as a space.
//
// A caption is a list of fields ("episode 3", "step 180", ...). They share one
// line, two spaces apart, when that line fits the frame; otherwise they are
// split over as few lines as fit, and only when one field per line is still
// too wide does the glyph scale shrink (down to 1: 6 px per character). So any
// frame at least 6 px wider than its longest field (6·12 + 4 = 76 px for a
// video's fields up to "return -9999.9") shows every character.
#pragma once

#include <string>
#include <vector>

#include "render/image.h"

namespace bsg::render {

struct CaptionLayout {
  int scale = 1;                   // pixels per font cell
  std::vector<std::string> lines;  // the fields, joined into lines
  int box_width = 0;               // the dark box, from the frame's top-left corner
  int box_height = 0;
};

// The preferred glyph scale of a frame: max(1, height / 180), legible at 480×360.
int preferred_caption_scale(int height);

// How `fields` fit a frame `width` wide and `height` high (see above).
CaptionLayout layout_caption(const std::vector<std::string>& fields, int width, int height);

// Draws `text` in the caption font with its top-left corner at (x, y), each
// font cell `scale` pixels, in the colour (r, g, b); for the labels of plots.
void draw_text(Image& image, int x, int y, const std::string& text, int scale, int r, int g, int b);
// The width in pixels of `text` drawn at `scale` (6 cells a character, the last without its gap).
int text_width(const std::string& text, int scale);

// Draws `fields` as layout_caption lays them out; returns the layout.
CaptionLayout draw_caption(Image& image, const std::vector<std::string>& fields);

}  // namespace bsg::render

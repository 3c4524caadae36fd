// Captions fit their frame: at 240, 480 and 1920 pixels wide (and a range of
// heights) every lit pixel of the text is inside the frame. Oracle: the same
// fields drawn on an 8192-pixel-wide frame of the same height (one line, the
// preferred scale, nothing near an edge) light the same number of font cells
// (white pixels / scale²); a cut caption lights fewer. The layouts of the
// issue's examples are worked out by hand: 6·scale pixels per character plus a
// margin of 2·scale on each side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "render/caption.h"
#include "render/image.h"

namespace bsg::render {
namespace {

constexpr std::uint8_t kGrey = 200;

Image grey(int width, int height) {
  return {width, height, std::vector<std::uint8_t>(static_cast<size_t>(width * height * 3), kGrey)};
}

struct Drawn {
  int white = 0;       // pixels set to (255, 255, 255)
  int right_most = -1;  // the right-most column the caption changed
  int bottom_most = -1;
};

Drawn measure(const Image& image) {
  Drawn drawn;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      if (p[0] == kGrey && p[1] == kGrey && p[2] == kGrey) continue;
      drawn.right_most = std::max(drawn.right_most, x);
      drawn.bottom_most = std::max(drawn.bottom_most, y);
      if (p[0] == 255 && p[1] == 255 && p[2] == 255) ++drawn.white;
    }
  }
  return drawn;
}

// Lit font cells of `fields` drawn where nothing can cut them.
int lit_cells(const std::vector<std::string>& fields, int height) {
  Image wide = grey(8192, height);
  const CaptionLayout layout = draw_caption(wide, fields);
  EXPECT_EQ(layout.lines.size(), 1u);
  const int scale = preferred_caption_scale(height);
  return measure(wide).white / (scale * scale);
}

const std::vector<std::vector<std::string>> kCaptions = {
    {"episode 1", "step 180", "return 257.0", "cost 12"},                // the issue's frame
    {"episode 1000", "step 1000", "return -12345.6", "cost 1000"},       // the longest a run gives
    {"episode 3", "return 4.2", "cost 0"},                               // a trajectory panel
};

TEST(Caption, EveryLitCellIsInsideTheFrameAt240_480And1920PixelsWide) {
  for (const int width : {240, 480, 1920}) {
    for (const int height : {120, 180, 360, 720, 1080, 1440, 2160}) {
      for (const std::vector<std::string>& fields : kCaptions) {
        Image image = grey(width, height);
        const CaptionLayout layout = draw_caption(image, fields);
        const Drawn drawn = measure(image);
        const std::string where = std::to_string(width) + "x" + std::to_string(height) + " " + fields[0];
        EXPECT_LE(layout.box_width, width) << where;
        EXPECT_LT(drawn.right_most, width) << where;
        // Every cell drawn: the same count as on the unconstrained frame.
        EXPECT_EQ(drawn.white, lit_cells(fields, height) * layout.scale * layout.scale) << where;
        // The box keeps its margin of 2·scale inside the frame on the right.
        EXPECT_LE(drawn.right_most + 1, layout.box_width) << where;
        EXPECT_GE(layout.scale, 1) << where;
        EXPECT_LE(drawn.bottom_most + 1, height / 4 + 1) << where << ": the caption covers the frame";
      }
    }
  }
}

TEST(Caption, IssueFrameAt480x360TakesTwoLinesAtScale2) {
  // One line: 4 + 4 + 12·42 = 512 px > 480; two lines of 19 and 21 characters: 4 + 4 + 12·21 = 260.
  const CaptionLayout layout = layout_caption(kCaptions[0], 480, 360);
  EXPECT_EQ(layout.scale, 2);
  ASSERT_EQ(layout.lines.size(), 2u);
  EXPECT_EQ(layout.lines[0], "episode 1  step 180");
  EXPECT_EQ(layout.lines[1], "return 257.0  cost 12");
  EXPECT_EQ(layout.box_width, 260);
  EXPECT_EQ(layout.box_height, 4 + 4 + 2 * 18 - 4);  // margins, 9 cells a line, no gap below the last
}

TEST(Caption, OneLineWhereItFitsAndTheScaleKeptWhileLinesCanSplit) {
  // 1920×1080: scale 6, 12 + 12 + 36·42 = 1536 ≤ 1920, one line.
  const CaptionLayout wide = layout_caption(kCaptions[0], 1920, 1080);
  EXPECT_EQ(wide.scale, 6);
  EXPECT_EQ(wide.lines.size(), 1u);
  EXPECT_EQ(wide.box_width, 1536);
  // 1920×1440: scale 8, one line 16 + 16 + 48·42 = 2048 > 1920: two lines, scale kept.
  const CaptionLayout tall = layout_caption(kCaptions[0], 1920, 1440);
  EXPECT_EQ(tall.scale, 8);
  EXPECT_EQ(tall.lines.size(), 2u);
  // 240×180: scale 1, 4 + 6·42 = 256 > 240: two lines of at most 21 characters, 130 px.
  const CaptionLayout small = layout_caption(kCaptions[0], 240, 180);
  EXPECT_EQ(small.scale, 1);
  EXPECT_EQ(small.lines.size(), 2u);
  EXPECT_EQ(small.box_width, 130);
  // The trajectory panel's 480×360 caption still fits on one line: 8 + 12·29 = 356.
  const CaptionLayout panel = layout_caption(kCaptions[2], 480, 360);
  EXPECT_EQ(panel.lines.size(), 1u);
  EXPECT_EQ(panel.box_width, 356);
}

TEST(Caption, ScaleShrinksOnlyWhenOneFieldPerLineIsTooWide) {
  // 100×720: preferred scale 4; the longest field "return -12345.6" (15 characters)
  // needs 16 + 24·15 = 376 px at scale 4, 8 + 12·15 = 188 at 2 and 4 + 6·15 = 94 at 1,
  // so scale 1 with one field per line (two fields on a line need 4 + 6·26 = 160).
  const CaptionLayout narrow = layout_caption(kCaptions[1], 100, 720);
  EXPECT_EQ(narrow.scale, 1);
  EXPECT_EQ(narrow.lines.size(), 4u);
  EXPECT_EQ(narrow.box_width, 94);
}

}  // namespace
}  // namespace bsg::render

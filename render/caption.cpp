#include "render/caption.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace bsg::render {
namespace {

struct Glyph {
  char character;
  std::array<const char*, 7> rows;  // '#' marks a lit pixel
};

// The 5×7 font: only the characters captions use.
constexpr Glyph kFont[] = {
    {'0', {" ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### "}},
    {'1', {"  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### "}},
    {'2', {" ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####"}},
    {'3', {"#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### "}},
    {'4', {"   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # "}},
    {'5', {"#####", "#    ", "#### ", "    #", "    #", "#   #", " ### "}},
    {'6', {"  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### "}},
    {'7', {"#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   "}},
    {'8', {" ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### "}},
    {'9', {" ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  "}},
    {'.', {"     ", "     ", "     ", "     ", "     ", " ##  ", " ##  "}},
    {'-', {"     ", "     ", "     ", "#####", "     ", "     ", "     "}},
    {':', {"     ", " ##  ", " ##  ", "     ", " ##  ", " ##  ", "     "}},
    {'/', {"     ", "    #", "   # ", "  #  ", " #   ", "#    ", "     "}},
    {'c', {"     ", "     ", " ### ", "#    ", "#    ", "#   #", " ### "}},
    {'d', {"    #", "    #", " ## #", "#  ##", "#   #", "#   #", " ####"}},
    {'e', {"     ", "     ", " ### ", "#   #", "#####", "#    ", " ### "}},
    {'i', {"  #  ", "     ", " ##  ", "  #  ", "  #  ", "  #  ", " ### "}},
    {'n', {"     ", "     ", "# ## ", "##  #", "#   #", "#   #", "#   #"}},
    {'o', {"     ", "     ", " ### ", "#   #", "#   #", "#   #", " ### "}},
    {'p', {"     ", "     ", "#### ", "#   #", "#### ", "#    ", "#    "}},
    {'r', {"     ", "     ", "# ## ", "##  #", "#    ", "#    ", "#    "}},
    {'s', {"     ", "     ", " ####", "#    ", " ### ", "    #", "#### "}},
    {'t', {" #   ", " #   ", "###  ", " #   ", " #   ", " #  #", "  ## "}},
    {'u', {"     ", "     ", "#   #", "#   #", "#   #", "#  ##", " ## #"}},
};

const Glyph* find_glyph(char c) {
  for (const Glyph& glyph : kFont) {
    if (glyph.character == c) return &glyph;
  }
  return nullptr;
}

void fill(Image& image, int x0, int y0, int w, int h, int r, int g, int b, bool darken) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y) {
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x) {
      std::uint8_t* p = image.pixel(x, y);
      if (darken) {
        for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(p[k] * 3 / 10);
      } else {
        p[0] = static_cast<std::uint8_t>(r);
        p[1] = static_cast<std::uint8_t>(g);
        p[2] = static_cast<std::uint8_t>(b);
      }
    }
  }
}

// The box around `lines` at `scale`: a margin of 2 cells on every side, 6 cells
// per character (5 lit and 1 after it), 9 cells per line (7 lit and 2 between).
CaptionLayout boxed(std::vector<std::string> lines, int scale) {
  CaptionLayout layout{scale, std::move(lines), 0, 0};
  size_t longest = 0;
  for (const std::string& line : layout.lines) longest = std::max(longest, line.size());
  const int margin = 2 * scale;
  layout.box_width = 2 * margin + 6 * scale * static_cast<int>(longest);
  layout.box_height = 2 * margin + 9 * scale * static_cast<int>(layout.lines.size()) - 2 * scale;
  return layout;
}

// `fields` in `count` lines of consecutive fields, each line as short as the
// split allows (greedy by length: a line takes fields while it is not longer
// than an even share of the whole).
std::vector<std::string> split_into_lines(const std::vector<std::string>& fields, size_t count) {
  const std::string separator = "  ";
  size_t total = 0;
  for (const std::string& field : fields) total += field.size() + separator.size();
  const size_t share = (total + count - 1) / count;
  std::vector<std::string> lines(1);
  for (size_t i = 0; i < fields.size(); ++i) {
    const size_t fields_left = fields.size() - i, lines_left = count - lines.size();
    const bool full = !lines.back().empty() &&
                      (lines.back().size() + separator.size() + fields[i].size() > share ||
                       fields_left <= lines_left);
    if (full && lines.size() < count) lines.emplace_back();
    if (!lines.back().empty()) lines.back() += separator;
    lines.back() += fields[i];
  }
  return lines;
}

}  // namespace

int preferred_caption_scale(int height) { return std::max(1, height / 180); }

CaptionLayout layout_caption(const std::vector<std::string>& fields, int width, int height) {
  if (fields.empty()) return boxed({}, preferred_caption_scale(height));
  for (int scale = preferred_caption_scale(height); scale >= 1; --scale) {
    for (size_t count = 1; count <= fields.size(); ++count) {
      CaptionLayout layout = boxed(split_into_lines(fields, count), scale);
      if (layout.box_width <= width) return layout;
    }
  }
  return boxed(split_into_lines(fields, fields.size()), 1);  // narrower than a field: cut
}

void draw_text(Image& image, int x, int y, const std::string& text, int scale, int r, int g, int b) {
  for (size_t i = 0; i < text.size(); ++i) {
    const Glyph* glyph = find_glyph(text[i]);
    if (glyph == nullptr) continue;
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if (glyph->rows[static_cast<size_t>(row)][col] != '#') continue;
        fill(image, x + static_cast<int>(i) * 6 * scale + col * scale, y + row * scale, scale, scale, r, g, b, false);
      }
    }
  }
}

int text_width(const std::string& text, int scale) {
  return text.empty() ? 0 : (6 * static_cast<int>(text.size()) - 1) * scale;
}

CaptionLayout draw_caption(Image& image, const std::vector<std::string>& fields) {
  const CaptionLayout layout = layout_caption(fields, image.width, image.height);
  const int scale = layout.scale, margin = 2 * scale;
  fill(image, 0, 0, layout.box_width, layout.box_height, 0, 0, 0, true);
  for (size_t line = 0; line < layout.lines.size(); ++line) {
    const int top = margin + static_cast<int>(line) * 9 * scale;
    draw_text(image, margin, top, layout.lines[line], scale, 255, 255, 255);
  }
  return layout;
}

}  // namespace bsg::render

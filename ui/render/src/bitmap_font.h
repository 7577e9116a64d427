#pragma once
// A tiny built-in 5 x 7 pixel font (digits, A-Z, a few symbols; lower case drawn as upper case) for
// legends and contact-sheet labels, so the renderer needs no font library.
#include <array>
#include <cstdint>
#include <string_view>

#include "drape/render/image.h"

namespace drape::render {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;  // pixels per character at scale 1, including one column of spacing

// True when pixel (col, row) of character c is ink; row 0 is the top. Unknown characters are blank.
bool glyphPixel(char c, int col, int row);

// Width and height in pixels of text drawn at an integer scale.
int textWidth(std::string_view text, int scale);
inline int textHeight(int scale) { return kGlyphHeight * scale; }

// Draws text into an image with its top-left corner at (x, y), clipped to the image.
void drawText(Image& image, int x, int y, std::string_view text, int scale, std::array<std::uint8_t, 3> rgb);

}  // namespace drape::render

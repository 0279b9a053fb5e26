// A 5x7 pixel font for short texts drawn into images (the heatmap's legend, rtdiff):
// digits, capital letters and the punctuation " :,.-+=<>()/%?". A lower-case letter is
// drawn as its capital, any other character the font lacks as '?'.
#pragma once
#include <cstdint>
#include <string>

#include "rt/image/image.h"

namespace rt {

constexpr int kGlyphWidth = 5;    // font pixels
constexpr int kGlyphHeight = 7;   // font pixels
constexpr int kGlyphAdvance = 6;  // font pixels from one character's left edge to the next's

// The width in image pixels of `text` drawn at `scale` (each font pixel a scale x scale
// square), from the first glyph's left edge to the last one's right edge; 0 when empty.
int text_width(const std::string& text, int scale);

// Draws `text` in colour `rgb` with the top left of its first glyph at column x, row y;
// only the glyphs' set pixels are painted, and those outside `img` are skipped.
void draw_text(Image& img, int x, int y, const std::string& text, int scale, const uint8_t rgb[3]);

}  // namespace rt

#pragma once
// The built-in 5x7 dot font: enough glyphs for a clock and a frame counter, compiled into the
// program so that no font file is needed at run time.
#include <cstdint>

namespace discreel::render {

inline constexpr int kGlyphColumns = 5;
inline constexpr int kGlyphRows = 7;
inline constexpr int kGlyphAdvance = 6;   // dots from one glyph to the next

// 35 bits: bit (row * 5 + column) is set where the glyph has a dot; row 0 is the top, column 0 the
// left. Characters without a glyph map to '?'.
std::uint64_t glyph_bits(char c);

}  // namespace discreel::render

#pragma once
// Text overlays as per-glyph instances: each glyph is one quad whose fragment shader looks up
// its 5x7 dot pattern, so a whole line of text is one draw with no texture.
#include <cstdint>
#include <vector>

#include "discreel/render.hpp"

namespace discreel::render {

struct GlyphInstance {
    float origin[2];     // pixels from the image centre, y up: the glyph's top-left corner
    float dot;           // pixels per dot
    // glyph_bits() split for 32-bit attributes: rows 0-3 in [0], rows 4-6 in [1], each row
    // 5 bits, left column lowest.
    std::uint32_t bits[2];
    float color[4];
};

// Replaces the contents of `out`: every text's shadows first, then its glyphs, so no shadow
// falls on a neighbouring glyph.
void make_text_instances(const FrameScene& frame, int width, int height,
                         std::vector<GlyphInstance>& out);

}  // namespace discreel::render

#include "text_instances.hpp"

#include <algorithm>

#include "glyph_font.hpp"

namespace discreel::render {
namespace {

// Dark and translucent: legible over light discs and invisible over a dark background.
constexpr float kShadowColor[4] = {0.0f, 0.0f, 0.0f, 0.6f};
constexpr int kMarginDots = 4;   // from the frame's edges
constexpr int kFirstFourRowsBits = 4 * kGlyphColumns;
constexpr std::uint64_t kFirstFourRows = (std::uint64_t{1} << kFirstFourRowsBits) - 1;

}  // namespace

void make_text_instances(const FrameScene& frame, int width, int height,
                         std::vector<GlyphInstance>& out) {
    out.clear();
    for (const TextGeom& t : frame.texts) {
        const int dot = std::max(t.dot, 1);
        const int count = static_cast<int>(t.text.size());
        const int text_width = (count * kGlyphAdvance - 1) * dot;
        const int text_height = kGlyphRows * dot;
        const bool left = t.corner == Corner::top_left || t.corner == Corner::bottom_left;
        const bool top = t.corner == Corner::top_left || t.corner == Corner::top_right;
        // Whole pixels from the image's left and top edges, so every dot covers whole pixels.
        const int column = left ? kMarginDots * dot : width - kMarginDots * dot - text_width;
        const int row = top ? kMarginDots * dot : height - kMarginDots * dot - text_height;
        const int shadow_offset = std::max(1, dot / 2);
        for (const bool shadow : {true, false}) {
            const int offset = shadow ? shadow_offset : 0;
            for (int i = 0; i < count; ++i) {
                const std::uint64_t bits = glyph_bits(t.text[static_cast<std::size_t>(i)]);
                if (bits == 0) continue;
                const int x = column + i * kGlyphAdvance * dot + offset;
                const int y = row + offset;
                GlyphInstance g{
                    .origin = {static_cast<float>(x) - static_cast<float>(width) / 2,
                               static_cast<float>(height) / 2 - static_cast<float>(y)},
                    .dot = static_cast<float>(dot),
                    .bits = {static_cast<std::uint32_t>(bits & kFirstFourRows),
                             static_cast<std::uint32_t>(bits >> kFirstFourRowsBits)},
                    .color = {t.color.r, t.color.g, t.color.b, t.color.a},
                };
                if (shadow) std::copy(std::begin(kShadowColor), std::end(kShadowColor), g.color);
                out.push_back(g);
            }
        }
    }
}

}  // namespace discreel::render

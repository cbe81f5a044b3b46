#pragma once
// RGBA frames to 8-bit palette indices for GIF, with one palette for the whole clip, fixed
// when the first frame arrives, so memory stays flat and every frame maps the same colour to
// the same index (no flicker, no dithering noise). The palette holds, in this order:
//   1. the key colours (the scene's background, walls and discs), so flat areas are exact;
//   2. the first frame's other colours, most frequent first (ties by colour value), which adds
//      the anti-aliased edge blends; all of them when the frame has 256 colours or fewer.
//      When there are more, the most frequent fill 131 entries and a 5x5x5 colour cube takes
//      the other 125, so that no colour is more than about 55 units (RGB distance) from an
//      entry, whatever later frames bring.
// Any colour is drawn with its nearest palette entry (squared RGB distance, ties to the
// lower index); a 2^24-entry table remembers each answer. Why not a palette per frame or an
// optimised one: per-frame palettes flicker and need the frame twice; a palette optimised over
// the whole clip needs the whole clip first, which would break "memory stays flat".
#include <cstdint>
#include <vector>

#include "discreel/encode.hpp"
#include "frame_converter.hpp"

namespace discreel::encode {

class PaletteConverter final : public FrameConverter {
public:
    explicit PaletteConverter(std::vector<Rgb> key_colours);
    void convert(const ImageView& frame, AVFrame& output) override;

private:
    void build_palette(const ImageView& first_frame);
    std::uint8_t index_of(std::uint32_t rgb);

    std::vector<Rgb> key_colours_;
    std::vector<Rgb> palette_;             // 1..256 entries once the first frame is seen
    std::vector<std::uint16_t> lookup_;    // by 0xRRGGBB: palette index + 1; 0: not yet known
};

}  // namespace discreel::encode

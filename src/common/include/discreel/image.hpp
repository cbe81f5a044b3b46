#pragma once
// RGBA8 pixels, top row first, rows packed (stride = 4 * width). This is the frame format that
// flows from render to encode and that golden images are compared in.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace discreel {

struct ImageView {
    int width = 0;                         // pixels
    int height = 0;                        // pixels
    std::span<const std::uint8_t> rgba;    // 4 * width * height bytes, top row first
};

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;        // 4 * width * height bytes, top row first

    ImageView view() const { return {width, height, rgba}; }
};

}  // namespace discreel

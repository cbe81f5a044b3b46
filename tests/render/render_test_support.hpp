#pragma once
// Shared helpers for the render tests: reading pixels of a frame and placing world points.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "discreel/image.hpp"
#include "discreel/render.hpp"

namespace discreel::render::test {

using Pixel = std::array<std::uint8_t, 4>;

inline Pixel pixel_at(const ImageView& image, int column, int row) {
    const std::size_t i = 4 * (static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) +
                               static_cast<std::size_t>(column));
    return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2], image.rgba[i + 3]};
}

// The pixel whose area contains world point (x, y), following the contract in render.hpp:
// `camera.height` metres span the image height, y up, camera centre at the image centre.
inline Pixel pixel_at_world(const ImageView& image, const Camera& camera, double x, double y) {
    const double scale = image.height / camera.height;
    const double column = image.width / 2.0 + (x - camera.center_x) * scale;
    const double row = image.height / 2.0 - (y - camera.center_y) * scale;
    return pixel_at(image, static_cast<int>(std::floor(column)), static_cast<int>(std::floor(row)));
}

// How an sRGB channel in 0..1 lands in an 8-bit framebuffer.
inline std::uint8_t to_byte(float channel) {
    return static_cast<std::uint8_t>(std::lround(channel * 255.0f));
}

inline Pixel opaque(const Rgba& color) {
    return {to_byte(color.r), to_byte(color.g), to_byte(color.b), 255};
}

}  // namespace discreel::render::test

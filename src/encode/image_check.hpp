#pragma once
// The shape checks every entry point applies to an incoming RGBA frame.
#include <optional>
#include <string>

#include "discreel/image.hpp"

namespace discreel::encode {

// Why the view cannot be an RGBA8 image, or nothing when it is well formed.
inline std::optional<std::string> image_problem(const ImageView& image) {
    if (image.width <= 0 || image.height <= 0) {
        return "image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
               " is empty";
    }
    const auto expected_bytes = std::size_t{4} * static_cast<std::size_t>(image.width) *
                                static_cast<std::size_t>(image.height);
    if (image.rgba.size() != expected_bytes) {
        return "a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
               " RGBA image needs " + std::to_string(expected_bytes) + " bytes, got " +
               std::to_string(image.rgba.size());
    }
    return std::nullopt;
}

}  // namespace discreel::encode

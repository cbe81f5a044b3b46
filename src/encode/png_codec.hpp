#pragma once
// PNG bytes <-> RGBA8 images through libavcodec's png encoder and decoder, in memory. Errors
// carry the reason only; callers prefix the path they were reading or writing.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/image.hpp"
#include "discreel/encode.hpp"
#include "discreel/output_file.hpp"

namespace discreel::encode {

// An RGBA PNG (8 bits per channel) holding exactly the given pixels.
Expected<std::vector<std::uint8_t>> encode_png(const ImageView& image);

// A 16-bit grey PNG of exactly these values (instance masks).
Expected<std::vector<std::uint8_t>> encode_png_gray16(const Gray16View& image);
// A 16-bit grey PNG's values, top row first; any other PNG is an error.
Expected<Gray16Image> decode_png_gray16(std::span<const std::uint8_t> png_bytes);

// Any PNG the decoder reads (grey, palette, RGB, 16-bit, with or without alpha), converted to
// RGBA8, top row first.
Expected<Image> decode_png(std::span<const std::uint8_t> png_bytes);

// The PNG of `image` written to a temporary file for `path`, not yet committed or sealed: the
// caller decides when it becomes visible (a still at once, a sequence when all frames are in).
Expected<OutputFile> write_png_to_temporary(const std::string& path, const ImageView& image);

}  // namespace discreel::encode

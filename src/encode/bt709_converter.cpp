#include "bt709_converter.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

extern "C" {
#include <libavutil/frame.h>
}

#include "discreel/clones.hpp"

namespace discreel::encode {
namespace {

// BT.709 (Kr = 0.2126, Kb = 0.0722), limited range: Y' in 16..235 and Cb, Cr in 16..240 from
// full-range R'G'B'. Coefficients are the matrix times 219/255 (luma) or 224/255 (chroma),
// times 2^16, rounded; the green one of each row is whatever makes the row's sum exact, so that
// greys have Cb = Cr = 128 and white has Y' = 235 with no clamping anywhere.
constexpr int fraction_bits = 16;
constexpr std::int32_t luma_r = 11966, luma_g = 40254, luma_b = 4064;
constexpr std::int32_t cb_r = -6596, cb_g = -22188, cb_b = 28784;
constexpr std::int32_t cr_r = 28784, cr_g = -26145, cr_b = -2639;
static_assert(cb_r + cb_g + cb_b == 0 && cr_r + cr_g + cr_b == 0, "greys must stay grey");
static_assert(((luma_r + luma_g + luma_b) * 255 + (16 << fraction_bits) +
               (1 << (fraction_bits - 1))) >> fraction_bits == 235,
              "white must be 235");

// Offsets with rounding to nearest; `extra_bits` for sums of 2^extra_bits pixels.
constexpr std::int32_t offset(int level, int extra_bits) {
    const int shift = fraction_bits + extra_bits;
    return (level << shift) + (1 << (shift - 1));
}

// A pixel's channels, or the sum of several pixels' (wide enough for the products).
struct Rgb32 {
    std::int32_t r, g, b;
};

// The pixel is loaded as one 32-bit word and split with shifts, which the compiler turns into
// a few vector instructions for many pixels at once; byte-wise loads do not vectorise as well.
constexpr int r_shift = std::endian::native == std::endian::little ? 0 : 24;
constexpr int g_shift = std::endian::native == std::endian::little ? 8 : 16;
constexpr int b_shift = std::endian::native == std::endian::little ? 16 : 8;
inline Rgb32 channels(const std::uint8_t* pixel) {
    std::uint32_t word;
    std::memcpy(&word, pixel, sizeof word);
    return {static_cast<std::int32_t>((word >> r_shift) & 0xff),
            static_cast<std::int32_t>((word >> g_shift) & 0xff),
            static_cast<std::int32_t>((word >> b_shift) & 0xff)};
}
inline Rgb32 operator+(const Rgb32& a, const Rgb32& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }

inline std::uint8_t luma(const Rgb32& c) {
    return static_cast<std::uint8_t>(
        (luma_r * c.r + luma_g * c.g + luma_b * c.b + offset(16, 0)) >> fraction_bits);
}

// Cb and Cr of a colour that is the sum of 2^extra_bits pixels.
inline std::uint8_t chroma_b(const Rgb32& c, int extra_bits) {
    return static_cast<std::uint8_t>((cb_r * c.r + cb_g * c.g + cb_b * c.b +
                                      offset(128, extra_bits)) >>
                                     (fraction_bits + extra_bits));
}
inline std::uint8_t chroma_r(const Rgb32& c, int extra_bits) {
    return static_cast<std::uint8_t>((cr_r * c.r + cr_g * c.g + cr_b * c.b +
                                      offset(128, extra_bits)) >>
                                     (fraction_bits + extra_bits));
}

// Integer arithmetic gives the same bytes whichever instructions compute it, so the row
// loops are also compiled for AVX2 and the loader picks that version where the CPU has it
// (SSE2 lacks 32-bit vector multiplies, which the baseline version then does piecewise).
DISCREEL_CLONES
void luma_row(const std::uint8_t* __restrict rgba, std::uint8_t* __restrict y,
              std::ptrdiff_t width) {
    for (std::ptrdiff_t x = 0; x < width; ++x) y[x] = luma(channels(rgba + 4 * x));
}

DISCREEL_CLONES
void full_chroma_row(const std::uint8_t* __restrict rgba, std::uint8_t* __restrict cb,
                     std::uint8_t* __restrict cr, std::ptrdiff_t width) {
    for (std::ptrdiff_t x = 0; x < width; ++x) {
        const Rgb32 c = channels(rgba + 4 * x);
        cb[x] = chroma_b(c, 0);
        cr[x] = chroma_r(c, 0);
    }
}

// One chroma row of yuv420p from two image rows: each sample from the sum of a 2x2 block.
DISCREEL_CLONES
void halved_chroma_row(const std::uint8_t* __restrict top, const std::uint8_t* __restrict bottom,
                       std::uint8_t* __restrict cb, std::uint8_t* __restrict cr,
                       std::ptrdiff_t chroma_width) {
    for (std::ptrdiff_t x = 0; x < chroma_width; ++x) {
        const Rgb32 sum = channels(top + 8 * x) + channels(top + 8 * x + 4) +
                          channels(bottom + 8 * x) + channels(bottom + 8 * x + 4);
        cb[x] = chroma_b(sum, 2);
        cr[x] = chroma_r(sum, 2);
    }
}

}  // namespace

void Bt709Converter::convert(const ImageView& frame, AVFrame& output) {
    const auto row_bytes = static_cast<std::ptrdiff_t>(4) * frame.width;
    const std::uint8_t* rgba = frame.rgba.data();
    auto plane_row = [&](int plane, int row) {
        return output.data[plane] + static_cast<std::ptrdiff_t>(row) * output.linesize[plane];
    };
    for (int row = 0; row < frame.height; ++row) {
        luma_row(rgba + row * row_bytes, plane_row(0, row), frame.width);
    }
    if (!subsampled_chroma_) {
        for (int row = 0; row < frame.height; ++row) {
            full_chroma_row(rgba + row * row_bytes, plane_row(1, row), plane_row(2, row),
                            frame.width);
        }
        return;
    }
    for (int row = 0; row < frame.height / 2; ++row) {
        const std::uint8_t* top = rgba + std::ptrdiff_t{2} * row * row_bytes;
        halved_chroma_row(top, top + row_bytes, plane_row(1, row), plane_row(2, row),
                          frame.width / 2);
    }
}

}  // namespace discreel::encode

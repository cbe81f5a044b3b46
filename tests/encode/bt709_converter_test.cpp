// Bt709Converter against the BT.709 formula, against libswscale (an independent
// implementation of the same conversion), and against a pinned hash that holds on every CPU.
#include "bt709_converter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "rgba_converter.hpp"

extern "C" {
#include <libavutil/frame.h>
#include <libavutil/pixdesc.h>
}

namespace discreel::encode {
namespace {

struct FrameDeleter {
    void operator()(AVFrame* f) const { av_frame_free(&f); }
};
using Frame = std::unique_ptr<AVFrame, FrameDeleter>;

Frame allocate(int width, int height, AVPixelFormat format) {
    Frame frame(av_frame_alloc());
    frame->format = format;
    frame->width = width;
    frame->height = height;
    EXPECT_EQ(av_frame_get_buffer(frame.get(), 0), 0);
    return frame;
}

std::vector<std::uint8_t> noise(int width, int height, std::uint32_t seed) {
    std::vector<std::uint8_t> rgba(std::size_t{4} * width * height);
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        seed = seed * 1103515245u + 12345u;
        rgba[i] = i % 4 == 3 ? 255 : static_cast<std::uint8_t>(seed >> 16);
    }
    return rgba;
}

int sample(const AVFrame& frame, int plane, int x, int y) {
    return frame.data[plane][y * frame.linesize[plane] + x];
}

// Y'CbCr of one colour from the BT.709 definition, limited range, in doubles.
struct Ycc {
    double y, cb, cr;
};
Ycc bt709(double r, double g, double b) {
    const double kr = 0.2126, kb = 0.0722, kg = 1.0 - kr - kb;
    const double y = (kr * r + kg * g + kb * b) / 255.0;
    return {16.0 + 219.0 * y, 128.0 + 224.0 * (b / 255.0 - y) / (2.0 * (1.0 - kb)),
            128.0 + 224.0 * (r / 255.0 - y) / (2.0 * (1.0 - kr))};
}

TEST(Bt709ConverterTest, PrimariesWhiteAndBlackHaveTheirNominalValues) {
    // 2x2 blocks of one colour, so yuv420p's averaging changes nothing.
    const std::uint8_t colours[][3] = {{255, 255, 255}, {0, 0, 0},     {255, 0, 0}, {0, 255, 0},
                                       {0, 0, 255},     {128, 128, 128}, {255, 255, 0}};
    for (const bool subsampled : {true, false}) {
        for (const auto& c : colours) {
            std::vector<std::uint8_t> rgba;
            for (int i = 0; i < 4; ++i) rgba.insert(rgba.end(), {c[0], c[1], c[2], 255});
            Frame out = allocate(2, 2, subsampled ? AV_PIX_FMT_YUV420P : AV_PIX_FMT_YUV444P);
            Bt709Converter(subsampled).convert({2, 2, rgba}, *out);
            const Ycc expected = bt709(c[0], c[1], c[2]);
            SCOPED_TRACE(testing::Message() << int(c[0]) << "," << int(c[1]) << "," << int(c[2]));
            // Rounded to the nearest level: the fixed-point coefficients are within 2^-17 of
            // the matrix, far from moving any of these colours to another level.
            EXPECT_EQ(sample(*out, 0, 1, 1), std::lround(expected.y));
            EXPECT_EQ(sample(*out, 1, 0, 0), std::lround(expected.cb));
            EXPECT_EQ(sample(*out, 2, 0, 0), std::lround(expected.cr));
        }
    }
}

TEST(Bt709ConverterTest, Yuv420ChromaIsTheAverageOfEach2x2Block) {
    // Red, green, blue and white in one block, and a second block of black and greys.
    const std::vector<std::uint8_t> rgba = {
        255, 0,   0,   255, 0,  255, 0,  255, 0,   0,   0,   255, 60,  60,  60,  255,
        0,   0,   255, 255, 255, 255, 255, 255, 200, 200, 200, 255, 100, 100, 100, 255};
    Frame out = allocate(4, 2, AV_PIX_FMT_YUV420P);
    Bt709Converter(true).convert({4, 2, rgba}, *out);
    const Ycc mixed = bt709(510.0 / 4, 510.0 / 4, 510.0 / 4);
    EXPECT_EQ(sample(*out, 1, 0, 0), std::lround(mixed.cb));   // 128: the block averages to grey
    EXPECT_EQ(sample(*out, 2, 0, 0), std::lround(mixed.cr));
    EXPECT_EQ(sample(*out, 1, 1, 0), 128);
    EXPECT_EQ(sample(*out, 2, 1, 0), 128);
    EXPECT_EQ(sample(*out, 0, 3, 1), std::lround(bt709(100, 100, 100).y));
}

TEST(Bt709ConverterTest, AgreesWithLibswscale) {
    const int width = 64, height = 48;
    const std::vector<std::uint8_t> rgba = noise(width, height, 1);
    for (const AVPixelFormat format : {AV_PIX_FMT_YUV420P, AV_PIX_FMT_YUV444P}) {
        Frame ours = allocate(width, height, format);
        Frame theirs = allocate(width, height, format);
        Bt709Converter(format == AV_PIX_FMT_YUV420P).convert({width, height, rgba}, *ours);
        auto reference =
            RgbaConverter::create(width, height, format, AVCOL_SPC_BT709, AVCOL_RANGE_MPEG);
        ASSERT_TRUE(reference);
        reference->convert({width, height, rgba}, *theirs);
        // Luma, and chroma at full resolution, round the same matrix at a different precision
        // (libswscale: 15-bit intermediates): one level apart at most. yuv420p chroma is not
        // compared: libswscale's "bilinear" downsampling is a 4x4 tent, ours a 2x2 box, so on
        // noise they differ by tens of levels by design.
        const int planes = format == AV_PIX_FMT_YUV444P ? 3 : 1;
        int worst = 0;
        for (int p = 0; p < planes; ++p) {
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    worst = std::max(worst,
                                     std::abs(sample(*ours, p, x, y) - sample(*theirs, p, x, y)));
                }
            }
        }
        EXPECT_LE(worst, 1) << av_get_pix_fmt_name(format);
    }
}

// The rows are compiled for AVX2 and for plain x86-64 and picked at run time; integer
// arithmetic must give the same bytes either way, and on any other CPU. This hash was taken
// with -O0, -O2, -O3 and -O3 -mavx2 builds, which all agreed.
TEST(Bt709ConverterTest, SameBytesOnEveryCpu) {
    const int width = 1282, height = 722;   // not a multiple of any vector width
    const std::vector<std::uint8_t> rgba = noise(width, height, 7);
    const std::uint64_t expected[] = {0xbf70e8db39a62407ull, 0xfa702163d7af829dull};
    for (const bool subsampled : {false, true}) {
        Frame out = allocate(width, height, subsampled ? AV_PIX_FMT_YUV420P : AV_PIX_FMT_YUV444P);
        Bt709Converter(subsampled).convert({width, height, rgba}, *out);
        std::uint64_t hash = 1469598103934665603ull;   // FNV-1a over the visible samples
        for (int p = 0; p < 3; ++p) {
            const int plane_width = p > 0 && subsampled ? width / 2 : width;
            const int plane_height = p > 0 && subsampled ? height / 2 : height;
            for (int y = 0; y < plane_height; ++y) {
                for (int x = 0; x < plane_width; ++x) {
                    hash ^= static_cast<std::uint64_t>(sample(*out, p, x, y));
                    hash *= 1099511628211ull;
                }
            }
        }
        EXPECT_EQ(hash, expected[subsampled ? 1 : 0]) << (subsampled ? "yuv420p" : "yuv444p");
    }
}

}  // namespace
}  // namespace discreel::encode

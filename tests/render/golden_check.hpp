#pragma once
// Golden-image comparison for the render tests (and the frame-scene goldens in tests/app):
// draw, then compare with tests/golden/render/<name>.png.
//
// Regenerating: run with DISCREEL_UPDATE_GOLDENS=1 to write tests/golden/render/<name>.png
// (and <name>.txt, the GL renderer it was made with) instead of comparing; look at the
// image before committing it. On a mismatch the actual frame and an amplified difference are
// written to <build dir>/render-golden-mismatch/ for a human to inspect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "discreel/encode.hpp"
#include "discreel/render.hpp"

namespace discreel::render::test {

namespace fs = std::filesystem;

// llvmpipe is bit-identical across runs and thread counts, so on the machine that made the
// golden the frames match exactly. The tolerance only absorbs Mesa/LLVM version differences in
// anti-aliased edges: a pixel "differs" when any channel is off by more than 2, and at most
// 0.1% of the pixels (57 of 320x180) may differ. A misplaced disc, a turned spoke or a colour
// change touches hundreds of pixels.
inline constexpr int kChannelTolerance = 2;
inline constexpr double kMaxDifferingFraction = 0.001;

struct Comparison {
    int differing_pixels = 0;
    int max_channel_difference = 0;
    Image difference;   // |actual - golden| x 16, opaque, for looking at
};

inline Comparison compare(const ImageView& actual, const ImageView& golden) {
    Comparison result;
    result.difference = {actual.width, actual.height,
                         std::vector<std::uint8_t>(actual.rgba.size(), 255)};
    for (std::size_t pixel = 0; pixel < actual.rgba.size(); pixel += 4) {
        int worst = 0;
        for (std::size_t c = 0; c < 4; ++c) {
            const int d = std::abs(int{actual.rgba[pixel + c]} - int{golden.rgba[pixel + c]});
            worst = std::max(worst, d);
            if (c < 3) result.difference.rgba[pixel + c] = static_cast<std::uint8_t>(std::min(255, d * 16));
        }
        result.max_channel_difference = std::max(result.max_channel_difference, worst);
        if (worst > kChannelTolerance) ++result.differing_pixels;
    }
    return result;
}

inline std::string read_text(const fs::path& path) {
    std::ifstream file(path);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// `allowed_pixels` overrides the default allowance (kMaxDifferingFraction of the frame) where a
// feature is too small for it to catch a regression.
inline void check_golden(const std::string& name, const FrameScene& frame, int width, int height,
                         int allowed_pixels = -1) {
    auto renderer = Renderer::create({.width = width, .height = height});
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    auto actual = renderer->draw(frame);
    ASSERT_TRUE(actual.ok()) << actual.error().message;

    const fs::path golden_dir = fs::path(DISCREEL_SOURCE_DIR) / "tests/golden/render";
    const fs::path golden_png = golden_dir / (name + ".png");
    const fs::path golden_info = golden_dir / (name + ".txt");
    const char* update = std::getenv("DISCREEL_UPDATE_GOLDENS");
    if (update != nullptr && std::string(update) == "1") {
        fs::create_directories(golden_dir);
        Status written = encode::write_png(golden_png.string(), *actual);
        ASSERT_TRUE(written.ok()) << written.error().message;
        std::ofstream(golden_info) << renderer->renderer_info() << "\n";
        GTEST_SKIP() << "wrote " << golden_png << "; not compared";
    }

    auto golden = encode::read_png(golden_png.string());
    ASSERT_TRUE(golden.ok()) << golden.error().message
                             << " (DISCREEL_UPDATE_GOLDENS=1 writes the golden)";
    ASSERT_EQ(golden->width, actual->width);
    ASSERT_EQ(golden->height, actual->height);

    const Comparison result = compare(*actual, golden->view());
    const int allowed = allowed_pixels >= 0
                            ? allowed_pixels
                            : static_cast<int>(kMaxDifferingFraction * width * height);
    if (result.differing_pixels > allowed) {
        const fs::path out_dir = fs::path(DISCREEL_BINARY_DIR) / "render-golden-mismatch";
        fs::create_directories(out_dir);
        const fs::path actual_png = out_dir / (name + ".actual.png");
        const fs::path difference_png = out_dir / (name + ".difference.png");
        (void)encode::write_png(actual_png.string(), *actual);
        (void)encode::write_png(difference_png.string(), result.difference.view());
        ADD_FAILURE() << result.differing_pixels << " pixels differ by more than "
                      << kChannelTolerance << " (allowed: " << allowed << "), largest channel "
                      << "difference " << result.max_channel_difference << ".\n"
                      << "golden made with: " << read_text(golden_info)
                      << "this renderer:    " << renderer->renderer_info() << "\n"
                      << "actual: " << actual_png << "\ndifference x16: " << difference_png;
    }
}

}  // namespace discreel::render::test

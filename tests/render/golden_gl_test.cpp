// Golden-image test: a small frame with every kind of geometry, compared with a committed PNG.
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
#include <sstream>
#include <string>

#include "discreel/encode.hpp"
#include "discreel/render.hpp"

namespace discreel::render {
namespace {

namespace fs = std::filesystem;

// llvmpipe is bit-identical across runs and thread counts, so on the machine that made the
// golden the frames match exactly. The tolerance only absorbs Mesa/LLVM version differences in
// anti-aliased edges: a pixel "differs" when any channel is off by more than 2, and at most
// 0.1% of the pixels (57 of 320x180) may differ. A misplaced disc, a turned spoke or a colour
// change touches hundreds of pixels.
constexpr int kChannelTolerance = 2;
constexpr double kMaxDifferingFraction = 0.001;

struct Comparison {
    int differing_pixels = 0;
    int max_channel_difference = 0;
    Image difference;   // |actual - golden| x 16, opaque, for looking at
};

Comparison compare(const ImageView& actual, const ImageView& golden) {
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

std::string read_text(const fs::path& path) {
    std::ifstream file(path);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// 320x180, 20 pixels per metre: a box of capsule walls, a slanted wall, moving discs of
// several sizes, colours and angles (one translucent, two near the one-pixel floor), and pegs.
FrameScene golden_scene() {
    FrameScene f;
    f.background = {0.11f, 0.12f, 0.15f, 1};
    f.camera = {.center_x = 0, .center_y = 0, .height = 9};
    const Rgba wall{0.55f, 0.58f, 0.64f, 1};
    const float w = 7.8f, h = 4.3f, t = 0.1f;
    f.capsules = {
        {.ax = -w, .ay = -h, .bx = w, .by = -h, .radius = t, .color = wall},
        {.ax = -w, .ay = h, .bx = w, .by = h, .radius = t, .color = wall},
        {.ax = -w, .ay = -h, .bx = -w, .by = h, .radius = t, .color = wall},
        {.ax = w, .ay = -h, .bx = w, .by = h, .radius = t, .color = wall},
        {.ax = -5, .ay = 1.5f, .bx = -2, .by = 0.5f, .radius = 0.2f, .color = {0.8f, 0.6f, 0.3f, 1}},
    };
    auto moving = [](float x, float y, float r, float angle, Rgba fill) {
        return DiscGeom{.x = x, .y = y, .radius = r, .angle = angle, .fill = fill};
    };
    auto peg = [](float x, float y, float r, Rgba fill) {
        return DiscGeom{.x = x, .y = y, .radius = r, .fill = fill, .is_static = true};
    };
    f.discs = {
        moving(-5, -2, 1.6f, 0.5f, {0.90f, 0.30f, 0.25f, 1}),
        moving(-1.5f, -2.5f, 1.1f, 2.0f, {0.25f, 0.60f, 0.95f, 1}),
        moving(1.8f, 2, 1.3f, -1.0f, {0.95f, 0.85f, 0.30f, 1}),
        moving(4.8f, -1.5f, 0.7f, 3.5f, {0.35f, 0.80f, 0.45f, 1}),
        moving(3.2f, 0.8f, 0.4f, 0.0f, {0.80f, 0.40f, 0.85f, 1}),
        moving(6.0f, 2.8f, 0.1f, 0.0f, {0.95f, 0.95f, 0.95f, 1}),
        moving(6.6f, 2.8f, 0.02f, 0.0f, {0.95f, 0.95f, 0.95f, 1}),
        peg(-1, 1.8f, 0.5f, {0.60f, 0.62f, 0.68f, 1}),
        peg(0.0f, 0.6f, 0.7f, {0.85f, 0.50f, 0.20f, 1}),
        moving(-0.8f, -1.8f, 0.8f, 1.0f, {0.95f, 0.95f, 0.95f, 0.6f}),
    };
    return f;
}

void check_golden(const std::string& name, const FrameScene& frame, int width, int height) {
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
    const int allowed = static_cast<int>(kMaxDifferingFraction * width * height);
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

TEST(RenderGoldenGLTest, MixedScene) {
    check_golden("mixed_scene", golden_scene(), 320, 180);
}

}  // namespace
}  // namespace discreel::render

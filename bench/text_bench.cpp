// text_bench: what text costs a frame. 20 lines of overlay text (a title, readout lines whose
// digits change every frame, labels) at 1920x1080 on an empty frame, against the same frame
// without text; milliseconds per frame of Renderer::draw (draw, readback and the text, thread
// CPU time), appended to bench/results/text_bench.csv (bench_results.hpp). The budget is 1 ms
// for the 20 lines (issue 41). See docs/performance.md.
#include <time.h>

#include <cstdio>
#include <string>

#include "bench_results.hpp"
#include "discreel/render.hpp"

namespace {

using namespace discreel;

constexpr int frames = 200;
constexpr int lines = 20;

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

render::FrameScene scene_of(int frame, bool text) {
    render::FrameScene scene;
    scene.background = {0.06f, 0.09f, 0.12f, 1};
    scene.camera = {.center_x = 0, .center_y = 0, .height = 9};
    if (!text) return scene;
    scene.labels.push_back({.text = "Momentum is conserved in every collision", .world = false,
                            .x = 0.5, .y = 0.04, .size = 0.06, .anchor = render::Anchor::top,
                            .color = {1, 1, 1, 1}, .outline = {}});
    for (int k = 1; k < lines; ++k) {
        // Readouts: digits that change every frame, as {t} and {energy} do.
        const std::string line = "t = " + std::to_string(frame / 60.0).substr(0, 5) +
                                 " s   E = " + std::to_string(1000.0 - frame * 0.37 - k) +
                                 " J   v = " + std::to_string(k * 0.31 + frame * 0.01) + " m/s";
        scene.labels.push_back({.text = line, .world = false, .x = 0.03, .y = 0.1 + 0.042 * k,
                                .size = 0.03, .anchor = render::Anchor::left,
                                .color = {0.95f, 0.65f, 0.07f, 1}, .outline = {}});
    }
    return scene;
}

}  // namespace

int main() {
    // Drawing on this thread, as `discreel render` does, so thread CPU time is all of it.
    render::set_rasterizer_threads(0);
    auto renderer = render::Renderer::create({.width = 1920, .height = 1080});
    if (!renderer) {
        std::fprintf(stderr, "%s\n", renderer.error().message.c_str());
        return 1;
    }
    bench::ResultsFile results("text_bench", {"lines", "width", "height", "frames",
                                              "ms_per_frame_without", "ms_per_frame_with",
                                              "ms_per_frame_for_text"});
    double ms[2] = {};
    for (const bool text : {false, true}) {
        if (auto warm = renderer->draw(scene_of(0, text)); !warm) {   // shaders, font, glyphs
            std::fprintf(stderr, "%s\n", warm.error().message.c_str());
            return 1;
        }
        const double start = thread_seconds();
        for (int frame = 0; frame < frames; ++frame) {
            if (!renderer->draw(scene_of(frame, text))) return 1;
        }
        ms[text ? 1 : 0] = 1000.0 * (thread_seconds() - start) / frames;
    }
    std::printf("1920x1080, %d frames, thread CPU time: %.3f ms a frame without text, %.3f with "
                "%d lines: %.3f ms for the text\n",
                frames, ms[0], ms[1], lines, ms[1] - ms[0]);
    results.append({std::to_string(lines), "1920", "1080", std::to_string(frames),
                    bench::csv_number(ms[0], 3), bench::csv_number(ms[1], 3),
                    bench::csv_number(ms[1] - ms[0], 3)});
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

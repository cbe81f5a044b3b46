// shapes_render_bench: what drawing a body of another shape costs next to a disc. 1 000 discs,
// 1 000 boxes, 1 000 hexagons and 1 000 capsules of about the same size, each set on its own at
// 1280x720 on a 16:9 grid that shifts and turns a little every frame; milliseconds per frame of
// Renderer::draw (draw and readback, thread CPU time, llvmpipe on the same thread as in
// `discreel render`), appended to bench/results/shapes_render_bench.csv (bench_results.hpp).
// See docs/performance.md.
#include <time.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "bench_results.hpp"
#include "discreel/render.hpp"

namespace {

using namespace discreel;

constexpr int frames = 200;
constexpr int count = 1000;
constexpr float size = 0.08f;   // metres: the discs' radius, the shapes' circumradius

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

void place(int i, int frame, float& x, float& y) {
    x = -8.0f + 16.0f * static_cast<float>(i % 40) / 40.0f + 0.01f * static_cast<float>(frame);
    y = -4.5f + 9.0f * static_cast<float>(i / 40) / 25.0f;
}

render::PolygonGeom regular(int sides, float rounding) {
    render::PolygonGeom p;
    p.count = sides;
    p.rounding = rounding;
    for (int k = 0; k < sides; ++k) {
        const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k) /
                        static_cast<float>(sides) + std::numbers::pi_v<float> / 4;
        p.vertices[2 * k] = (size - rounding) * std::cos(a);
        p.vertices[2 * k + 1] = (size - rounding) * std::sin(a);
    }
    p.fill = {0.2f, 0.5f, 0.9f, 1};
    return p;
}

render::FrameScene scene_of(const std::string& shape, int frame) {
    render::FrameScene scene;
    scene.camera = {.center_x = 0, .center_y = 0, .height = 9};
    for (int i = 0; i < count; ++i) {
        float x = 0, y = 0;
        place(i, frame, x, y);
        const float angle = 0.1f * static_cast<float>(frame + i);
        if (shape == "disc") {
            scene.discs.push_back({.x = x, .y = y, .radius = size, .angle = angle,
                                   .fill = {0.9f, 0.4f, 0.2f, 1}, .is_static = false});
            continue;
        }
        render::PolygonGeom p = shape == "box"       ? regular(4, 0)
                                : shape == "hexagon" ? regular(6, 0.01f)
                                                     : regular(2, 0.035f);   // capsule
        p.x = x;
        p.y = y;
        p.angle = angle;
        scene.polygons.push_back(p);
    }
    return scene;
}

}  // namespace

int main() {
    // Drawing on this thread, as `discreel render` does, so thread CPU time is all of it.
    render::set_rasterizer_threads(0);
    auto renderer = render::Renderer::create({.width = 1280, .height = 720});
    if (!renderer) {
        std::fprintf(stderr, "%s\n", renderer.error().message.c_str());
        return 1;
    }
    bench::ResultsFile results("shapes_render_bench",
                               {"shape", "count", "width", "height", "frames", "ms_per_frame"});
    std::printf("ms per frame, %d of each at 1280x720, %d frames, thread CPU time\n", count,
                frames);
    for (const std::string shape : {"disc", "box", "hexagon", "capsule"}) {
        (void)renderer->draw(scene_of(shape, 0));   // warm up: shader JIT, buffers
        const double start = thread_seconds();
        for (int frame = 0; frame < frames; ++frame) {
            if (!renderer->draw(scene_of(shape, frame))) return 1;
        }
        const double ms = 1000.0 * (thread_seconds() - start) / frames;
        std::printf("%-8s %.3f\n", shape.c_str(), ms);
        results.append({shape, std::to_string(count), "1280", "720", std::to_string(frames),
                        bench::csv_number(ms, 3)});
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

// readback_bench: is a pixel-pack-buffer readback worth having on llvmpipe? For 1280x720 and
// 1920x1080 frames of 1 000 discs drawn by the Renderer, times per frame, after the draw
// (whose own readback finishes the frame's rendering):
//   direct  glReadPixels into client memory, as Renderer::draw_into does (the pipeline's slot)
//   PBO     glReadPixels into a persistently mapped pixel-pack buffer (GL 4.4 buffer storage,
//           coherent), then a fence and a wait: the pixels are in the mapped memory, where an
//           encoder could read them
// and checks that both give the draw's bytes. Plain program; prints milliseconds per frame
// (thread CPU time; the readback runs on one thread) and appends them to
// bench/results/readback_bench.csv (bench_results.hpp). See docs/performance.md.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <time.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "discreel/render.hpp"

namespace {

using namespace discreel;

constexpr int frames = 200;

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

// 1 000 discs on a 16:9 grid, shifted a little every frame.
render::FrameScene discs(int frame) {
    render::FrameScene scene;
    scene.camera = {.center_x = 0, .center_y = 0, .height = 9};
    for (int i = 0; i < 1000; ++i) {
        const float x = -8.0f + 16.0f * static_cast<float>(i % 40) / 40.0f + 0.01f * frame;
        const float y = -4.5f + 9.0f * static_cast<float>(i / 40) / 25.0f;
        scene.discs.push_back({.x = x, .y = y, .radius = 0.08f, .angle = 0.1f * frame,
                               .fill = {0.9f, 0.4f, 0.2f, 1}});
    }
    return scene;
}

void measure(int width, int height, bench::ResultsFile& results) {
    render::set_rasterizer_threads(0);
    auto renderer = render::Renderer::create({.width = width, .height = height});
    if (!renderer) {
        std::fprintf(stderr, "%s\n", renderer.error().message.c_str());
        std::exit(1);
    }
    const auto bytes = std::size_t{4} * static_cast<std::size_t>(width) *
                       static_cast<std::size_t>(height);
    std::vector<std::uint8_t> drawn(bytes);
    std::vector<std::uint8_t> direct(bytes);
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
    const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glBufferStorage(GL_PIXEL_PACK_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, flags);
    const void* mapped =
        glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(bytes), flags);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (mapped == nullptr || glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "no persistently mapped pixel-pack buffer\n");
        std::exit(1);
    }
    double direct_seconds = 0;
    double pbo_seconds = 0;
    int mismatches = 0;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int frame = 0; frame < frames; ++frame) {
        if (!renderer->draw_into(discs(frame), drawn)) std::exit(1);
        double start = thread_seconds();
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, direct.data());
        direct_seconds += thread_seconds() - start;

        start = thread_seconds();
        glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, GL_TIMEOUT_IGNORED);
        glDeleteSync(fence);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        pbo_seconds += thread_seconds() - start;

        mismatches += std::memcmp(direct.data(), drawn.data(), bytes) != 0 ||
                      std::memcmp(mapped, drawn.data(), bytes) != 0;
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    glDeleteBuffers(1, &buffer);
    std::printf("%dx%d  direct %6.3f  PBO %6.3f  (frames whose bytes differ: %d)\n", width,
                height, 1000.0 * direct_seconds / frames, 1000.0 * pbo_seconds / frames,
                mismatches);
    results.append({std::to_string(width), std::to_string(height), std::to_string(frames),
                    bench::csv_number(1000.0 * direct_seconds / frames, 3),
                    bench::csv_number(1000.0 * pbo_seconds / frames, 3),
                    std::to_string(mismatches)});
}

}  // namespace

int main() {
    std::printf("ms per frame of readback, %d frames, thread CPU time\n", frames);
    bench::ResultsFile results("readback_bench",
                               {"width", "height", "frames", "direct_ms_per_frame",
                                "pbo_ms_per_frame", "frames_differing"});
    measure(1280, 720, results);
    measure(1920, 1080, results);
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}

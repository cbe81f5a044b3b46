// yuv_conversion_bench: where should RGBA -> yuv420p happen on llvmpipe? Times, per 1280x720
// frame already in a GL render target:
//   A  glReadPixels RGBA, then libswscale (the flags VideoSink uses: bilinear, accurate
//      rounding, bit-exact) on the CPU
//   B  two GL passes (BT.709 limited range: Y at full size, U and V from 2x2 averages at half
//      size) and glReadPixels of the 1.5 bytes per pixel
//   C  glReadPixels RGBA, then discreel's own integer converter (Bt709Converter, what the
//      sinks use for yuv420p and yuv444p)
// Plain program; prints wall milliseconds per frame and appends them to
// bench/results/yuv_conversion_bench.csv (bench_results.hpp). See docs/performance.md.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>

extern "C" {
#include <libavutil/frame.h>
#include <libswscale/swscale.h>
}

#include "bench_results.hpp"
#include "bt709_converter.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr int width = 1280;
constexpr int height = 720;
constexpr int frames = 200;

using Clock = std::chrono::steady_clock;

const char* const fullscreen_vert = R"(#version 330 core
void main() {
    vec2 corner = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1);
    gl_Position = vec4(corner, 0.0, 1.0);
})";

const char* const luma_frag = R"(#version 330 core
uniform sampler2D rgba;
out float luma;
void main() {
    vec3 c = texelFetch(rgba, ivec2(gl_FragCoord.xy), 0).rgb;
    luma = (16.0 + 219.0 * dot(c, vec3(0.2126, 0.7152, 0.0722))) / 255.0;
})";

const char* const chroma_frag = R"(#version 330 core
uniform sampler2D rgba;
out vec2 chroma;
void main() {
    ivec2 p = 2 * ivec2(gl_FragCoord.xy);
    vec3 c = 0.25 * (texelFetch(rgba, p, 0).rgb + texelFetch(rgba, p + ivec2(1, 0), 0).rgb +
                     texelFetch(rgba, p + ivec2(0, 1), 0).rgb + texelFetch(rgba, p + ivec2(1, 1), 0).rgb);
    float y = dot(c, vec3(0.2126, 0.7152, 0.0722));
    chroma = (128.0 + 224.0 * vec2((c.b - y) / 1.8556, (c.r - y) / 1.5748)) / 255.0;
})";

void check(bool ok, const char* what) {
    if (!ok) {
        std::fprintf(stderr, "failed: %s\n", what);
        std::exit(1);
    }
}

GLuint program(const char* frag_source) {
    const auto compile = [](GLenum type, const char* source) {
        const GLuint shader = glCreateShader(type);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        GLint ok = 0;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        check(ok != 0, "compiling a shader");
        return shader;
    };
    const GLuint p = glCreateProgram();
    glAttachShader(p, compile(GL_VERTEX_SHADER, fullscreen_vert));
    glAttachShader(p, compile(GL_FRAGMENT_SHADER, frag_source));
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    check(ok != 0, "linking a program");
    return p;
}

GLuint target(GLenum format, int w, int h, GLuint& texture) {
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    check(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "framebuffer");
    return fbo;
}

double ms_per_frame(Clock::time_point start) {
    return 1000.0 * std::chrono::duration<double>(Clock::now() - start).count() / frames;
}

}  // namespace

int main() {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                           OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
    std::vector<std::uint8_t> dummy(4);
    check(context != nullptr && OSMesaMakeCurrent(context, dummy.data(), GL_UNSIGNED_BYTE, 1, 1),
          "OSMesa context");

    // The rendered frame: an RGBA8 target holding something that is not flat.
    std::vector<std::uint8_t> rgba(std::size_t{4} * width * height);
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<std::uint8_t>((i * 7) ^ (i >> 11));
    GLuint frame_texture = 0;
    const GLuint frame_fbo = target(GL_RGBA8, width, height, frame_texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);

    // A: read RGBA back, convert with libswscale.
    AVFrame* yuv = av_frame_alloc();
    yuv->format = AV_PIX_FMT_YUV420P;
    yuv->width = width;
    yuv->height = height;
    check(av_frame_get_buffer(yuv, 0) == 0, "AVFrame");
    SwsContext* sws = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height,
                                     AV_PIX_FMT_YUV420P,
                                     SWS_BILINEAR | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr,
                                     nullptr, nullptr);
    sws_setColorspaceDetails(sws, sws_getCoefficients(SWS_CS_DEFAULT), 1,
                             sws_getCoefficients(SWS_CS_ITU709), 0, 0, 1 << 16, 1 << 16);
    std::vector<std::uint8_t> readback(rgba.size());
    double read_ms = 0;
    double sws_ms = 0;
    for (int i = 0; i < frames; ++i) {
        glBindFramebuffer(GL_FRAMEBUFFER, frame_fbo);
        auto start = Clock::now();
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, readback.data());
        read_ms += ms_per_frame(start);
        start = Clock::now();
        const std::uint8_t* planes[1] = {readback.data()};
        const int strides[1] = {4 * width};
        sws_scale(sws, planes, strides, 0, height, yuv->data, yuv->linesize);
        sws_ms += ms_per_frame(start);
    }

    // B: convert in GL, read back the planes.
    GLuint luma_texture = 0, chroma_texture = 0;
    const GLuint luma_fbo = target(GL_R8, width, height, luma_texture);
    const GLuint chroma_fbo = target(GL_RG8, width / 2, height / 2, chroma_texture);
    const GLuint luma_program = program(luma_frag);
    const GLuint chroma_program = program(chroma_frag);
    std::vector<std::uint8_t> luma(std::size_t{1} * width * height);
    std::vector<std::uint8_t> chroma(std::size_t{2} * (width / 2) * (height / 2));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, frame_texture);
    const auto start = Clock::now();
    for (int i = 0; i < frames; ++i) {
        glBindFramebuffer(GL_FRAMEBUFFER, luma_fbo);
        glViewport(0, 0, width, height);
        glUseProgram(luma_program);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glReadPixels(0, 0, width, height, GL_RED, GL_UNSIGNED_BYTE, luma.data());
        glBindFramebuffer(GL_FRAMEBUFFER, chroma_fbo);
        glViewport(0, 0, width / 2, height / 2);
        glUseProgram(chroma_program);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glReadPixels(0, 0, width / 2, height / 2, GL_RG, GL_UNSIGNED_BYTE, chroma.data());
    }
    const double gl_ms = ms_per_frame(start);
    check(glGetError() == GL_NO_ERROR, "GL calls");

    // C: the same readback as A, converted by Bt709Converter.
    discreel::encode::Bt709Converter converter(true);
    double ours_ms = 0;
    for (int i = 0; i < frames; ++i) {
        const auto converting = Clock::now();
        converter.convert({width, height, readback}, *yuv);
        ours_ms += ms_per_frame(converting);
    }

    std::printf("%dx%d, %d frames, ms per frame\n", width, height, frames);
    std::printf("A  glReadPixels RGBA        %6.2f\n", read_ms);
    std::printf("A  libswscale to yuv420p    %6.2f\n", sws_ms);
    std::printf("A  total                    %6.2f\n", read_ms + sws_ms);
    std::printf("B  GL passes + readback     %6.2f\n", gl_ms);
    std::printf("C  Bt709Converter           %6.2f\n", ours_ms);
    std::printf("C  total                    %6.2f\n", read_ms + ours_ms);
    discreel::bench::ResultsFile results(
        "yuv_conversion_bench",
        {"width", "height", "frames", "readback_ms_per_frame", "swscale_ms_per_frame",
         "gl_passes_and_readback_ms_per_frame", "bt709_converter_ms_per_frame"});
    const auto ms = [](double value) { return discreel::bench::csv_number(value, 3); };
    results.append({std::to_string(width), std::to_string(height), std::to_string(frames),
                    ms(read_ms), ms(sws_ms), ms(gl_ms), ms(ours_ms)});
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    sws_freeContext(sws);
    av_frame_free(&yuv);
    OSMesaDestroyContext(context);
    return 0;
}

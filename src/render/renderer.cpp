#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "discreel/render.hpp"
#include "discreel_shaders.hpp"
#include "gl_objects.hpp"
#include "instance_stream.hpp"
#include "instances.hpp"
#include "offscreen_target.hpp"
#include "osmesa_context.hpp"
#include "shader_program.hpp"
#include "text_instances.hpp"
#include "text_raster.hpp"

namespace discreel::render {
namespace {

std::string gl_string(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s != nullptr ? s : "";
}

Status check_gl(const char* during) {
    if (GLenum e = glGetError(); e != GL_NO_ERROR) {
        return Error{"GL error " + std::to_string(e) + " while " + during};
    }
    return {};
}

// Shader positions arrive in pixels from the image centre, y up. Negating y here makes GL's
// row 0 the image's top row, so glReadPixels yields rows top first with no reordering.
void set_pixels_to_ndc(const GlProgram& program, int width, int height) {
    glUseProgram(program.id());
    glUniform2f(glGetUniformLocation(program.id(), "u_pixels_to_ndc"),
                2.0f / static_cast<float>(width), -2.0f / static_cast<float>(height));
}

}  // namespace

struct Renderer::Impl {
    // Declared first so it is destroyed last: every GL object below is deleted while it exists.
    OsmesaContext context;
    int width = 0;
    int height = 0;
    std::string info;
    std::string font_path;
    std::optional<FontRaster> font;   // opened at the first frame with text

    std::optional<OffscreenTarget> target;
    GlProgram disc_program;
    GlProgram capsule_program;
    GlProgram polygon_program;
    GlProgram glyph_program;
    GLint disc_point_sprites = -1;   // uniform locations
    GLint polygon_point_sprites = -1;
    float max_point_size = 0;        // pixels
    std::optional<InstanceStream> disc_stream;
    std::optional<InstanceStream> capsule_stream;
    std::optional<InstanceStream> polygon_stream;
    std::optional<InstanceStream> glyph_stream;

    std::vector<DiscInstance> disc_instances;        // reused from frame to frame
    std::vector<CapsuleInstance> capsule_instances;
    std::vector<CapsuleInstance> trail_instances;
    std::vector<CapsuleInstance> joint_instances;
    std::vector<CapsuleInstance> debug_instances;
    std::vector<CapsuleInstance> arrow_instances;
    std::vector<PolygonInstance> polygon_instances;
    std::vector<GlyphInstance> glyph_instances;
    // The last frame of draw(), top row first; sized on first use, so callers of draw_into()
    // do not pay a frame of memory for it.
    std::vector<std::uint8_t> pixels;

    std::size_t frame_bytes() const {
        return std::size_t{4} * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }

    explicit Impl(OsmesaContext c) : context(std::move(c)) {}
    ~Impl() { (void)context.make_current(); }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    Status init(const RendererDef& def);
    Expected<ImageView> draw(const FrameScene& frame, std::span<std::uint8_t> out);
    template <class Instance>
    void draw_points_or_quads(const GlProgram& program, InstanceStream& stream,
                              const std::vector<Instance>& instances, GLint point_sprites);
};

// As point sprites where they fit, as quads where not, in runs that keep the instances' order
// (the later one is blended over the earlier where their edges meet). Discs and polygons alike.
template <class Instance>
void Renderer::Impl::draw_points_or_quads(const GlProgram& program, InstanceStream& stream,
                                          const std::vector<Instance>& instances,
                                          GLint point_sprites) {
    glUseProgram(program.id());
    stream.upload(instances.data(), instances.size());
    const auto as_point = [&](const Instance& instance) {
        return fits_point_sprite(instance, width, height, max_point_size);
    };
    for (std::size_t first = 0; first < instances.size();) {
        const bool points = as_point(instances[first]);
        std::size_t end = first + 1;
        while (end < instances.size() && as_point(instances[end]) == points) ++end;
        glUniform1i(point_sprites, points ? 1 : 0);
        stream.draw_uploaded(points ? InstanceStream::Shape::point : InstanceStream::Shape::quad,
                             first, end - first);
        first = end;
    }
}

Status Renderer::Impl::init(const RendererDef& def) {
    const std::string size = std::to_string(def.width) + "x" + std::to_string(def.height);
    if (def.width <= 0 || def.height <= 0) {
        return Error{"renderer size must be positive, got " + size};
    }
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (def.width > max_size || def.height > max_size) {
        return Error{"renderer size " + size + " exceeds the GL limit of " +
                     std::to_string(max_size) + " pixels"};
    }
    font_path = def.font;
    width = def.width;
    height = def.height;
    info = gl_string(GL_RENDERER) + ", " + gl_string(GL_VERSION);

    auto created_target = OffscreenTarget::create(width, height);
    if (!created_target) return created_target.error();
    target.emplace(std::move(created_target.value()));

    auto discs = build_program(discreel_shaders::disc_vert, discreel_shaders::disc_frag);
    if (!discs) return Error{"disc shaders: " + discs.error().message};
    disc_program = std::move(discs.value());
    auto capsules = build_program(discreel_shaders::capsule_vert, discreel_shaders::capsule_frag);
    if (!capsules) return Error{"capsule shaders: " + capsules.error().message};
    capsule_program = std::move(capsules.value());
    auto polygons = build_program(discreel_shaders::polygon_vert, discreel_shaders::polygon_frag);
    if (!polygons) return Error{"polygon shaders: " + polygons.error().message};
    polygon_program = std::move(polygons.value());
    auto glyphs = build_program(discreel_shaders::glyph_vert, discreel_shaders::glyph_frag);
    if (!glyphs) return Error{"glyph shaders: " + glyphs.error().message};
    glyph_program = std::move(glyphs.value());
    set_pixels_to_ndc(disc_program, width, height);
    set_pixels_to_ndc(capsule_program, width, height);
    set_pixels_to_ndc(polygon_program, width, height);
    set_pixels_to_ndc(glyph_program, width, height);
    disc_point_sprites = glGetUniformLocation(disc_program.id(), "u_point_sprites");
    polygon_point_sprites = glGetUniformLocation(polygon_program.id(), "u_point_sprites");
    GLfloat point_sizes[2] = {0, 0};
    glGetFloatv(GL_POINT_SIZE_RANGE, point_sizes);
    max_point_size = point_sizes[1];

    disc_stream = InstanceStream::create(
        sizeof(DiscInstance), {{0, 2, GL_FLOAT, offsetof(DiscInstance, center)},
                               {1, 1, GL_FLOAT, offsetof(DiscInstance, radius)},
                               {2, 1, GL_FLOAT, offsetof(DiscInstance, angle)},
                               {3, 4, GL_FLOAT, offsetof(DiscInstance, color)},
                               {4, 1, GL_UNSIGNED_INT, offsetof(DiscInstance, flags)}});
    capsule_stream = InstanceStream::create(
        sizeof(CapsuleInstance), {{0, 2, GL_FLOAT, offsetof(CapsuleInstance, a)},
                                  {1, 2, GL_FLOAT, offsetof(CapsuleInstance, b)},
                                  {2, 1, GL_FLOAT, offsetof(CapsuleInstance, radius)},
                                  {3, 4, GL_FLOAT, offsetof(CapsuleInstance, color)},
                                  {4, 1, GL_UNSIGNED_INT, offsetof(CapsuleInstance, flags)}});
    polygon_stream = InstanceStream::create(
        sizeof(PolygonInstance), {{0, 2, GL_FLOAT, offsetof(PolygonInstance, center)},
                                  {1, 4, GL_FLOAT, offsetof(PolygonInstance, vertices)},
                                  {2, 4, GL_FLOAT, offsetof(PolygonInstance, vertices) + 16},
                                  {3, 4, GL_FLOAT, offsetof(PolygonInstance, vertices) + 32},
                                  {4, 4, GL_FLOAT, offsetof(PolygonInstance, vertices) + 48},
                                  {5, 4, GL_FLOAT, offsetof(PolygonInstance, shape)},
                                  {6, 3, GL_FLOAT, offsetof(PolygonInstance, spoke)},
                                  {7, 4, GL_FLOAT, offsetof(PolygonInstance, color)}});
    glyph_stream = InstanceStream::create(
        sizeof(GlyphInstance), {{0, 2, GL_FLOAT, offsetof(GlyphInstance, origin)},
                                {1, 1, GL_FLOAT, offsetof(GlyphInstance, dot)},
                                {2, 2, GL_UNSIGNED_INT, offsetof(GlyphInstance, bits)},
                                {3, 4, GL_FLOAT, offsetof(GlyphInstance, color)}});

    // The context belongs to this renderer alone, so fixed state is set once.
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_DITHER);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glEnable(GL_BLEND);
    // The framebuffer holds premultiplied colour: the source's colour enters multiplied by its
    // alpha and what is below by one minus it, which is "over" in premultiplied terms. Over an
    // opaque background that is the ordinary blend and alpha stays 1; over a transparent one
    // the frame is made straight again after reading (unpremultiply).
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

    return check_gl("setting up the renderer");
}

// Premultiplied RGBA8 to straight: colour / alpha, rounded; fully transparent pixels are black.
static void unpremultiply(std::span<std::uint8_t> rgba) {
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
        const unsigned a = rgba[i + 3];
        if (a == 255) continue;
        for (std::size_t c = 0; c < 3; ++c) {
            rgba[i + c] = a == 0 ? 0
                                 : static_cast<std::uint8_t>(
                                       std::min(255u, (rgba[i + c] * 255u + a / 2) / a));
        }
    }
}

Expected<ImageView> Renderer::Impl::draw(const FrameScene& frame, std::span<std::uint8_t> out) {
    if (out.size() < frame_bytes()) {
        return Error{"frame buffer holds " + std::to_string(out.size()) + " bytes, " +
                     std::to_string(frame_bytes()) + " needed"};
    }
    const double view_height = frame.camera.height;
    if (!(view_height > 0.0) || !std::isfinite(view_height)) {
        return Error{"camera height must be a positive number of metres"};
    }
    if (Status current = context.make_current(); !current) return current.error();

    const double pixels_per_metre = static_cast<double>(height) / view_height;
    make_capsule_instances(frame, pixels_per_metre, capsule_instances);
    make_line_instances(frame, frame.trails, pixels_per_metre, trail_instances);
    make_line_instances(frame, frame.joints, pixels_per_metre, joint_instances);
    make_line_instances(frame, frame.debug, pixels_per_metre, debug_instances);
    make_polygon_instances(frame, pixels_per_metre, polygon_instances);
    make_disc_instances(frame, pixels_per_metre, disc_instances);
    make_arrow_instances(frame, pixels_per_metre, arrow_instances);
    make_text_instances(frame, width, height, glyph_instances);

    const float alpha = std::clamp(frame.background.a, 0.0f, 1.0f);
    glClearColor(frame.background.r * alpha, frame.background.g * alpha,
                 frame.background.b * alpha, alpha);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(capsule_program.id());
    capsule_stream->draw(capsule_instances.data(), capsule_instances.size());
    capsule_stream->draw(trail_instances.data(), trail_instances.size());
    draw_points_or_quads(polygon_program, *polygon_stream, polygon_instances,
                         polygon_point_sprites);
    draw_points_or_quads(disc_program, *disc_stream, disc_instances, disc_point_sprites);
    glUseProgram(capsule_program.id());
    capsule_stream->draw(joint_instances.data(), joint_instances.size());
    capsule_stream->draw(arrow_instances.data(), arrow_instances.size());
    capsule_stream->draw(debug_instances.data(), debug_instances.size());
    glUseProgram(glyph_program.id());
    glyph_stream->draw(glyph_instances.data(), glyph_instances.size());
    target->read(out);
    if (Status ok = check_gl("drawing a frame"); !ok) return ok.error();
    if (alpha < 1.0f) unpremultiply(out.first(frame_bytes()));
    if (!frame.labels.empty()) {
        if (!font) {
            auto opened = FontRaster::open(font_path);
            if (!opened) return opened.error();
            font.emplace(std::move(opened.value()));
        }
        for (const TextLabel& label : frame.labels) {
            font->draw(label, frame.camera, out.first(frame_bytes()), width, height);
        }
    }
    return ImageView{width, height, out.first(frame_bytes())};
}

Expected<Renderer> Renderer::create(const RendererDef& def) {
    auto context = OsmesaContext::create();
    if (!context) return context.error();
    auto impl = std::make_unique<Impl>(std::move(context.value()));
    if (Status ok = impl->init(def); !ok) return ok.error();
    return Renderer(std::move(impl));
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

Expected<ImageView> Renderer::draw(const FrameScene& frame) {
    impl_->pixels.resize(impl_->frame_bytes());
    return impl_->draw(frame, impl_->pixels);
}

Expected<ImageView> Renderer::draw_into(const FrameScene& frame, std::span<std::uint8_t> out) {
    return impl_->draw(frame, out);
}

std::string Renderer::renderer_info() const { return impl_->info; }

void Renderer::release() { impl_->context.release(); }

RendererDef Renderer::def() const {
    return {.width = impl_->width, .height = impl_->height, .font = impl_->font_path};
}

}  // namespace discreel::render

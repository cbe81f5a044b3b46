#pragma once
// Draws an abstract frame description off-screen (OSMesa, core-profile GL) and returns RGBA
// pixels. It knows nothing of scenes, physics or encoders: callers fill a FrameScene.
//     auto renderer = render::Renderer::create({.width = 1280, .height = 720});
//     auto image = renderer->draw(frame);   // top row first
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/image.hpp"

namespace discreel::render {

struct Rgba {
    float r = 0, g = 0, b = 0, a = 1;   // sRGB-encoded 0..1, straight alpha
};

struct DiscGeom {
    float x = 0, y = 0;             // centre, world metres
    float radius = 0;               // metres; drawn at least one pixel across
    float angle = 0;                // radians, counter-clockwise from +x (the spin marker points so)
    Rgba fill;
    bool is_static = false;         // pegs are drawn differently from moving discs
    std::uint16_t mask_id = 0;      // its value in draw_mask: the caller's id, 0 for none
};

// A rigid body of another shape: a convex outline of 2..8 vertices (2: a capsule's segment)
// swept by `rounding`, in the body's frame (its centroid at the origin), counter-clockwise.
struct PolygonGeom {
    float x = 0, y = 0;             // the body's origin, world metres
    float angle = 0;                // radians, counter-clockwise
    std::array<float, 16> vertices{};   // (x, y) pairs, metres, body frame
    int count = 0;                  // vertices used, 2..8
    float rounding = 0;             // metres swept around the outline
    Rgba fill;
    bool is_static = false;         // drawn darker, without the spin marker
    std::uint16_t mask_id = 0;      // its value in draw_mask: the caller's id, 0 for none
};

struct CapsuleGeom {                // walls: segment a..b swept by a circle of `radius`
    float ax = 0, ay = 0, bx = 0, by = 0;   // world metres
    float radius = 0;               // metres; drawn at least one pixel wide
    Rgba color;
};

// A flat line with round caps, drawn without the walls' darker rim: motion trails (one segment
// per stretch of history, its colour already faded toward the background) and joints (a pin's
// ring is two dots, one over the other).
struct LineGeom {
    float ax = 0, ay = 0, bx = 0, by = 0;   // world metres
    float radius = 0;               // metres (half the line width); drawn at least one pixel wide
    Rgba color;
};

// An arrow from tail to head (classic velocity arrows): a shaft and two barbs, all of a fixed
// pixel width so arrows read the same at every zoom.
struct ArrowGeom {
    float tail_x = 0, tail_y = 0, head_x = 0, head_y = 0;   // world metres
    float width = 2;                // pixels
    Rgba color;
};

enum class Corner { top_left, top_right, bottom_left, bottom_right };

// A line of text in a corner of the frame, in a built-in 5x7 dot font with a soft shadow.
// Glyphs exist for digits, space and . : = - / s f r a m e t; anything else shows as '?'.
struct TextGeom {
    std::string text;
    Corner corner = Corner::top_left;
    int dot = 1;                    // pixels per font dot, >= 1: glyphs are 5 x 7 dots
    Rgba color;
};

// Which point of a text's box lies at its position.
enum class Anchor { top_left, top, top_right, left, center, right, bottom_left, bottom, bottom_right };

// Text in a TrueType font (DejaVu Sans through FreeType), anti-aliased, drawn over everything:
// a title, a caption, a live readout, a body's label. Lines break at '\n'.
struct TextLabel {
    std::string text;               // UTF-8
    bool world = false;             // x, y and size in world metres, else fractions of the frame
    double x = 0.5, y = 0.5;        // frame: fractions of the width and height from the top left
    double size = 0.05;             // the font's em height: a fraction of the frame's height, or m
    Anchor anchor = Anchor::center;
    Rgba color;
    double angle = 0;               // radians, counter-clockwise about the anchor point
    // Drawn first around every glyph, a twelfth of the em wide (at least a pixel): a label's
    // halo in its body's colour hides the spin marker under it.
    std::optional<Rgba> outline;
};

struct Camera {
    double center_x = 0, center_y = 0;   // world metres at the image centre
    double height = 1;                    // world metres visible vertically; y points up
};

struct FrameScene {
    // Below alpha 1 the frame is transparent there, and what is drawn over it keeps its own
    // coverage: the image's alpha is what a compositor needs (straight, not premultiplied).
    Rgba background;
    Camera camera;
    bool disc_outlines = true;            // a darker rim on every disc
    bool spin_markers = true;             // the spoke on every non-static disc
    // Drawn in this order, each list in its own order, later on top.
    std::vector<CapsuleGeom> capsules;
    std::vector<LineGeom> trails;
    std::vector<PolygonGeom> polygons;
    std::vector<DiscGeom> discs;
    std::vector<LineGeom> joints;         // over the bodies: joints' lines, springs, pins
    std::vector<ArrowGeom> arrows;
    // The testbed's debug drawing (contact points as dots, normals, boxes), over the bodies,
    // joints and arrows, under the text.
    std::vector<LineGeom> debug;
    std::vector<TextGeom> texts;
    std::vector<TextLabel> labels;        // last, over everything
};

// Where the font for TextLabel comes from: Debian's fonts-dejavu-core.
inline constexpr const char* default_font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Where a world point lands in a width x height image of `camera`: pixel = M [x, y, 1], in
// pixels from the image's top-left corner, y down, a pixel's centre at (i + 0.5, j + 0.5).
// The renderer draws through exactly this.
struct PixelTransform {
    double m00 = 1, m01 = 0, m02 = 0;
    double m10 = 0, m11 = -1, m12 = 0;
    double pixels_per_metre = 1;
};
PixelTransform pixel_transform(const Camera& camera, int width, int height);

// What an instance mask gives the walls (every CapsuleGeom).
inline constexpr std::uint16_t wall_mask_id = 65535;

// Which geometry is drawn on top at each pixel of the frame, width x height, top row first:
// a disc's or polygon's mask_id, wall_mask_id for capsules (walls), 0 for nothing. No anti-aliasing:
// a pixel belongs to a shape when its centre is inside it (a shape thinner than a pixel as
// wide as the renderer draws it). In the renderer's order, later on top; geometry with mask_id
// 0 or a transparent colour is left out (it hides nothing). The same frame gives the same ids.
std::vector<std::uint16_t> draw_mask(const FrameScene& frame, int width, int height);

// How many threads of its own llvmpipe rasterizes on (Mesa's LP_NUM_THREADS), for the whole
// process: 0 draws on the thread that calls draw(). By default Mesa starts one per core and the
// drawing thread waits for them; next to a video encoder that keeps the cores busy, they
// compete with it and cost more CPU than they save (see docs/performance.md). Mesa reads the
// setting once, when the process's first Renderer is created, so call this before that and
// before starting other threads (it sets an environment variable). A value already in the
// environment wins: the user's choice is kept. Frames are the same bytes either way.
void set_rasterizer_threads(int count);

struct RendererDef {
    int width = 1280;               // pixels
    int height = 720;               // pixels
    std::string font = default_font;   // a TrueType file, opened at the first frame with text
};

class Renderer {
public:
    static Expected<Renderer> create(const RendererDef& def);
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;

    // The view stays valid until the next draw() or until the Renderer is destroyed. Every
    // pixel has alpha 255. Fails for a camera height that is not a positive number.
    Expected<ImageView> draw(const FrameScene& frame);

    // Like draw(), but reads the pixels straight into `out` (at least 4 * width * height bytes)
    // and returns a view of it, so a caller that keeps its own pool of frame buffers needs no
    // copy. The bytes are the same as draw()'s. Fails as draw() does, and for a smaller `out`.
    Expected<ImageView> draw_into(const FrameScene& frame, std::span<std::uint8_t> out);

    std::string renderer_info() const;   // GL_RENDERER and GL_VERSION, for golden metadata
    RendererDef def() const;             // the size it draws

    // Unbinds its GL context from the calling thread. A renderer that threads draw with in
    // turn (under the caller's lock) is released after each draw: a thread must not keep a
    // context current that another thread then binds or destroys.
    void release();

private:
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::render

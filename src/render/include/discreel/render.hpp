#pragma once
// Draws an abstract frame description off-screen (OSMesa, core-profile GL) and returns RGBA
// pixels. It knows nothing of scenes, physics or encoders: callers fill a FrameScene.
//     auto renderer = render::Renderer::create({.width = 1280, .height = 720});
//     auto image = renderer->draw(frame);   // top row first
#include <cstdint>
#include <memory>
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
};

struct CapsuleGeom {                // walls: segment a..b swept by a circle of `radius`
    float ax = 0, ay = 0, bx = 0, by = 0;   // world metres
    float radius = 0;               // metres; drawn at least one pixel wide
    Rgba color;
};

struct Camera {
    double center_x = 0, center_y = 0;   // world metres at the image centre
    double height = 1;                    // world metres visible vertically; y points up
};

struct FrameScene {
    Rgba background;                      // its alpha is ignored: frames are opaque
    Camera camera;
    std::vector<CapsuleGeom> capsules;    // drawn first
    std::vector<DiscGeom> discs;          // drawn in order, later on top
};

struct RendererDef {
    int width = 1280;               // pixels
    int height = 720;               // pixels
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

    std::string renderer_info() const;   // GL_RENDERER and GL_VERSION, for golden metadata

private:
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::render

#include "frame_scene.hpp"

#include <algorithm>
#include <limits>

namespace discreel::app {
namespace {

render::Rgba to_rgba(const scene::Color& c) {
    return {c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, c.a / 255.0f};
}

struct Bounds {
    double min_x = std::numeric_limits<double>::infinity();
    double min_y = std::numeric_limits<double>::infinity();
    double max_x = -std::numeric_limits<double>::infinity();
    double max_y = -std::numeric_limits<double>::infinity();

    void add(Vec2 p, double pad) {
        min_x = std::min(min_x, p.x - pad);
        min_y = std::min(min_y, p.y - pad);
        max_x = std::max(max_x, p.x + pad);
        max_y = std::max(max_y, p.y + pad);
    }
    bool empty() const { return !(min_x <= max_x); }
};

// A box's walls are drawn just outside its corners, so that a disc resting against the box
// touches the wall's inner edge on screen as it does in the simulation.
void add_box_capsules(const scene::Wall& w, std::vector<render::CapsuleGeom>& out) {
    const double r = w.thickness / 2;
    const double x0 = w.a.x - r, y0 = w.a.y - r, x1 = w.b.x + r, y1 = w.b.y + r;
    const render::Rgba color = to_rgba(w.color);
    const auto f = [](double v) { return static_cast<float>(v); };
    out.push_back({f(x0), f(y0), f(x1), f(y0), f(r), color});
    out.push_back({f(x1), f(y0), f(x1), f(y1), f(r), color});
    out.push_back({f(x1), f(y1), f(x0), f(y1), f(r), color});
    out.push_back({f(x0), f(y1), f(x0), f(y0), f(r), color});
}

}  // namespace

render::Camera fit_camera(const scene::Scene& scene) {
    const double aspect = static_cast<double>(scene.video.width) / scene.video.height;
    Bounds box;
    for (const scene::Wall& w : scene.walls) {
        box.add(w.a, w.thickness);
        box.add(w.b, w.thickness);
    }
    if (box.empty()) {
        for (const scene::Disc& d : scene.discs) box.add(d.position, d.radius);
    }
    render::Camera camera;
    if (box.empty()) {
        camera.height = 10.0;
    } else {
        const double margin = 1.1;  // 5 % of the extent on each side
        camera.center_x = (box.min_x + box.max_x) / 2;
        camera.center_y = (box.min_y + box.max_y) / 2;
        camera.height = std::max({(box.max_y - box.min_y) * margin,
                                  (box.max_x - box.min_x) * margin / aspect, 1e-3});
    }
    if (scene.camera.center) {
        camera.center_x = scene.camera.center->x;
        camera.center_y = scene.camera.center->y;
    }
    if (scene.camera.height) camera.height = *scene.camera.height;
    return camera;
}

FrameSceneBuilder::FrameSceneBuilder(const scene::Scene& scene) : scene_(scene) {
    frame_.background = to_rgba(scene.video.background);
    frame_.camera = fit_camera(scene);
    for (const scene::Wall& w : scene.walls) {
        if (w.shape == scene::Wall::Shape::box) {
            add_box_capsules(w, frame_.capsules);
        } else {
            frame_.capsules.push_back({static_cast<float>(w.a.x), static_cast<float>(w.a.y),
                                       static_cast<float>(w.b.x), static_cast<float>(w.b.y),
                                       static_cast<float>(w.thickness / 2), to_rgba(w.color)});
        }
    }
    frame_.discs.resize(scene.discs.size());
    for (std::size_t i = 0; i < scene.discs.size(); ++i) {
        const scene::Disc& d = scene.discs[i];
        frame_.discs[i].radius = static_cast<float>(d.radius);
        frame_.discs[i].fill = to_rgba(d.color);
        frame_.discs[i].is_static = d.is_static;
    }
}

const render::FrameScene& FrameSceneBuilder::build(std::span<const physics::DiscState> discs) {
    for (std::size_t i = 0; i < discs.size(); ++i) {
        frame_.discs[i].x = static_cast<float>(discs[i].position.x);
        frame_.discs[i].y = static_cast<float>(discs[i].position.y);
        frame_.discs[i].angle = static_cast<float>(discs[i].angle);
    }
    return frame_;
}

}  // namespace discreel::app

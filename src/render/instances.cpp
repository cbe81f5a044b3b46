#include "instances.hpp"

namespace discreel::render {
namespace {

struct ToPixels {
    const Camera& camera;
    double scale;   // pixels per metre
    float x(double metres) const { return static_cast<float>((metres - camera.center_x) * scale); }
    float y(double metres) const { return static_cast<float>((metres - camera.center_y) * scale); }
    float length(double metres) const { return static_cast<float>(metres * scale); }
};

}  // namespace

void make_disc_instances(const FrameScene& frame, double pixels_per_metre,
                         std::vector<DiscInstance>& out) {
    const ToPixels to_px{frame.camera, pixels_per_metre};
    out.clear();
    for (const DiscGeom& d : frame.discs) {
        out.push_back({
            .center = {to_px.x(d.x), to_px.y(d.y)},
            .radius = to_px.length(d.radius),
            .angle = d.angle,
            .color = {d.fill.r, d.fill.g, d.fill.b, d.fill.a},
            .flags = d.is_static ? kDiscStatic : 0u,
        });
    }
}

void make_capsule_instances(const FrameScene& frame, double pixels_per_metre,
                            std::vector<CapsuleInstance>& out) {
    const ToPixels to_px{frame.camera, pixels_per_metre};
    out.clear();
    for (const CapsuleGeom& c : frame.capsules) {
        out.push_back({
            .a = {to_px.x(c.ax), to_px.y(c.ay)},
            .b = {to_px.x(c.bx), to_px.y(c.by)},
            .radius = to_px.length(c.radius),
            .color = {c.color.r, c.color.g, c.color.b, c.color.a},
        });
    }
}

}  // namespace discreel::render

#include "instances.hpp"

#include <algorithm>
#include <cmath>

namespace discreel::render {
namespace {

struct ToPixels {
    const Camera& camera;
    double scale;   // pixels per metre
    float x(double metres) const { return static_cast<float>((metres - camera.center_x) * scale); }
    float y(double metres) const { return static_cast<float>((metres - camera.center_y) * scale); }
    float length(double metres) const { return static_cast<float>(metres * scale); }
};

constexpr float kBarbAngle = 0.5f;   // radians between shaft and barb, about 29 degrees
constexpr float kArrowHalo = 1.0f;   // pixels of dark outline on each side of an arrow
constexpr float kArrowHaloColor[3] = {0.04f, 0.05f, 0.07f};

}  // namespace

void make_disc_instances(const FrameScene& frame, double pixels_per_metre,
                         std::vector<DiscInstance>& out) {
    const ToPixels to_px{frame.camera, pixels_per_metre};
    const std::uint32_t style_flags = (frame.disc_outlines ? 0u : kDiscNoOutline) |
                                      (frame.spin_markers ? 0u : kDiscNoSpinMarker);
    out.clear();
    for (const DiscGeom& d : frame.discs) {
        out.push_back({
            .center = {to_px.x(d.x), to_px.y(d.y)},
            .radius = to_px.length(d.radius),
            .angle = d.angle,
            .color = {d.fill.r, d.fill.g, d.fill.b, d.fill.a},
            .flags = (d.is_static ? kDiscStatic : 0u) | style_flags,
        });
    }
}

void make_polygon_instances(const FrameScene& frame, double pixels_per_metre,
                            std::vector<PolygonInstance>& out) {
    const ToPixels to_px{frame.camera, pixels_per_metre};
    const std::uint32_t style_flags = (frame.disc_outlines ? 0u : kPolygonNoOutline) |
                                      (frame.spin_markers ? 0u : kPolygonNoSpinMarker);
    out.clear();
    for (const PolygonGeom& p : frame.polygons) {
        PolygonInstance instance{};
        instance.center[0] = to_px.x(p.x);
        instance.center[1] = to_px.y(p.y);
        const double c = std::cos(p.angle), s = std::sin(p.angle);
        const auto count = static_cast<std::size_t>(std::clamp(p.count, 0, 8));
        double extent = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const double x = p.vertices[2 * i], y = p.vertices[2 * i + 1];
            const double px = (c * x - s * y) * pixels_per_metre;
            const double py = (s * x + c * y) * pixels_per_metre;
            instance.vertices[2 * i] = static_cast<float>(px);
            instance.vertices[2 * i + 1] = static_cast<float>(py);
            extent = std::max(extent, std::hypot(px, py));
        }
        const float rounding = to_px.length(p.rounding);
        instance.shape[0] = static_cast<float>(count);
        instance.shape[1] = rounding;
        instance.shape[2] = static_cast<float>(extent) + rounding;
        instance.shape[3] = static_cast<float>((p.is_static ? kPolygonStatic : 0u) | style_flags);
        // The marker runs from the centroid along the body's x axis to 70 % of the way to the
        // outline: the core's nearest edge crossing on that ray (the segment's end for a
        // capsule, the centre for a circle), plus the rounding.
        double reach = 0;
        if (count == 2) {
            reach = std::abs(p.vertices[0]);
        } else if (count > 2) {
            reach = HUGE_VAL;
            for (std::size_t i = 0; i < count; ++i) {
                const std::size_t j = (i + 1) % count;
                const double ex = p.vertices[2 * j] - p.vertices[2 * i];
                const double ey = p.vertices[2 * j + 1] - p.vertices[2 * i + 1];
                const double nx = ey, ny = -ex;   // outward for counter-clockwise vertices
                if (nx <= 0) continue;           // the ray +x leaves through edges facing +x
                reach = std::min(reach, (nx * p.vertices[2 * i] + ny * p.vertices[2 * i + 1]) / nx);
            }
            if (!std::isfinite(reach)) reach = 0;
        }
        instance.spoke[0] = static_cast<float>(c);
        instance.spoke[1] = static_cast<float>(s);
        instance.spoke[2] = static_cast<float>(0.7 * (reach * pixels_per_metre) + 0.7 * rounding);
        instance.color[0] = p.fill.r;
        instance.color[1] = p.fill.g;
        instance.color[2] = p.fill.b;
        instance.color[3] = p.fill.a;
        out.push_back(instance);
    }
}

namespace {

// GL drops a point whose centre leaves the view (this keeps it a pixel inside) and caps the
// size of a sprite.
bool sprite_fits(const float* center, float size, int width, int height, float max_point_size) {
    const float inside_x = 0.5f * static_cast<float>(width) - 1.0f;
    const float inside_y = 0.5f * static_cast<float>(height) - 1.0f;
    return size <= max_point_size && std::abs(center[0]) <= inside_x &&
           std::abs(center[1]) <= inside_y;
}

}  // namespace

bool fits_point_sprite(const DiscInstance& disc, int width, int height, float max_point_size) {
    const float size = 2.0f * (std::max(disc.radius, kDiscMinRadius) + kDiscQuadMargin);
    return sprite_fits(disc.center, size, width, height, max_point_size);
}

bool fits_point_sprite(const PolygonInstance& polygon, int width, int height,
                       float max_point_size) {
    const float size = 2.0f * (polygon.shape[2] + kPolygonQuadMargin);
    return sprite_fits(polygon.center, size, width, height, max_point_size);
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
            .flags = 0,
        });
    }
}

void make_line_instances(const FrameScene& frame, std::span<const LineGeom> lines,
                         double pixels_per_metre, std::vector<CapsuleInstance>& out) {
    const ToPixels to_px{frame.camera, pixels_per_metre};
    out.clear();
    for (const LineGeom& l : lines) {
        out.push_back({
            .a = {to_px.x(l.ax), to_px.y(l.ay)},
            .b = {to_px.x(l.bx), to_px.y(l.by)},
            .radius = to_px.length(l.radius),
            .color = {l.color.r, l.color.g, l.color.b, l.color.a},
            .flags = kCapsuleFlat,
        });
    }
}

void make_arrow_instances(const FrameScene& frame, double pixels_per_metre,
                          std::vector<CapsuleInstance>& out) {
    const ToPixels to_px{frame.camera, pixels_per_metre};
    out.clear();
    for (const ArrowGeom& a : frame.arrows) {
        const float tx = to_px.x(a.tail_x), ty = to_px.y(a.tail_y);
        const float hx = to_px.x(a.head_x), hy = to_px.y(a.head_y);
        const float dx = hx - tx, dy = hy - ty;
        const float length = std::hypot(dx, dy);
        // Shorter than a pixel there is no direction worth showing.
        if (!(length >= 1.0f)) continue;
        const float ux = dx / length, uy = dy / length;
        // The head grows with the line width but never past 40 % of the arrow, so short arrows
        // stay arrows rather than chevrons.
        const float barb = std::min(3.0f * a.width + 4.0f, 0.4f * length);
        const float c = std::cos(kBarbAngle), s = std::sin(kBarbAngle);
        // A dark halo first, kArrowHalo pixels wider on each side, then the arrow: it reads on
        // light bodies and on dark ones alike. The halo's pieces overlap at the head, so it is
        // as opaque as the arrow (translucent, the overlaps would show darker).
        for (const bool halo : {true, false}) {
            const float radius = a.width / 2 + (halo ? kArrowHalo : 0.0f);
            const float color[4] = {halo ? kArrowHaloColor[0] : a.color.r,
                                    halo ? kArrowHaloColor[1] : a.color.g,
                                    halo ? kArrowHaloColor[2] : a.color.b, a.color.a};
            const auto line = [&](float x0, float y0, float x1, float y1) {
                out.push_back({.a = {x0, y0}, .b = {x1, y1}, .radius = radius,
                               .color = {color[0], color[1], color[2], color[3]},
                               .flags = kCapsuleFlat});
            };
            line(tx, ty, hx, hy);
            // The barbs point back from the head, turned by +-kBarbAngle from the shaft.
            line(hx, hy, hx - barb * (c * ux - s * uy), hy - barb * (s * ux + c * uy));
            line(hx, hy, hx - barb * (c * ux + s * uy), hy - barb * (-s * ux + c * uy));
        }
    }
}

}  // namespace discreel::render

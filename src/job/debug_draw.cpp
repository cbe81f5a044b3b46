#include "debug_draw.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace discreel::job {
namespace {

// Colours of the debug drawing, sRGB: bright, and apart from the usual palettes.
constexpr render::Rgba contact_colour{1.0f, 0.23f, 0.19f, 1};    // red dots
constexpr render::Rgba normal_colour{0.2f, 0.78f, 0.35f, 1};     // green
constexpr render::Rgba push_colour{1.0f, 0.8f, 0.0f, 1};         // yellow
constexpr render::Rgba box_colour{0.69f, 0.32f, 0.87f, 1};       // violet
constexpr render::Rgba anchor_colour{0.35f, 0.78f, 0.98f, 1};    // sky blue

// Sizes in pixels, converted to metres with the frame's scale.
constexpr double dot_px = 3.0;        // radius of a contact's or an anchor's dot
constexpr double normal_px = 12.0;    // length of a normal
constexpr double thin_px = 0.75;      // half width of normals and boxes
constexpr double push_px = 1.25;      // half width of a push
constexpr double longest_push = 2.0;  // radii of the lighter body

render::LineGeom segment(double ax, double ay, double bx, double by, double half,
                         const render::Rgba& colour) {
    return {static_cast<float>(ax), static_cast<float>(ay), static_cast<float>(bx),
            static_cast<float>(by), static_cast<float>(half), colour};
}

void add_box(double x0, double y0, double x1, double y1, double half,
             std::vector<render::LineGeom>& out) {
    out.push_back(segment(x0, y0, x1, y0, half, box_colour));
    out.push_back(segment(x1, y0, x1, y1, half, box_colour));
    out.push_back(segment(x1, y1, x0, y1, half, box_colour));
    out.push_back(segment(x0, y1, x0, y0, half, box_colour));
}

void add_boxes(const render::FrameScene& frame, double half, std::vector<render::LineGeom>& out) {
    for (const render::DiscGeom& d : frame.discs) {
        add_box(d.x - d.radius, d.y - d.radius, d.x + d.radius, d.y + d.radius, half, out);
    }
    for (const render::PolygonGeom& p : frame.polygons) {
        const double c = std::cos(p.angle), s = std::sin(p.angle);
        double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
        const auto count = static_cast<std::size_t>(std::max(p.count, 0));
        for (std::size_t k = 0; k < count; ++k) {
            const double vx = p.vertices[2 * k];
            const double vy = p.vertices[2 * k + 1];
            const double x = p.x + c * vx - s * vy, y = p.y + s * vx + c * vy;
            x0 = std::min(x0, x);
            x1 = std::max(x1, x);
            y0 = std::min(y0, y);
            y1 = std::max(y1, y);
        }
        add_box(x0 - p.rounding, y0 - p.rounding, x1 + p.rounding, y1 + p.rounding, half, out);
    }
}

// A push is drawn as long as the lighter body's radius when its force equals that body's
// weight (its mass under the scene's gravity, or 9.81 m/s^2 without any), to four radii.
double push_length(const scene::Scene& scene, const physics::ContactPoint& c) {
    const double g = std::hypot(scene.physics.gravity.x, scene.physics.gravity.y);
    const double g0 = g > 0 ? g : 9.81;
    double mass = std::numeric_limits<double>::infinity(), radius = 0;
    const auto consider = [&](std::size_t i) {
        const scene::Body& b = scene.bodies[i];
        if (b.is_static || b.kinematic || !(b.mass > 0)) return;
        if (b.mass < mass) {
            mass = b.mass;
            radius = b.radius;
        }
    };
    consider(c.a);
    if (c.other_kind == physics::ContactEvent::Other::body) consider(c.other);
    if (!std::isfinite(mass)) return 0;
    return std::min(longest_push, c.force / (mass * g0)) * radius;
}

}  // namespace

render::Rgba asleep_fill(const render::Rgba& fill) {
    const float grey = 0.5f;
    return {0.5f * (fill.r + grey), 0.5f * (fill.g + grey), 0.5f * (fill.b + grey), fill.a};
}

void add_debug_geometry(const scene::Scene& scene, const DebugState& state,
                        render::FrameScene& frame) {
    std::vector<render::LineGeom>& out = frame.debug;
    out.clear();
    const scene::DebugDraw& debug = scene.style.debug;
    const double m = frame.camera.height / scene.video.height;   // metres per pixel
    if (debug.boxes) add_boxes(frame, thin_px * m, out);
    for (const physics::ContactPoint& c : state.contacts) {
        const double x = c.point.x, y = c.point.y;
        if (debug.impulses) {
            // The push on body a: from the point into a, against the normal.
            const double l = push_length(scene, c);
            if (l > 0) {
                out.push_back(segment(x, y, x - c.normal.x * l, y - c.normal.y * l, push_px * m,
                                      push_colour));
            }
        }
        if (debug.normals) {
            const double l = normal_px * m;
            out.push_back(segment(x, y, x + c.normal.x * l, y + c.normal.y * l, thin_px * m,
                                  normal_colour));
        }
        if (debug.contacts) out.push_back(segment(x, y, x, y, dot_px * m, contact_colour));
    }
    if (debug.joints) {
        for (const physics::JointState& j : state.joints) {
            const Vec2 a = j.anchor_a, b = j.anchor_b;
            if (a.x != b.x || a.y != b.y) {
                out.push_back(segment(a.x, a.y, b.x, b.y, thin_px * m, anchor_colour));
            }
            out.push_back(segment(a.x, a.y, a.x, a.y, dot_px * m, anchor_colour));
            out.push_back(segment(b.x, b.y, b.x, b.y, 0.6 * dot_px * m, anchor_colour));
        }
    }
}

}  // namespace discreel::job

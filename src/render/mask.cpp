// Instance masks on the CPU: exact, cheap at dataset sizes, and free of the GL pass's
// anti-aliasing and blending, which a mask must not have.
#include <algorithm>
#include <cmath>

#include "discreel/render.hpp"

namespace discreel::render {
namespace {

struct Point {
    double x = 0, y = 0;
};

double distance_to_segment(Point p, Point a, Point b) {
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double length2 = dx * dx + dy * dy;
    double t = length2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / length2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Distance from `p` to a convex outline (counter-clockwise, 1..8 points; 1 is a point, 2 a
// segment), 0 inside it.
double distance_to_outline(Point p, const PolygonGeom& g) {
    const auto n = static_cast<std::size_t>(std::clamp(g.count, 0, 8));
    if (n == 1) return std::hypot(p.x - g.vertices[0], p.y - g.vertices[1]);
    bool inside = n >= 3;
    double nearest = HUGE_VAL;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (i + 1) % n;
        const Point a{g.vertices[2 * i], g.vertices[2 * i + 1]};
        const Point b{g.vertices[2 * j], g.vertices[2 * j + 1]};
        if ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) < 0) inside = false;
        nearest = std::min(nearest, distance_to_segment(p, a, b));
    }
    return inside ? 0.0 : nearest;
}

// Pixel grid of one frame: which pixels a world-space box covers, and each pixel's centre in
// the world.
class Grid {
public:
    Grid(const FrameScene& frame, int width, int height, std::vector<std::uint16_t>& ids)
        : t_(pixel_transform(frame.camera, width, height)), width_(width), height_(height),
          ids_(ids) {}

    double half_pixel() const { return 0.5 / t_.pixels_per_metre; }

    // Sets `id` at every pixel whose centre lies within the world box around (x, y) of
    // half-size `reach` and for which inside(world point) holds.
    template <class Inside>
    void fill(double x, double y, double reach, std::uint16_t id, Inside inside) {
        const double px = t_.m00 * x + t_.m02, py = t_.m11 * y + t_.m12;
        const double r = reach * t_.pixels_per_metre;
        const int i0 = std::max(0, static_cast<int>(std::floor(px - r - 0.5)));
        const int i1 = std::min(width_ - 1, static_cast<int>(std::ceil(px + r - 0.5)));
        const int j0 = std::max(0, static_cast<int>(std::floor(py - r - 0.5)));
        const int j1 = std::min(height_ - 1, static_cast<int>(std::ceil(py + r - 0.5)));
        for (int j = j0; j <= j1; ++j) {
            const double wy = (j + 0.5 - t_.m12) / t_.m11;
            for (int i = i0; i <= i1; ++i) {
                const double wx = (i + 0.5 - t_.m02) / t_.m00;
                if (inside(Point{wx, wy})) {
                    ids_[static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
                         static_cast<std::size_t>(i)] = id;
                }
            }
        }
    }

private:
    PixelTransform t_;
    int width_, height_;
    std::vector<std::uint16_t>& ids_;
};

}  // namespace

PixelTransform pixel_transform(const Camera& camera, int width, int height) {
    const double s = static_cast<double>(height) / camera.height;
    return {.m00 = s,
            .m01 = 0,
            .m02 = 0.5 * width - camera.center_x * s,
            .m10 = 0,
            .m11 = -s,
            .m12 = 0.5 * height + camera.center_y * s,
            .pixels_per_metre = s};
}

std::vector<std::uint16_t> draw_mask(const FrameScene& frame, int width, int height) {
    std::vector<std::uint16_t> ids(static_cast<std::size_t>(std::max(width, 0)) *
                                   static_cast<std::size_t>(std::max(height, 0)));
    if (ids.empty() || !(frame.camera.height > 0) || !std::isfinite(frame.camera.height)) {
        return ids;
    }
    Grid grid(frame, width, height, ids);
    const double least = grid.half_pixel();   // every shape is drawn at least a pixel wide
    for (const CapsuleGeom& c : frame.capsules) {
        if (c.color.a <= 0) continue;   // a transparent wall hides nothing
        const Point a{c.ax, c.ay}, b{c.bx, c.by};
        const double r = std::max<double>(c.radius, least);
        grid.fill(0.5 * (a.x + b.x), 0.5 * (a.y + b.y),
                  0.5 * std::hypot(b.x - a.x, b.y - a.y) + r, wall_mask_id,
                  [&](Point p) { return distance_to_segment(p, a, b) <= r; });
    }
    for (const PolygonGeom& g : frame.polygons) {
        if (g.mask_id == 0 || g.fill.a <= 0 || g.count < 1) continue;
        double reach = 0;
        for (std::size_t k = 0; k < static_cast<std::size_t>(std::min(g.count, 8)); ++k)
            reach = std::max<double>(reach, std::hypot(g.vertices[2 * k], g.vertices[2 * k + 1]));
        const double rounding = std::max<double>(g.rounding, g.count <= 2 ? least : 0.0);
        const double c = std::cos(static_cast<double>(g.angle));
        const double s = std::sin(static_cast<double>(g.angle));
        grid.fill(g.x, g.y, reach + rounding, g.mask_id, [&](Point p) {
            const double dx = p.x - g.x, dy = p.y - g.y;
            const Point local{c * dx + s * dy, -s * dx + c * dy};   // turned back by the angle
            return distance_to_outline(local, g) <= rounding;
        });
    }
    for (const DiscGeom& d : frame.discs) {
        if (d.mask_id == 0 || d.fill.a <= 0) continue;
        const double r = std::max<double>(d.radius, least);
        grid.fill(d.x, d.y, r, d.mask_id, [&](Point p) {
            const double dx = p.x - d.x, dy = p.y - d.y;
            return dx * dx + dy * dy <= r * r;
        });
    }
    return ids;
}

}  // namespace discreel::render

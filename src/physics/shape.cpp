#include "shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace discreel::physics::detail {
namespace {

// Below this a length or an area is no size at all: a millionth of a millimetre, relative
// to the shape's scale, is well under anything the solver resolves.
constexpr double tiny = 1e-9;

void set_normals(Polygon& p) {
    for (int i = 0; i < p.count; ++i) {
        const V2 edge = p.vertices[(i + 1) % p.count] - p.vertices[i];
        p.normals[i] = V2(edge.y(), -edge.x()).normalized();
    }
}

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

Expected<Polygon> make_box(double width, double height, double rounding) {
    if (!positive_finite(width) || !positive_finite(height)) {
        return Error{"a box needs a width and a height greater than 0"};
    }
    if (!(rounding >= 0) || 2 * rounding >= std::min(width, height)) {
        return Error{"rounding must be at least 0 and less than half the box's smaller side"};
    }
    const double hw = width / 2 - rounding, hh = height / 2 - rounding;
    Polygon p;
    p.count = 4;
    p.vertices = {V2(-hw, -hh), V2(hw, -hh), V2(hw, hh), V2(-hw, hh)};
    p.radius = rounding;
    set_normals(p);
    return p;
}

Expected<PolygonResult> make_polygon(std::span<const Vec2> points, double rounding) {
    const int n = static_cast<int>(points.size());
    if (n < 3) return Error{"a polygon needs at least 3 points, got " + std::to_string(n)};
    if (n > max_polygon_vertices) {
        return Error{"a polygon has at most 8 points, got " + std::to_string(n) +
                     "; split it into convex pieces of up to 8"};
    }
    if (!(rounding >= 0) || !std::isfinite(rounding)) return Error{"rounding must be at least 0"};
    std::array<V2, max_polygon_vertices> v{};
    double scale = 0;
    for (int i = 0; i < n; ++i) {
        v[i] = V2(points[i].x, points[i].y);
        scale = std::max({scale, std::abs(v[i].x()), std::abs(v[i].y())});
    }
    // Twice the signed area: its sign is the winding.
    double area2 = 0;
    for (int i = 0; i < n; ++i) area2 += cross(v[i], v[(i + 1) % n]);
    const double eps = tiny * std::max(scale * scale, 1e-12);
    if (!(std::abs(area2) > eps)) {
        // No area: either every point is on one line, or the outline crosses itself so that
        // its halves cancel (a bow-tie).
        double spread = 0;
        for (int i = 1; i < n; ++i) {
            for (int j = i + 1; j < n; ++j) {
                spread = std::max(spread, std::abs(cross(v[i] - v[0], v[j] - v[0])));
            }
        }
        if (spread > eps) {
            return Error{"the polygon's outline crosses itself; list its points in order "
                         "around it"};
        }
        return Error{"the polygon has no area (its points are on a line)"};
    }
    if (area2 < 0) std::reverse(v.begin(), v.begin() + n);   // counter-clockwise from here on
    for (int i = 0; i < n; ++i) {
        const V2& a = v[i];
        const V2& b = v[(i + 1) % n];
        const V2& c = v[(i + 2) % n];
        const double turn = cross(b - a, c - b);
        if (turn < -eps) {
            return Error{"the polygon is not convex (it turns the other way at point " +
                         std::to_string((i + 1) % n) + "); split it into convex pieces"};
        }
        if (turn <= eps) {
            return Error{"point " + std::to_string((i + 1) % n) +
                         " lies on the line between its neighbours; remove it"};
        }
    }
    // Every turn the same way but the outline could still wind twice (a pentagram): the
    // angles then add to more than a full turn, which the area test above cannot see.
    double turning = 0;
    for (int i = 0; i < n; ++i) {
        const V2 e0 = v[(i + 1) % n] - v[i];
        const V2 e1 = v[(i + 2) % n] - v[(i + 1) % n];
        turning += std::atan2(cross(e0, e1), e0.dot(e1));
    }
    if (turning > 2 * std::numbers::pi + 1e-6) {
        return Error{"the polygon's outline crosses itself; list its points in order around it"};
    }
    // Area centroid, relative to the first point for accuracy far from the origin.
    V2 centroid = V2::Zero();
    double area = 0;
    for (int i = 1; i + 1 < n; ++i) {
        const V2 e1 = v[i] - v[0], e2 = v[i + 1] - v[0];
        const double a = 0.5 * cross(e1, e2);
        centroid += a * (e1 + e2) / 3.0;
        area += a;
    }
    centroid = v[0] + centroid / area;
    PolygonResult result;
    result.offset = centroid;
    result.polygon.count = n;
    result.polygon.radius = rounding;
    for (int i = 0; i < n; ++i) result.polygon.vertices[i] = v[i] - centroid;
    set_normals(result.polygon);
    return result;
}

Expected<Polygon> make_capsule(double length, double radius) {
    if (!positive_finite(length) || !positive_finite(radius)) {
        return Error{"a capsule needs a length and a radius greater than 0"};
    }
    Polygon p;
    p.count = 2;
    p.vertices[0] = V2(-length / 2, 0);
    p.vertices[1] = V2(length / 2, 0);
    p.normals[0] = V2(0, -1);
    p.normals[1] = V2(0, 1);
    p.radius = radius;
    return p;
}

Polygon make_circle(double radius) {
    Polygon p;
    p.count = 1;
    p.vertices[0] = V2::Zero();   // Eigen leaves its vectors uninitialised by default
    p.normals[0] = V2::UnitY();
    p.radius = radius;
    return p;
}

MassProperties mass_properties(const Polygon& shape, double density) {
    const double r = shape.radius;
    MassProperties m;
    if (shape.count == 1) {
        m.area = std::numbers::pi * r * r;
        m.mass = density * m.area;
        m.inertia = 0.5 * m.mass * r * r;
        return m;
    }
    if (shape.count == 2) {
        // A rectangle of length x 2r and two half discs, which together make a disc of radius
        // r whose halves sit at the ends: the parallel-axis term uses the half discs' own
        // centroids, 4r/(3 pi) beyond the segment's ends.
        const double length = (shape.vertices[1] - shape.vertices[0]).norm();
        const double box_mass = density * length * 2 * r;
        const double disc_mass = density * std::numbers::pi * r * r;
        const double box_inertia = box_mass * (length * length + 4 * r * r) / 12;
        const double lever = length / 2 + 4 * r / (3 * std::numbers::pi);
        const double half_disc_own = 0.5 * disc_mass * r * r -
                                     disc_mass * std::pow(4 * r / (3 * std::numbers::pi), 2);
        m.area = length * 2 * r + std::numbers::pi * r * r;
        m.mass = box_mass + disc_mass;
        m.inertia = box_inertia + half_disc_own + disc_mass * lever * lever;
        return m;
    }
    // The core polygon as triangles from the centroid (the origin), then the rounding: a band
    // of width r along every edge (a rectangle on each edge) and a circular sector at every
    // corner, whose angles add to a full turn. Each piece's second moment about the origin is
    // its own plus the shift to where it is: exact for every piece.
    double area = 0, second_moment = 0;   // the core, per unit density
    for (int i = 0; i < shape.count; ++i) {
        const V2& a = shape.vertices[i];
        const V2& b = shape.vertices[(i + 1) % shape.count];
        const double t = 0.5 * cross(a, b);
        area += t;
        second_moment += t * (a.squaredNorm() + a.dot(b) + b.squaredNorm()) / 6;
    }
    double total_area = area, total_second = second_moment;
    if (r > 0) {
        for (int i = 0; i < shape.count; ++i) {
            const V2& a = shape.vertices[i];
            const V2& b = shape.vertices[(i + 1) % shape.count];
            const double length = (b - a).norm();
            const V2 centre = 0.5 * (a + b) + shape.normals[i] * (r / 2);
            const double band = length * r;
            total_area += band;
            total_second += band * ((length * length + r * r) / 12 + centre.squaredNorm());
        }
        // Corner sectors: their angles add to a full turn.
        double corner_area = 0;
        for (int i = 0; i < shape.count; ++i) {
            const V2& n0 = shape.normals[(i + shape.count - 1) % shape.count];
            const V2& n1 = shape.normals[i];
            const double angle = std::atan2(cross(n0, n1), n0.dot(n1));
            const double sector = 0.5 * angle * r * r;
            corner_area += sector;
            // About its apex (the vertex v) a sector has A r^2 / 2; about the origin
            // |v + q|^2 adds A |v|^2 and 2 v . (A c), c its centroid from the apex.
            const V2 bisector = (n0 + n1).normalized();
            const double reach = 4 * r * std::sin(angle / 2) / (3 * angle);
            const V2& v = shape.vertices[i];
            total_second += sector * (0.5 * r * r + v.squaredNorm() + 2 * reach * v.dot(bisector));
        }
        total_area += corner_area;
    }
    m.area = total_area;
    m.mass = density * total_area;
    m.inertia = density * total_second;
    return m;
}

double bounding_radius(const Polygon& shape) {
    double farthest = 0;
    for (int i = 0; i < shape.count; ++i) farthest = std::max(farthest, shape.vertices[i].norm());
    return farthest + shape.radius;
}

std::array<Slab, 4> container_slabs(const V2& lo, const V2& hi) {
    // A container without an inside still gets slabs of some size (make_box needs one).
    const double width = std::max(hi.x() - lo.x(), tiny), height = std::max(hi.y() - lo.y(), tiny);
    const double depth = std::max(width, height);
    const auto slab = [](double w, double h, const V2& centre) {
        Slab s;
        s.shape = *make_box(w, h);   // w, h >= tiny > 0, no rounding: always made
        s.centre = centre;
        return s;
    };
    const double outer_w = width + 2 * depth;
    const V2 middle = 0.5 * (lo + hi);
    return {slab(outer_w, depth, V2(middle.x(), lo.y() - depth / 2)),    // floor
            slab(outer_w, depth, V2(middle.x(), hi.y() + depth / 2)),    // ceiling
            slab(depth, height, V2(lo.x() - depth / 2, middle.y())),     // left
            slab(depth, height, V2(hi.x() + depth / 2, middle.y()))};    // right
}

}  // namespace discreel::physics::detail

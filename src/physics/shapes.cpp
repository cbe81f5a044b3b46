// The public face of shape.hpp: the same makers and measures over plain vectors.
#include "discreel/shapes.hpp"

#include <algorithm>

#include "discreel/physics.hpp"

#include "manifold.hpp"
#include "shape.hpp"

namespace discreel::physics {
namespace {

Shape to_shape(const detail::Polygon& p) {
    Shape s;
    s.radius = p.radius;
    for (int i = 0; i < p.count; ++i) s.vertices.push_back({p.vertices[i].x(), p.vertices[i].y()});
    return s;
}

}  // namespace

namespace detail {

Polygon to_polygon(const Shape& s) {
    Polygon p;
    p.count = static_cast<int>(std::min<std::size_t>(s.vertices.size(), max_polygon_vertices));
    p.radius = s.radius;
    for (int i = 0; i < p.count; ++i) p.vertices[i] = V2(s.vertices[i].x, s.vertices[i].y);
    if (p.count == 1) {
        p.normals[0] = V2::UnitY();
    } else if (p.count == 2) {
        const V2 n = perp(p.vertices[1] - p.vertices[0]).normalized();
        p.normals[0] = -n;
        p.normals[1] = n;
    } else {
        for (int i = 0; i < p.count; ++i) {
            const V2 edge = p.vertices[(i + 1) % p.count] - p.vertices[i];
            p.normals[i] = V2(edge.y(), -edge.x()).normalized();
        }
    }
    return p;
}

}  // namespace detail

Expected<Shape> box_shape(double width, double height, double rounding) {
    auto p = detail::make_box(width, height, rounding);
    if (!p) return p.error();
    return to_shape(*p);
}

Expected<CentredShape> polygon_shape(std::span<const Vec2> points, double rounding) {
    auto p = detail::make_polygon(points, rounding);
    if (!p) return p.error();
    return CentredShape{to_shape(p->polygon), {p->offset.x(), p->offset.y()}};
}

Expected<Shape> capsule_shape(double length, double radius) {
    auto p = detail::make_capsule(length, radius);
    if (!p) return p.error();
    return to_shape(*p);
}

Shape circle_shape(double radius) { return to_shape(detail::make_circle(radius)); }

ShapeMass shape_mass(const Shape& shape, double density) {
    const detail::MassProperties m = detail::mass_properties(detail::to_polygon(shape), density);
    return {m.mass, m.inertia, m.area};
}

double bounding_radius(const Shape& shape) {
    return detail::bounding_radius(detail::to_polygon(shape));
}

double separation(const Shape& a, const Vec2& position_a, double angle_a, const Shape& b,
                  const Vec2& position_b, double angle_b, double reach) {
    const detail::Manifold m = detail::collide(
        detail::to_polygon(a), detail::Transform::of({position_a.x, position_a.y}, angle_a),
        detail::to_polygon(b), detail::Transform::of({position_b.x, position_b.y}, angle_b),
        reach);
    double nearest = reach;
    for (int k = 0; k < m.count; ++k) nearest = std::min(nearest, m.points[k].separation);
    return nearest;
}

double inertia_of(const BodyDef& def) {
    if (!def.shape) return 0.5 * def.mass * def.radius * def.radius;
    const ShapeMass unit = shape_mass(*def.shape, 1.0);
    return unit.area > 0 ? def.mass * unit.inertia / unit.mass : 0.0;
}

}  // namespace discreel::physics

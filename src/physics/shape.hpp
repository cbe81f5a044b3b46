#pragma once
// Rigid-body shapes other than the disc fast path, in one representation: a convex polygon of
// 1..8 vertices swept by a radius. A circle is one vertex with a radius, a capsule two vertices
// (its segment) with a radius, a box or polygon 3..8 vertices with an optional corner rounding.
// One representation lets one pair function per shape class produce every manifold, as Box2D
// does with its rounded polygons. Coordinates are in the body's frame, the centroid at the
// origin; vertices counter-clockwise; everything in double.
#include <array>
#include <span>
#include <string>

#include "body.hpp"
#include "discreel/expected.hpp"
#include "discreel/shapes.hpp"
#include "discreel/vec2.hpp"

namespace discreel::physics::detail {

inline constexpr int max_polygon_vertices = 8;

// Only the first `count` vertices and normals are set (Eigen does not zero the others).
struct Polygon {
    std::array<V2, max_polygon_vertices> vertices;     // metres, counter-clockwise
    std::array<V2, max_polygon_vertices> normals;      // outward unit normal of edge i -> i+1
    int count = 0;                                     // 1 circle, 2 capsule, 3..8 polygon
    double radius = 0.0;                               // metres swept around the core
};

// A box of width w and height h centred on the origin, with corners rounded by `rounding`
// (the rounding adds to the extent: the box's core is (w - 2r) x (h - 2r)).
Expected<Polygon> make_box(double width, double height, double rounding = 0.0);
// Any convex polygon of 3..8 points in either winding; shifted so that the area centroid of
// the core is the origin (`offset` says by how much: the body's position is where the
// centroid goes). Collinear middle points, a concave or self-crossing outline, a zero area or
// more than 8 points are refused with the reason.
struct PolygonResult {
    Polygon polygon;
    V2 offset = V2::Zero();   // subtracted from every input point
};
Expected<PolygonResult> make_polygon(std::span<const Vec2> points, double rounding = 0.0);
// A capsule: a segment of `length` along the body's x axis, swept by `radius`.
Expected<Polygon> make_capsule(double length, double radius);
Polygon make_circle(double radius);
// The public plain-data shape (discreel/shapes.hpp) as a Polygon, normals computed.
Polygon to_polygon(const Shape& shape);

struct MassProperties {
    double mass = 0.0;      // kg
    double inertia = 0.0;   // kg m^2, about the centroid
    double area = 0.0;      // m^2
};

// Mass and moment of inertia of a uniform shape of `density` (kg/m^2), the rounding included.
MassProperties mass_properties(const Polygon& shape, double density);

// The farthest point of the shape from its centroid, metres: the trace's bounding radius.
double bounding_radius(const Polygon& shape);

// A box wall (a closed container whose inside is lo..hi) as four solid slabs around that
// inside, for bodies of any shape: each as deep as the container is wide or high, so a body
// pushed into one is pushed back inside, never through to the far side.
struct Slab {
    Polygon shape;
    V2 centre = V2::Zero();   // metres, where the slab's centroid is
};
std::array<Slab, 4> container_slabs(const V2& lo, const V2& hi);

}  // namespace discreel::physics::detail

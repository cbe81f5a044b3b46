#pragma once
// Shapes of rigid bodies other than plain discs, as plain data for the scene loader, the
// renderer and the trace: a convex core of 1..8 vertices swept by a radius (1 vertex: a
// circle; 2: a capsule; 3..8: a polygon, rounded when the radius is above 0). The makers
// check their input and say what is wrong in words; physics steps what they make.
#include <span>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/vec2.hpp"

namespace discreel::physics {

inline constexpr int max_shape_vertices = 8;

struct Shape {
    std::vector<Vec2> vertices;    // metres, body frame, area centroid at the origin,
                                   // counter-clockwise; 1..8 of them
    double radius = 0.0;           // metres swept around the core (rounding or capsule radius)
};

// width x height, centred; `rounding` (metres) rounds the corners within that extent.
Expected<Shape> box_shape(double width, double height, double rounding = 0.0);

// Any convex outline of 3..8 points in either winding, moved so that its area centroid is
// the origin: `offset` is the centroid in the points' own frame.
struct CentredShape {
    Shape shape;
    Vec2 offset;                   // metres
};
Expected<CentredShape> polygon_shape(std::span<const Vec2> points, double rounding = 0.0);

// A segment of `length` along the body's x axis, swept by `radius` (metres).
Expected<Shape> capsule_shape(double length, double radius);
Shape circle_shape(double radius);

struct ShapeMass {
    double mass = 0.0;             // kg
    double inertia = 0.0;          // kg m^2 about the centroid
    double area = 0.0;             // m^2
};
ShapeMass shape_mass(const Shape& shape, double density);   // density in kg/m^2

// Farthest point of the shape from its centroid, metres.
double bounding_radius(const Shape& shape);

// Signed distance between two placed shapes, metres: negative when they overlap (by the
// depth along the axis of least overlap), exact to rounding when apart up to `reach`, and
// `reach` or more when farther apart than that.
double separation(const Shape& a, const Vec2& position_a, double angle_a, const Shape& b,
                  const Vec2& position_b, double angle_b, double reach = 1.0);

}  // namespace discreel::physics

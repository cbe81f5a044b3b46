#pragma once
// Contact manifolds between shapes: one pair function per pair of shape classes, chosen from a
// table, each producing up to two points with their separations and feature ids (for warm
// starting: the same id next step means the same pair of features touching). The solver will
// consume these rows, never shapes. Computed in double, in the reference body's frame.
#include <array>
#include <cstdint>

#include "body.hpp"
#include "shape.hpp"

namespace discreel::physics::detail {

struct Transform {
    V2 p = V2::Zero();       // position of the body's origin (its centroid), metres
    double c = 1, s = 0;     // cos and sin of the body's angle

    static Transform of(const V2& position, double angle) {
        return {position, std::cos(angle), std::sin(angle)};
    }
    V2 rotate(const V2& v) const { return {c * v.x() - s * v.y(), s * v.x() + c * v.y()}; }
    V2 inverse_rotate(const V2& v) const { return {c * v.x() + s * v.y(), -s * v.x() + c * v.y()}; }
    V2 apply(const V2& v) const { return p + rotate(v); }
    V2 inverse_apply(const V2& v) const { return inverse_rotate(v - p); }
};

struct ManifoldPoint {
    V2 point = V2::Zero();       // world, midway between the two surfaces
    double separation = 0;       // metres along the normal; negative when overlapping
    std::uint16_t id = 0;        // which features: stable while they keep touching
};

struct Manifold {
    V2 normal = V2::UnitY();     // world, unit, pointing from A to B
    std::array<ManifoldPoint, 2> points{};
    int count = 0;               // 0: farther apart than the speculative distance
};

// Points farther apart than `speculative` (metres) are left out; closer ones are kept even
// when not yet touching, so that the solver can stop bodies that would touch within the step.
Manifold collide(const Polygon& a, const Transform& xa, const Polygon& b, const Transform& xb,
                 double speculative);

}  // namespace discreel::physics::detail

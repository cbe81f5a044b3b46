#pragma once
// The body both solvers step. The disc solver's array holds the discs, then one fixed body per
// wall feature; the manifold solver's the bodies, then the walls as fixed bodies: either way
// every contact is a pair of body indices.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {

using V2 = Eigen::Vector2d;

inline double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline V2 perp(const V2& a) { return V2(-a.y(), a.x()); }
// The point of segment [a, b] nearest to x.
inline V2 closest_on_segment(const V2& x, const V2& a, const V2& b) {
    const V2 ab = b - a;
    const double length2 = ab.squaredNorm();
    if (length2 <= 0) return a;
    const double s = std::clamp((x - a).dot(ab) / length2, 0.0, 1.0);
    return a + s * ab;
}

inline V2 to_v2(const Vec2& p) { return V2(p.x, p.y); }

// (cos, sin) of an angle `turn` radians, turned on by `by` radians with the angle-sum rule:
// positions are corrected by little, and below a hundredth of a radian the series (to the
// sixth power) is exact to rounding and needs no libm call.
inline std::pair<double, double> turned_on(const std::pair<double, double>& turn, double by) {
    double c = 0, s = 0;
    if (std::abs(by) < 0.01) {
        const double by2 = by * by;
        c = 1 - by2 / 2 + by2 * by2 / 24;
        s = by * (1 - by2 / 6 + by2 * by2 / 120);
    } else {
        c = std::cos(by);
        s = std::sin(by);
    }
    const auto [c0, s0] = turn;
    return {c0 * c - s0 * s, s0 * c + c0 * s};
}

enum class Motion : std::uint8_t {
    dynamic,  // moved by gravity and contacts
    fixed,    // pegs and walls: never moves, infinitely heavy
    held,     // grabbed: follows a scripted path, infinitely heavy to the others
};

// A body of either solver, whatever its shape: the disc solver's discs and wall features, the
// manifold solver's bodies and fixed walls (its shapes are kept beside the bodies, in the same
// order: a body's motion is read far more often than its outline).
struct Body {
    V2 x = V2::Zero();             // metres; the centroid
    V2 v = V2::Zero();             // m/s
    double angle = 0.0;            // radians
    double omega = 0.0;            // rad/s
    // Metres: a disc's radius, or the farthest point of a shape from its centroid; 0 for the
    // disc solver's wall features (contact offset is then zero).
    double radius = 0.0;
    double mass = 0.0;             // kg (kept while held, for the release)
    double inertia = 0.0;          // kg m^2 about the centroid
    double inv_mass = 0.0;         // 1/kg; 0 when fixed or held
    double inv_inertia = 0.0;      // 1/(kg m^2)
    double restitution = 0.0;
    double friction = 0.0;
    Motion motion = Motion::fixed;
    // The manifold solver's sleeping (body_sleep.cpp): an asleep body is left out of the step,
    // at rest, until an awake body reaches it or a throw moves it. (Each field of the struct
    // is placed where it costs the disc solver no bytes: a pile's steps read every body.)
    bool asleep = false;

    // The disc solver's substep scratch. The impulsive stage applies an impulse at a time tau
    // inside the substep; the body then covers (v_new - v_old) * tau less ground than a
    // start-of-substep impulse would give it, which `shift` and `turn` record so that
    // integration stays exact.
    V2 v_begin = V2::Zero();       // velocity after the impulsive stage, before gravity
    double omega_begin = 0.0;
    V2 shift = V2::Zero();         // metres
    double turn = 0.0;             // radians
    double t_last = 0.0;           // seconds into the substep of its latest impulse
    std::uint32_t strikes = 0;     // impacts applied to it in this substep

    // The manifold solver's: while asleep, the island it fell asleep with (a body index).
    std::uint32_t island = 0;

    bool moves() const { return motion != Motion::fixed; }
    // Held as a grab or a kinematic body holds it: infinitely heavy to the others, turned and
    // moved only as told.
    void hold() {
        motion = Motion::held;
        inv_mass = 0.0;
        inv_inertia = 0.0;
        omega = 0.0;
    }
    bool falls() const { return motion == Motion::dynamic; }
};

// Adds the kinetic and potential energy (-m g.x, zero at the origin) of the bodies that move
// to `stats`, J.
void add_energy(std::span<const Body> bodies, const V2& gravity, WorldStats& stats);
// A body's state as World::bodies() gives it.
inline BodyState state_of(const Body& b) {
    return BodyState{{b.x.x(), b.x.y()}, {b.v.x(), b.v.y()}, b.angle, b.omega};
}

// The body a definition describes, for either solver (one factory): static bodies fixed, the
// others dynamic, with the mass and moment of inertia of their shape.
Body make_body(const BodyDef& def);

}  // namespace discreel::physics::detail
